// Scenes and maps a careless user gives, whose cost or whose parameters the estimates and the
// report can get wrong: every stage asked for is in the memory estimate, before anything is
// laid out; the time estimate counts the cores there are; a parameter undefined for a map is
// said to be, not printed as a number.
#include <catch2/catch.hpp>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "io/x3p.hpp"
#include "support/run_command.hpp"

namespace fs = std::filesystem;

namespace {
const std::string kQuick = "configs/examples/quick.toml";
}  // namespace

TEST_CASE("a step-over too fine for memory is refused before any pass is laid out",
          "[hostile][resources]") {
  // 1e-7 mm (8.6 M passes) would end in bad_alloc at 2 GB; 2.1e-8 mm would spend 18-26 s and
  // 2.1 GB laying out passes before a refusal after the layout, `check` included.
  for (const std::string set : {"--set cutting.stepover=1e-7",
                                "--set cutting.stepover=2.1e-8 --set path.plugin=raster_across "
                                "--set region.size=[0.1,0.1]"}) {
    INFO(set);
    const auto started = std::chrono::steady_clock::now();
    const auto r = testing::run_topomill("check configs/paper/lambda30.toml -q " + set,
                                         "TOPOMILL_MEMORY_LIMIT=2G");
    const double took =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.err, Catch::Contains("key 'cutting.stepover': the patch would need about"));
    CHECK_THAT(r.err, Catch::Contains("whose layout alone needs"));
    CHECK(took < 2.0);
  }
}

TEST_CASE("the memory estimate includes the parameters asked for", "[hostile][resources]") {
  // analysis.parameters = ["all"] peaks at 440 MiB where the estimate without the
  // autocorrelation's fields says 200 MiB fits.
  const std::string fine = "check " + kQuick + " -q --set region.spacing=0.0005";
  const std::string limit = "TOPOMILL_MEMORY_LIMIT=60M";
  CHECK(testing::run_topomill(fine, limit).exit_code == 0);
  const auto r = testing::run_topomill(fine + " --set 'analysis.parameters=[\"all\"]'", limit);
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Catch::Contains("analysis.parameters:"));
  CHECK_THAT(r.err, Catch::Contains("or choose fewer analysis.parameters"));
}

TEST_CASE("the long-run warning counts the cores, not the threads asked for",
          "[hostile][resources]") {
  // With --threads 256 on 2 cores an estimate divided by 256 hides the warning of a run of
  // hours. A 0.86 mm patch at 12 nm: 5e9 nodes, hours on any machine.
  const std::string huge = "check configs/paper/lambda30.toml -q --set region.spacing=0.000012";
  const std::string limit = "TOPOMILL_MEMORY_LIMIT=100000G";  // the memory check passes
  const auto one = testing::run_topomill(huge + " --threads 1", limit);
  const auto many = testing::run_topomill(huge + " --threads 256", limit);
  INFO(one.err << many.err);
  CHECK(one.exit_code == 0);
  CHECK(many.exit_code == 0);
  CHECK_THAT(one.err, Catch::Contains("estimates this run at about"));
  CHECK_THAT(many.err, Catch::Contains("estimates this run at about"));
  CHECK(many.err.find("on 256 thread(s)") == std::string::npos);
}

TEST_CASE("the long-run warning counts the stages after the evaluation", "[hostile][resources]") {
  // 9 M nodes: evaluated in about 14 s on one thread, but an x3p of each map takes a minute more
  // to write (6.4 us a node) and the default parameters, form removal and csv seconds.
  const std::string fine = "check " + kQuick + " -q --set region.spacing=0.0001";
  const auto x3p = testing::run_topomill(fine + " --set 'output.formats=[\"x3p\"]'");
  const auto csv = testing::run_topomill(fine + " --set 'output.formats=[\"csv\"]'");
  INFO(x3p.err << csv.err);
  CHECK(x3p.exit_code == 0);
  CHECK_THAT(x3p.err, Catch::Contains("estimates this run at about"));
  CHECK_THAT(x3p.err, Catch::Contains("driven by region.spacing (the grid's form removal"));
  CHECK(csv.err.find("estimates this run") == std::string::npos);
}

TEST_CASE("parameters undefined for a map are said to be, with why", "[hostile][metrology]") {
  // Not 0 for Sdq and Sdr without valid neighbours, nor 1 for Ssk and Sku on a level map, nor
  // Sq 0 below Sa on denormal heights.
  const std::string dir = testing::temp_dir("undefined_parameters");
  fs::create_directories(dir);
  topomill::Grid g;
  g.nx = g.ny = 8;
  g.dx = g.dy = 0.01;
  topomill::HeightMap level(g), tiny(g), checker(g);
  std::vector<std::uint8_t> alternate(g.size());
  for (std::size_t j = 0; j < g.ny; ++j)
    for (std::size_t i = 0; i < g.nx; ++i) {
      level.at(i, j) = 0.1;                                  // a level map far from zero
      tiny.at(i, j) = ((i * 7 + j * 3) % 5) * 1e-312;        // denormal heights
      checker.at(i, j) = 1e-3 * static_cast<double>(i + j);  // a slope
      alternate[g.index(i, j)] = (i + j) % 2;                // no two valid neighbours
    }
  topomill::write_x3p(dir + "/level.x3p", level);
  topomill::write_x3p(dir + "/tiny.x3p", tiny);
  topomill::write_x3p(dir + "/checker.x3p", checker, {}, alternate);
  auto measure = [&](const std::string& file) {
    const auto r = testing::run_topomill("measure " + dir + "/" + file + " --json");
    INFO(file << ": " << r.err);
    REQUIRE(r.exit_code == 0);
    return nlohmann::json::parse(r.out)["roughness"];
  };
  const auto level_r = measure("level.x3p");
  for (const char* n : {"Ssk", "Sku"}) CHECK(level_r[n].contains("undefined"));
  const auto tiny_r = measure("tiny.x3p");
  CHECK(tiny_r["Sq"]["value"].get<double>() >= tiny_r["Sa"]["value"].get<double>());
  CHECK(tiny_r["Sq"]["value"].get<double>() > 0);
  const auto checker_r = measure("checker.x3p");
  for (const char* n : {"Sdq", "Sdr", "Sdr_gwyddion"}) CHECK(checker_r[n].contains("undefined"));
  CHECK(checker_r["Sa"].contains("value"));
}

TEST_CASE("a ringed cutter's corner at a concave arc's bottom is refused by tooth_passage",
          "[hostile][cutter]") {
  // A bull-nose (c 8 mm) wider than the valley's bottom rests on both walls there: its centre's
  // path turns a corner at the bottom, y = 0 by symmetry, which the centre tables cannot follow.
  // Once an internal error (exit 1); now the evaluator's table and key, the place, the way out.
  const std::string dir = testing::temp_dir("concave_corner");
  fs::create_directories(dir);
  const std::string scene = dir + "/scene.toml";
  std::ofstream(scene) << "[tool]\nplugin = \"bull_nose\"\ndiameter = 20.0\ncorner_radius = 2.0\n"
                          "[workpiece]\nplugin = \"concave_arc\"\nradius = 25.0\n"
                          "[cutting]\nspindle_speed = 4000\nfeed_per_tooth = 0.1\n"
                          "depth_of_cut = 0.1\nstepover = 0.5\n"
                          "[region]\ncentre = [0.0, 5.0]\nsize = [0.1, 0.1]\nspacing = 0.01\n"
                          "[evaluator]\nplugin = \"tooth_passage\"\n";
  const std::string out = dir + "/out";
  const auto r = testing::run_topomill("run '" + scene + "' -q --out '" + out + "'");
  INFO(r.err);
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Catch::Contains(scene + ":17:1: error: key 'evaluator.plugin': tooth_passage "
                                            "follows smooth centre paths only"));
  CHECK_THAT(r.err, Catch::Contains("expected evaluator.plugin = \"zmap\""));
  const std::string at = "turns a corner near y = ";
  const auto k = r.err.find(at);
  REQUIRE(k != std::string::npos);
  CHECK(std::abs(std::stod(r.err.substr(k + at.size()))) < 1e-3);
  CHECK_FALSE(fs::exists(out + "/summary.json"));
}
