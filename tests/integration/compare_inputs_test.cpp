// compare's inputs as users give them: a measurement with scattered missing points keeps its
// points and its parameters; a run's directory counts only once sealed; heights too large to
// difference are refused by name, never printed as -nan.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>

#include "compare.hpp"
#include "io/x3p.hpp"
#include "metrology/resample.hpp"
#include "support/run_command.hpp"
#include "support/scenes.hpp"

using namespace topomill;
namespace fs = std::filesystem;

namespace {
using testing::paper_surface;

// `s` with `share` of its points marked missing, at random (a fixed seed).
Surface with_dropouts(Surface s, double share, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  s.valid.assign(s.map.z.size(), 1);
  for (auto& v : s.valid) v = u(rng) < share ? 0 : 1;
  s.source = "with dropouts";
  return s;
}

CompareSettings settings() {
  CompareSettings c;
  c.names = select_parameters({"default"});
  return c;
}

double value(const ParameterValues& v, const std::string& name) {
  for (const auto& r : v.reported)
    if (r.name == name) return r.value;
  return NAN;
}
}  // namespace

TEST_CASE("compare keeps a measurement's points around its scattered dropouts", "[compare]") {
  // Counting a point only where all 16 of its cubic's nodes are valid leaves 15.7 % overlap with
  // 10 % of the points missing (Sa 13 % off), and with 30 % calls a copy of the same surface
  // "maps of different places".
  const Surface sim = paper_surface(0.4, 0.004);
  for (const double share : {0.1, 0.3}) {
    INFO(share * 100 << " % missing");
    const Surface meas = with_dropouts(sim, share, 7);
    const Comparison c = compare_surfaces(sim, meas, settings());
    CHECK(std::abs(c.registration.tx) < 1e-6);
    CHECK(std::abs(c.registration.ty) < 1e-6);
    // A point between nodes needs its cell's four corners: the overlap is at least the share of
    // whole cells (at the nodes themselves, their own share).
    CHECK(c.overlap_share > std::pow(1 - share, 4) - 0.03);
    CHECK(value(c.meas_parameters, "Sa") == Approx(value(c.sim_parameters, "Sa")).epsilon(1e-3));
  }
}

TEST_CASE("between nodes a dropout costs the cells that touch it, exactly interpolated",
          "[compare]") {
  // A plane, which Keys' cubic, its end condition and the line through two nodes all reproduce
  // exactly: with dropouts the completed neighbours keep it exact, and a point is lost only
  // where its cell has a missing corner.
  Grid g;
  g.nx = g.ny = 41;
  g.dx = g.dy = 0.01;
  Surface s;
  s.map = HeightMap(g);
  auto f = [](double x, double y) { return 1e-3 * (0.3 * x - 0.2 * y + 0.5); };
  for (std::size_t j = 0; j < g.ny; ++j)
    for (std::size_t i = 0; i < g.nx; ++i) s.map.at(i, j) = f(g.x(i), g.y(j));
  const Surface holed = with_dropouts(s, 0.1, 3);
  const CubicSampler sample(holed);
  std::size_t given = 0, cells_whole = 0;
  for (double y = 0.0025; y < 0.4; y += 0.01)
    for (double x = 0.0035; x < 0.4; x += 0.01) {
      const auto i = static_cast<std::size_t>(x / g.dx), j = static_cast<std::size_t>(y / g.dy);
      const bool whole = holed.is_valid(g.index(i, j)) && holed.is_valid(g.index(i + 1, j)) &&
                         holed.is_valid(g.index(i, j + 1)) && holed.is_valid(g.index(i + 1, j + 1));
      const auto z = sample.at(x, y);
      CHECK(z.has_value() == whole);
      cells_whole += whole;
      if (!z) continue;
      ++given;
      CHECK(*z == Approx(f(x, y)).margin(1e-15));
    }
  CHECK(given == cells_whole);
  CHECK(given > 1000);  // about 0.9^4 of 1600
}

TEST_CASE("compare takes a run's directory only once its run is sealed", "[compare][cli]") {
  // A directory without summary.json (a run stopped, failed or still writing) holds no finished
  // run to compare.
  const std::string dir = testing::temp_dir("compare_unsealed");
  fs::create_directories(dir);
  const Surface sim = paper_surface(0.2, 0.005);
  write_x3p(dir + "/height_residual.x3p", sim.map);
  const auto r = testing::run_topomill("compare " + dir + " " + dir +
                                       "/height_residual.x3p --out " + dir + "/report");
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Catch::Contains("holds no summary.json"));
  CHECK_FALSE(fs::exists(dir + "/report"));
}

TEST_CASE("compare gives huge heights finite numbers, or refuses them naming the file",
          "[compare][cli]") {
  // Heights of 1e100 um overflow Sku's fourth powers unless scaled (-nan was printed).
  const std::string dir = testing::temp_dir("compare_huge");
  fs::create_directories(dir);
  const Surface sim = paper_surface(0.2, 0.005);
  for (const double scale : {1e100, 1e300}) {
    INFO("heights times " << scale);
    Surface huge = sim;
    for (double& z : huge.map.z) z *= scale;
    write_x3p(dir + "/huge.x3p", huge.map);
    fs::remove_all(dir + "/report");
    const auto r = testing::run_topomill("compare " + dir + "/huge.x3p " + dir +
                                         "/huge.x3p --out " + dir + "/report");
    INFO(r.out << r.err);
    CHECK((r.exit_code == 0 || r.exit_code == 2));
    CHECK(r.out.find("nan") == std::string::npos);
    CHECK(r.err.find("nan") == std::string::npos);
    CHECK(r.out.find("inf") == std::string::npos);
    CHECK(r.exit_code == (scale > 1e200 ? 2 : 0));
    if (r.exit_code == 2) CHECK_THAT(r.err, Catch::Contains("huge.x3p: error: heights reach"));
    CHECK(fs::exists(dir + "/report") == (r.exit_code == 0));
  }
}
