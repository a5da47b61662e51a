// The cutters other than the ball end, through the whole pipeline, against closed forms derived
// in docs/cutters.md: the bull-nose's cross-feed scallop, the ball end it becomes at r = D/2, the
// tilted flat end's feed marks, and per-edge runout removing an edge's marks.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <sstream>
#include <string>

#include "support/scenes.hpp"

using testing::run_scene;

namespace {
// A single pass, or passes a step-over apart, along Y over a flat plate; the Z-map by default.
std::string plate_scene(const std::string& tool, double fz, double ap, double ae, double size_x,
                        double size_y, double spacing) {
  std::ostringstream s;
  s.precision(17);
  s << "[tool]\n"
    << tool << "\n[workpiece]\nplugin = 'inclined_plane'\nangle = 0.0\n"
    << "[cutting]\nspindle_speed = 4000\nfeed_per_tooth = " << fz << "\ndepth_of_cut = " << ap
    << "\nstepover = " << ae << "\n[region]\ncentre = [0.0, 0.0]\nsize = [" << size_x << ", "
    << size_y << "]\nspacing = " << spacing << "\n[evaluator]\nplugin = 'zmap'\n";
  return s.str();
}

// Across the passes, the highest of each line's lowest height along the feed: the cusp (um).
double cusp_um(const topomill::HeightMap& m) {
  const auto& g = m.grid;
  double cusp = -INFINITY, floor = INFINITY;
  for (std::size_t i = 0; i < g.nx; ++i) {
    double low = INFINITY;
    for (std::size_t j = 0; j < g.ny; ++j) low = std::min(low, m.at(i, j));
    cusp = std::max(cusp, low), floor = std::min(floor, low);
  }
  return (cusp - floor) * 1e3;
}

// Along the pass line x = 0 (the grid's middle column), highest less lowest height (um): the
// feed marks' depth.
double marks_um(const topomill::HeightMap& m) {
  const auto& g = m.grid;
  const std::size_t i = g.nx / 2;
  REQUIRE(std::abs(g.x0 + static_cast<double>(i) * g.dx) < 1e-12);
  double lo = INFINITY, hi = -INFINITY;
  for (std::size_t j = 0; j < g.ny; ++j)
    lo = std::min(lo, m.at(i, j)), hi = std::max(hi, m.at(i, j));
  return (hi - lo) * 1e3;
}

double circle_rise(double r, double d) {
  return r - std::sqrt(r * r - d * d);
}
}  // namespace

TEST_CASE("a bull-nose leaves the cusp of its corner where the bottoms' strips part",
          "[closed-form][cutter]") {
  // A vertical torus over a plate: the lowest point at distance d from its axis is its section's,
  // flat (-r) out to the ring c and r - sqrt(r^2 - (d - c)^2) above it beyond. Passes ae apart
  // meet at ae / 2: the cusp is r - sqrt(r^2 - (ae / 2 - c)^2) when ae > 2c, none when less.
  const std::string tool =
      "plugin = 'bull_nose'\ndiameter = 4.0\ncorner_radius = 1.0\nhelix_angle = 30.0";
  // The Z-map within 2 % (its nearest node); tooth_passage, exact at the nodes, within 1e-5 (1.3
  // nm): what the rows leave, 0.45 nm here (of the cusp line's nodes 0.01 mm apart, the best
  // has its lowest passage a few micrometres along the feed from the axis's closest approach),
  // and never below the closed form, which is the lowest any passage reaches there.
  using Run = std::pair<std::string, double>;
  const Run run = GENERATE(Run{"zmap", 0.02}, Run{"tooth_passage", 1e-5});
  const std::string& evaluator = run.first;
  const double tolerance = run.second;
  const std::vector<std::string> set{"evaluator.plugin=" + evaluator};
  INFO(evaluator);
  SECTION("ae 3 mm: the corners meet") {
    const auto r = run_scene(plate_scene(tool, 0.1, 0.3, 3.0, 3.0, 0.2, 0.01), set);
    CHECK(cusp_um(r.raw) == Approx(1e3 * circle_rise(1.0, 0.5)).epsilon(tolerance));  // 133.97 um
    CHECK(cusp_um(r.raw) >= 1e3 * circle_rise(1.0, 0.5) - 1e-6);
  }
  SECTION("ae 1.5 mm: the bottoms overlap, and the plate is flat") {
    const auto r = run_scene(plate_scene(tool, 0.1, 0.3, 1.5, 1.5, 0.2, 0.01), set);
    CHECK(cusp_um(r.raw) == Approx(0).margin(1e-9));
  }
}

TEST_CASE("a bull-nose with r = D/2 cuts the ball end's surface, to the bit", "[cutter]") {
  const std::string ball = "plugin = 'ball_end_constant_lead'\nradius = 2.0\nhelix_angle = 30.0";
  const std::string bull =
      "plugin = 'bull_nose'\ndiameter = 4.0\ncorner_radius = 2.0\nhelix_angle = 30.0";
  for (const std::string evaluator : {"zmap", "tooth_passage"}) {
    INFO(evaluator);
    const std::vector<std::string> set{"evaluator.plugin=" + evaluator};
    const auto a = run_scene(plate_scene(ball, 0.1, 0.1, 0.3, 0.3, 0.3, 0.01), set);
    const auto b = run_scene(plate_scene(bull, 0.1, 0.1, 0.3, 0.3, 0.3, 0.01), set);
    REQUIRE(a.raw.z.size() == b.raw.z.size());
    CHECK(a.raw.z == b.raw.z);
  }
}

TEST_CASE("a flat end with a lead leaves feed marks fz tan(lead) high", "[closed-form][cutter]") {
  // The bottom tilted by beta along the feed: on the pass line only its lowest rim point cuts,
  // and each tooth's radial end edge, pointing along the feed there, leaves the bottom's slope
  // tan(beta) behind it. Consecutive teeth are fz apart: a sawtooth fz tan(beta) high.
  const std::string tool = "plugin = 'flat_end'\ndiameter = 1.0\nteeth = 2\nhelix_angle = 30.0";
  for (const double lead : {2.0, -3.0}) {
    INFO("lead " << lead);
    const auto r = run_scene(plate_scene(tool, 0.1, 0.05, 10.0, 0.02, 0.3, 0.002),
                             {"path.lead=" + std::to_string(lead)});
    CHECK(marks_um(r.raw) == Approx(1e2 * std::tan(std::abs(lead) * M_PI / 180)).epsilon(0.04));
    // Tilted, the ring sits c sin(beta) higher, so that the rim's lowest point cuts ap deep.
    double low = INFINITY;
    for (double z : r.raw.z) low = std::min(low, z);
    CHECK(low == Approx(-0.05).margin(1e-9));
  }
}

TEST_CASE("an edge set higher than the marks' cusp leaves no mark: the period doubles",
          "[closed-form][cutter][runout]") {
  // Two helix-free teeth fz apart on a ball end R over a plate, leaning beta along the feed (a
  // vertical ball's tip would sweep the pass line, leaving no marks there): each passage leaves
  // on the pass line the meridian circle through the ball's lowest point, rising
  // R - sqrt(R^2 - d^2) at d from it. Edge 1, eps_a higher along the axis, has its circle
  // eps_a cos(beta) higher and eps_a sin(beta) along the feed; it cuts only where it dips below
  // edge 0's, whose marks are 2 fz apart. Above the threshold eps_a cos(beta) = R - sqrt(R^2 -
  // fz^2) (near enough: the shift moves it by a nanometre) it never does, and the marks are edge
  // 0's alone, R - sqrt(R^2 - fz^2) high; below it the highest point is where the circles cross
  // (found here by brute force over the span of two marks).
  const double R = 2, fz = 0.1, beta = 10 * M_PI / 180;
  const std::string tool = "plugin = 'ball_end_constant_lead'\nradius = 2.0\nhelix_angle = 0.0";
  auto expected_um = [&](double eps) {
    double top = 0;
    constexpr int kSamples = 200000;
    const double at = fz + eps * std::sin(beta), up = eps * std::cos(beta);
    for (int k = 0; k <= kSamples; ++k) {
      const double y = 2 * fz * k / kSamples;  // from a mark of edge 0 to the next
      const double edge0 = std::min(circle_rise(R, y), circle_rise(R, 2 * fz - y));
      top = std::max(top, std::min(edge0, up + circle_rise(R, std::abs(y - at))));
    }
    return top * 1e3;
  };
  CHECK(expected_um(0) == Approx(1e3 * circle_rise(R, fz / 2)).epsilon(1e-6));
  CHECK(expected_um(0.004) == Approx(1e3 * circle_rise(R, fz)).epsilon(1e-6));
  for (const double eps : {0.0, 0.001, 0.004}) {
    INFO("eps_a " << eps);
    std::ostringstream runout;
    runout << "[runout]\nedge_axial_step = " << eps << "\n";
    const auto r = run_scene(plate_scene(tool, fz, 0.05, 10.0, 0.004, 0.3, 0.002) + runout.str(),
                             {"path.lead=10"});
    // The Z-map's nearest node: the marks' slope, at most fz / R, times half a cell.
    CHECK(marks_um(r.raw) == Approx(expected_um(eps)).margin(0.06));
    // Edge 1 is the higher: edge 0's valleys stay at the depth of cut, none deeper.
    double low = INFINITY;
    for (double z : r.raw.z) low = std::min(low, z);
    CHECK(low == Approx(-0.05).margin(1e-6));
  }
}

TEST_CASE("an edge stepped outwards widens the strip a face mill cuts",
          "[closed-form][cutter][runout]") {
  // Round inserts ri on the circle c = D/2, one pass over a plate: the insert's circle meets the
  // uncut surface sqrt(2 ri ap - ap^2) beyond the ring, so the strip cut is that plus c either
  // side of the pass, and insert 1, eps_r farther out, widens it by eps_r; inwards, insert 0's.
  const std::string tool = "plugin = 'round_insert'\ndiameter = 2.0\ninsert_radius = 1.0";
  const double ap = 0.1, edge = 1 + std::sqrt(2 * ap - ap * ap), h = 0.005;
  for (const double eps : {0.02, -0.02}) {
    INFO("eps_r " << eps);
    std::ostringstream runout;
    runout << "[runout]\nedge_radial_step = " << eps << "\n";
    const auto r = run_scene(plate_scene(tool, 0.1, ap, 50.0, 0.2, 0.1, h) + runout.str(),
                             {"region.centre=[1.45, 0.0]"});
    double outermost = -INFINITY;  // the cut node farthest from the pass
    const auto& g = r.raw.grid;
    for (std::size_t i = 0; i < g.nx; ++i)
      for (std::size_t j = 0; j < g.ny; ++j)
        if (r.raw.at(i, j) < -1e-9)
          outermost = std::max(outermost, g.x0 + static_cast<double>(i) * g.dx);
    CHECK(outermost == Approx(edge + std::max(eps, 0.0)).margin(h));
  }
}
