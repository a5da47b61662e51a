// topomill lobes from the command line: the benchmark scenes' JSON, and every refusal (exit 2,
// naming the option or the scene's table).
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "support/run_command.hpp"

namespace {

const char* kFullImmersion = "configs/validation/lobes/insperger_1dof_aD1.toml";

}  // namespace

TEST_CASE("lobes: the benchmark's JSON, its envelope above the zero-order minimum", "[lobes]") {
  const auto r = testing::run_topomill(std::string("lobes ") + kFullImmersion +
                                       " --spindle 5000:25000:9 --json -q");
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  const auto j = nlohmann::json::parse(r.out);
  REQUIRE(j["spindle_rpm"].size() == 9);
  REQUIRE(j["depth_mm"].size() == 9);
  CHECK(j["spindle_rpm"][0].get<double>() == 5000);
  CHECK(j["spindle_rpm"][4].get<double>() == 15000);
  CHECK(j["spindle_rpm"][8].get<double>() == 25000);
  // Altintas and Budak's zero-order minimum for one mode along the feed at full immersion:
  // 2 k zeta (1 + zeta) / (N Kn / 4) (k = m wn^2 = 1340050 N/m, zeta 0.011, N 2, Kn 2e8 N/m^2):
  // 0.298 mm. The time-varying force makes the semi-discretised boundary a little higher: none of
  // the nine speeds lies below it, and at the lobes' feet (10000 and 15000 rpm) it lies within
  // 10 % above it.
  const double zoa = 2 * 1340049.6 * 0.011 * 1.011 / (2 * 2e8 / 4) * 1e3;
  double least = INFINITY;
  for (const auto& d : j["depth_mm"]) {
    REQUIRE(d.is_number());
    CHECK(d.get<double>() >= zoa);
    least = std::min(least, d.get<double>());
  }
  CHECK(least < 1.1 * zoa);
  for (const auto& o : j["onset"]) CHECK((o == "hopf" || o == "flip"));
  CHECK(j["operating_point"]["spindle_rpm"].get<double>() == 10000);
  CHECK(j["operating_point"]["stable"].get<bool>());
}

TEST_CASE("lobes draws its picture where asked", "[lobes]") {
  const std::string dir = testing::temp_dir("lobes");
  std::filesystem::create_directories(dir);
  const std::string png = dir + "/lobes.png";
  const auto r = testing::run_topomill(std::string("lobes ") + kFullImmersion +
                                       " --spindle 5000:25000:5 -q --png '" + png + "'");
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  CHECK(testing::read_file(png).substr(1, 3) == "PNG");
}

TEST_CASE("lobes refuses bad options and scenes without modes", "[lobes][errors]") {
  const std::string scene = kFullImmersion;
  struct Case {
    std::string args, expect;
  };
  for (const Case& c : {
           Case{"", "key '--spindle': missing: expected FROM:TO[:N]"},
           Case{"--spindle 25000:5000", "key '--spindle': '25000:5000': expected FROM:TO[:N]"},
           Case{"--spindle 5000:x", "key '--spindle': '5000:x': expected FROM:TO[:N]"},
           Case{"--spindle 5000:9000:1", "key '--spindle': '5000:9000:1': expected FROM:TO[:N]"},
           Case{"--spindle 5000:9000:2.5", "key '--spindle'"},
           Case{"--spindle 1:2", "key '--spindle': '1:2': expected FROM of at least 414.9"},
           Case{"--spindle 5000:9000 --steps 3", "key '--steps': expected 0 (automatic) or 4"},
           Case{"--spindle 5000:9000 --depth-max -1", "key '--depth-max': expected a positive"},
           Case{"--spindle 5000:9000 --depth-max 1e300", "key '--depth-max': expected a positive"},
           Case{"--spindle 5000:9000 --depth-max nan", "key '--depth-max'"},
           Case{"--spindle 5000:9000 --png /nonexistent/lobes.png",
                "key '--png': '/nonexistent/lobes.png': expected a file in an existing directory"},
           Case{"--spindle 5000:9000 --set vibration.enabled=false",
                scene + ":44:1: error: key 'vibration': lobes needs the structure's modes"},
       }) {
    const auto r = testing::run_topomill("lobes " + scene + " " + c.args + " -q");
    INFO(c.args << "\n" << r.err);
    CHECK(r.exit_code == 2);
    CHECK(r.err.find(c.expect) != std::string::npos);
    CHECK(r.out.empty());
  }
}
