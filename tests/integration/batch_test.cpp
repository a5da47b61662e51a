// topomill sweep and ablate as a user runs them: the table holds what separate runs give, a
// failing case is reported and the others go on, a rerun resumes, bad requests are refused.
#include <signal.h>
#include <sys/wait.h>

#include <catch2/catch.hpp>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <thread>

#include "support/csv_table.hpp"
#include "support/run_command.hpp"

namespace fs = std::filesystem;

using testing::column;
using testing::read_csv_rows;

namespace {

// Sa (um) of a single `topomill run` of the stability base scene with `set`.
double single_run_sa(const std::vector<std::string>& set) {
  std::string args = "run tests/stability/base.toml -q --out '" + testing::temp_dir("single") + "'";
  for (const auto& s : set) args += " --set '" + s + "'";
  const auto r = testing::run_topomill(args);
  REQUIRE(r.exit_code == 0);
  std::smatch m;
  REQUIRE(std::regex_search(r.out, m, std::regex(R"(Sa ([0-9.eE+-]+) um)")));
  return std::stod(m[1]);
}

bool is_png(const std::string& path) {
  return testing::read_file(path).substr(1, 3) == "PNG";
}

}  // namespace

TEST_CASE("sweep: cross product in one table, failures reported, reruns resume", "[batch]") {
  const std::string out = testing::temp_dir("sweep");
  const std::string args =
      "sweep tests/stability/base.toml --vary region.lambda=15,30,89.9 "
      "--vary cutting.feed_per_tooth=0.05,0.1 --jobs 2 --out '" +
      out + "'";
  const auto r = testing::run_topomill(args);
  INFO(r.err);
  CHECK(r.exit_code == 3);  // lambda 89.9 runs past the arc's end: those cases fail
  const auto rows = read_csv_rows(out + "/sweep.csv");
  REQUIRE(rows.size() == 7);
  const auto& h = rows.front();
  const std::size_t lam = column(h, "region.lambda"), fz = column(h, "cutting.feed_per_tooth"),
                    status = column(h, "status"), sa = column(h, "Sa_um"),
                    error = column(h, "error");
  int ok = 0;
  for (std::size_t i = 1; i < rows.size(); ++i) {
    const auto& row = rows[i];
    if (row[lam] == "89.9") {
      CHECK(row[status] == "failed (exit 2)");
      CHECK(row[error].find("key 'region.lambda'") != std::string::npos);
      CHECK(row[sa].empty());
      continue;
    }
    ++ok;
    CHECK(row[status] == "ok");
    // The table holds what a separate run of the same variant prints (4 digits).
    const double single =
        single_run_sa({"region.lambda=" + row[lam], "cutting.feed_per_tooth=" + row[fz]});
    CHECK(std::stod(row[sa]) == Approx(single).epsilon(1e-3));
  }
  CHECK(ok == 4);
  CHECK(is_png(out + "/sweep_region.lambda.png"));
  CHECK(is_png(out + "/sweep_cutting.feed_per_tooth.png"));

  // A case whose run was lost (no summary) is run again; the others are not.
  fs::remove(out + "/cases/region.lambda=30__cutting.feed_per_tooth=0.1/summary.json");
  const auto again = testing::run_topomill(args);
  CHECK(again.exit_code == 3);
  std::size_t pos = 0, done_earlier = 0;
  while ((pos = again.err.find("done earlier", pos)) != std::string::npos) ++done_earlier, ++pos;
  CHECK(done_earlier == 3);
  CHECK(again.err.find("region.lambda=30__cutting.feed_per_tooth=0.1: ok") != std::string::npos);
  CHECK(read_csv_rows(out + "/sweep.csv").size() == 7);

  // A case finished by other code (its summary's fingerprint of the program and libraries is
  // not that of the code here: a rebuild changed them) is run again; the rest resume.
  const std::string redone = out + "/cases/region.lambda=15__cutting.feed_per_tooth=0.05";
  std::string summary = testing::read_file(redone + "/summary.json");
  const std::regex fingerprint(R"re("code_fingerprint"\s*:\s*"[0-9a-f]{8}")re");
  REQUIRE(std::regex_search(summary, fingerprint));
  summary = std::regex_replace(summary, fingerprint, "\"code_fingerprint\": \"00000000\"");
  std::ofstream(redone + "/summary.json", std::ios::trunc) << summary;
  const auto third = testing::run_topomill(args);
  CHECK(third.err.find("region.lambda=15__cutting.feed_per_tooth=0.05: ok") != std::string::npos);
  std::size_t resumed = 0;
  for (pos = 0; (pos = third.err.find("done earlier", pos)) != std::string::npos; ++pos) ++resumed;
  CHECK(resumed == 3);
}

TEST_CASE("sweep: a case whose cutter-location file changed is run again", "[batch][cl]") {
  // The scene is unchanged (its time too); the file its path model reads is not. summary.json
  // lists that file with its bytes' checksum, and the resume compares them.
  const fs::path dir = testing::temp_dir("sweep_cl_input");
  fs::create_directories(dir / "cl");
  fs::copy_file("configs/examples/cl_plate_raster.toml", dir / "scene.toml");
  fs::copy_file("configs/examples/cl/plate_raster.csv", dir / "cl" / "plate_raster.csv");
  const std::string args = "sweep '" + (dir / "scene.toml").string() +
                           "' --vary region.spacing=0.02 --out '" + (dir / "out").string() + "'";
  REQUIRE(testing::run_topomill(args).exit_code == 0);
  const auto same = testing::run_topomill(args);
  CHECK(same.err.find("done earlier") != std::string::npos);
  // A comment appended: the same passes, but new bytes (the check is by bytes, not meaning).
  std::string csv = testing::read_file((dir / "cl" / "plate_raster.csv").string());
  csv += "# edited\n";
  std::ofstream(dir / "cl" / "plate_raster.csv", std::ios::trunc) << csv;
  const auto edited = testing::run_topomill(args);
  INFO(edited.err);
  CHECK(edited.exit_code == 0);
  CHECK(edited.err.find("done earlier") == std::string::npos);
  CHECK(edited.err.find(": ok") != std::string::npos);
}

TEST_CASE("sweep: an interrupted sweep stops promptly and a rerun finishes it", "[batch][kill]") {
  const std::string out = testing::temp_dir("sweep_interrupted");
  const std::string log = testing::temp_dir("sweep_interrupted.log");
  const std::vector<std::string> args = {"sweep",  "tests/stability/base.toml",
                                         "--vary", "region.lambda=10,20,30,40",
                                         "--set",  "evaluator.plugin=\"zmap\"",
                                         "--set",  "region.spacing=0.02",
                                         "--out",  out};
  const int pid = testing::spawn_topomill(args, log);
  testing::wait_until_catching(pid, SIGINT);
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  kill(pid, SIGINT);
  const int status = testing::wait_for(pid);
  CHECK(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 130);
  CHECK_FALSE(fs::exists(out + "/sweep.csv"));
  const int rerun = testing::wait_for(testing::spawn_topomill(args, log));
  CHECK(WEXITSTATUS(rerun) == 0);
  CHECK(read_csv_rows(out + "/sweep.csv").size() == 5);
}

TEST_CASE("SIGTERM and SIGHUP to a batch command stop its running cases too", "[batch][kill]") {
  // Issue 18: the cases (process groups of their own) outlived a terminated sweep and kept
  // writing. Each running case holds its directory's lock file, which names its pid.
  for (const int signal : {SIGTERM, SIGHUP}) {
    DYNAMIC_SECTION("signal " << signal) {
      const std::string out = testing::temp_dir("sweep_terminated");
      const std::string log = testing::temp_dir("sweep_terminated.log");
      const int pid = testing::spawn_topomill(  // zmap: cases seconds long, to be stopped
          {"sweep", "configs/paper/lambda30.toml", "--vary", "region.lambda=20,30", "--set",
           "evaluator.plugin=zmap", "--jobs", "2", "--out", out},
          log);
      std::vector<int> cases;
      const auto started = std::chrono::steady_clock::now();
      while (cases.size() < 2 &&
             std::chrono::steady_clock::now() - started < std::chrono::seconds(20)) {
        cases.clear();
        for (const char* id : {"region.lambda=20", "region.lambda=30"}) {
          const std::string holder = testing::read_file(out + "/cases/" + id + "/.lock");
          if (!holder.empty()) cases.push_back(std::stoi(holder));
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
      }
      REQUIRE(cases.size() == 2);
      kill(pid, signal);
      const int status = testing::wait_for(pid);
      INFO(testing::read_file(log));
      CHECK(WIFEXITED(status));
      CHECK(WEXITSTATUS(status) == 128 + signal);
      for (const int c : cases) CHECK(kill(c, 0) != 0);  // gone, not reparented and running
      CHECK_FALSE(fs::exists(out + "/sweep.csv"));
    }
  }
}

TEST_CASE("sweep and ablate refuse bad requests before running anything", "[batch][errors]") {
  const std::string out = testing::temp_dir("refused");
  auto r = testing::run_topomill(
      "sweep tests/stability/base.toml --vary cutting.feed=0.1,0.2 "
      "--out '" +
      out + "'");
  CHECK(r.exit_code == 2);
  CHECK(r.err.find("key '--vary cutting.feed'") != std::string::npos);
  CHECK(r.err.find("feed_per_tooth") != std::string::npos);  // did you mean
  r = testing::run_topomill("sweep tests/stability/base.toml --out '" + out + "'");
  CHECK(r.exit_code == 2);
  r = testing::run_topomill("sweep tests/stability/base.toml --vary region.lambda=10,10 --out '" +
                            out + "'");
  CHECK(r.exit_code == 2);
  CHECK(r.err.find("a value is given twice") != std::string::npos);
  r = testing::run_topomill("ablate tests/stability/base.toml --swap engine=x --out '" + out + "'");
  CHECK(r.exit_code == 2);
  CHECK(r.err.find("'engine' is not a slot; expected one of") != std::string::npos);
  r = testing::run_topomill("ablate tests/stability/base.toml --swap dynamics=modal_exact --out '" +
                            out + "'");
  CHECK(r.exit_code == 2);
  CHECK(r.err.find("the scene does not use [vibration]; enable it") != std::string::npos);
  r = testing::run_topomill(
      "ablate tests/stability/base.toml --set vibration.enabled=true "
      "--swap dynamics=modal_nope --out '" +
      out + "'");
  CHECK(r.exit_code == 2);
  CHECK(r.err.find("modal_exact") != std::string::npos);  // the known models
  CHECK_FALSE(fs::exists(out));
}

TEST_CASE("ablate: each effect off, ideal and a swapped model, against separate runs", "[batch]") {
  const std::string out = testing::temp_dir("ablate");
  const auto r = testing::run_topomill(
      "ablate tests/stability/base.toml --set vibration.enabled=true --set deflection.enabled=true "
      "--swap dynamics=modal_exact --jobs 2 --out '" +
      out + "'");
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  const auto rows = read_csv_rows(out + "/ablation.csv");
  REQUIRE(rows.size() == 6);
  const auto& h = rows.front();
  const std::size_t variant = column(h, "variant"), effects = column(h, "effects"),
                    sa = column(h, "Sa_um"), dsa = column(h, "dSa_percent");
  std::vector<std::string> names;
  for (std::size_t i = 1; i < rows.size(); ++i) names.push_back(rows[i][variant]);
  CHECK(names == std::vector<std::string>{"full", "no vibration", "no deflection", "ideal",
                                          "vibration=modal_exact"});
  CHECK(rows[1][effects] == "vibration+deflection");
  CHECK(rows[2][effects] == "deflection");
  CHECK(rows[4][effects] == "none");
  CHECK(rows[1][dsa] == "0");
  // The ideal row is the scene with every effect off, run on its own.
  CHECK(std::stod(rows[4][sa]) == Approx(single_run_sa({})).epsilon(1e-3));
  // The exact modal solution and RK4 give the same surface to well under a percent.
  CHECK(std::abs(std::stod(rows[5][dsa])) < 1.0);
  CHECK(is_png(out + "/ablation.png"));
  CHECK(is_png(out + "/ablation_maps.png"));
  CHECK(testing::read_file(out + "/ablation.md").find("| no vibration |") != std::string::npos);
}
