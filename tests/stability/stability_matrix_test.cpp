// The stability matrix (issue #9): every extreme of tests/stability/extremes.toml under every
// variant, run as a user would. A case either finishes with finite heights and parameters, or
// stops with exit code 2 and a message naming a key it changed; it never crashes, never exits 1
// and never writes NaN or Inf.
#include <toml++/toml.h>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <regex>

#include "metrology/read_surface.hpp"
#include "support/run_command.hpp"

namespace fs = std::filesystem;

namespace {

struct Case {
  std::string name;
  std::vector<std::string> set;
  std::string expect;  // "finite", "refused" or empty (either)
};

std::vector<std::string> strings(const toml::table& t, const char* key) {
  std::vector<std::string> out;
  if (const auto* a = t[key].as_array())
    for (const auto& v : *a) out.push_back(v.value<std::string>().value());
  return out;
}

std::vector<Case> matrix() {
  const toml::table doc =
      toml::parse_file(testing::source_dir() + "/tests/stability/extremes.toml");
  std::vector<Case> cases;
  for (const auto& e : *doc["extreme"].as_array()) {
    const auto& et = *e.as_table();
    for (const auto& v : *doc["variant"].as_array()) {
      const auto& vt = *v.as_table();
      Case c;
      c.name =
          et["name"].value<std::string>().value() + " | " + vt["name"].value<std::string>().value();
      c.set = strings(vt, "set");
      for (const auto& s : strings(et, "set")) c.set.push_back(s);  // the extreme wins
      const bool effects = vt["effects"].value_or(false);
      c.expect = et[effects ? "expect_effects" : "expect"].value_or(std::string());
      cases.push_back(c);
    }
  }
  return cases;
}

// The table of "table.key=value".
std::string table_of(const std::string& assignment) {
  return assignment.substr(0, assignment.find('.'));
}

bool all_finite(const std::string& csv) {
  const topomill::Surface s = topomill::read_surface(csv, 0);  // the grid from the header
  for (double z : s.map.z)
    if (!std::isfinite(z)) return false;
  return !s.map.z.empty();
}

}  // namespace

TEST_CASE("stability matrix: every extreme finishes finite or is refused naming its key",
          "[stability]") {
  const auto cases = matrix();
  REQUIRE(cases.size() >= 50);
  int index = 0, finished = 0, refused = 0;
  for (const auto& c : cases) {
    const std::string out = testing::temp_dir("stability_" + std::to_string(index++));
    std::string args = "run tests/stability/base.toml -q --threads 2 --out '" + out + "'";
    for (const auto& s : c.set) args += " --set '" + s + "'";
    const auto r = testing::run_topomill(args);
    INFO(c.name << "\ntopomill " << args << "\n" << r.err);
    CHECK_FALSE(r.crashed);
    REQUIRE((r.exit_code == 0 || r.exit_code == 2));
    if (r.exit_code == 0) {
      ++finished;
      CHECK(c.expect != "refused");
      const std::string summary = testing::read_file(out + "/summary.json");
      REQUIRE_FALSE(summary.empty());
      CHECK_FALSE(std::regex_search(
          summary, std::regex(R"((^|[^a-z])(nan|inf)([^a-z]|$))", std::regex::icase)));
      CHECK(all_finite(out + "/height_raw.csv"));
      CHECK(all_finite(out + "/height_residual.csv"));
    } else {
      ++refused;
      CHECK(c.expect != "finite");
      std::smatch m;
      REQUIRE(std::regex_search(r.err, m, std::regex(R"(error: key '([a-z_]+)[.']?)")));
      bool named = false;
      for (const auto& s : c.set) named = named || table_of(s) == m[1].str();
      CHECK(named);
      UNSCOPED_INFO("refused: " << c.name << ": " << r.err.substr(r.err.find("error:")));
      CHECK_FALSE(fs::exists(out + "/summary.json"));
    }
  }
  WARN(cases.size() << " cases: " << finished << " finished, " << refused << " refused");
}
