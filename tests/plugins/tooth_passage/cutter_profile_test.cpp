// tooth_passage's cutter profile, against the tool's own section and lag: the depth over a node
// at the section's distance is the section's height, wherever an edge is, and the lag goes on
// continuously past the reach; the hull is never shallower than the surface and never deepens
// outwards; the lag's slope in ln(rho) is the lag's central difference; the steepness is the
// depth's central difference, and the section no steeper below a depth than steepest_below says;
// and the profile says it describes a tool exactly when the section is the tube's circle, sheared
// by an axial rake or not. An insert with an axial rake folds back on
// itself: past a fold the section is above the surface over the same distance, not on it.
#include <catch2/catch.hpp>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "support/builtin_models.hpp"
#include "tooth_passage/cutter_profile.hpp"

using topomill::ToolGeometry;
using topomill::plugins::CutterProfile;

namespace {
using Values = std::vector<std::pair<std::string, double>>;
struct Tool {
  const char* plugin;
  Values values;
};
std::vector<Tool> tools() {
  return {{"bull_nose", {{"diameter", 6}, {"corner_radius", 1}, {"helix_angle", 40}}},
          {"flat_end", {{"diameter", 4}, {"corner_radius", 0.3}, {"helix_angle", 20}}},
          {"round_insert", {{"diameter", 10}, {"insert_radius", 3}, {"radial_rake", 4}}},
          {"round_insert", {{"diameter", 10}, {"insert_radius", 3}, {"axial_rake", 20}}},
          {"round_insert", {{"diameter", 4}, {"insert_radius", 2.5}, {"axial_rake", -25}}},
          {"ball_end_loxodrome", {{"radius", 2}, {"helix_angle", 30}}}};
}
// A tube whose section is half as deep as it is wide: no circle, sheared or not.
struct Squashed : ToolGeometry {
  double radius() const override { return 1; }
  int teeth() const override { return 2; }
  double ring() const override { return 2; }
  double lag(double) const override { return 0; }
  double lag_slope(double) const override { return 0; }
  topomill::Vec2 section(double a) const override { return {2 + std::sin(a), -0.5 * std::cos(a)}; }
};
}  // namespace

TEST_CASE("the profile's depth is the section's height wherever an edge is", "[tooth_passage]") {
  const Tool t = GENERATE(from_range(tools()));
  const auto tool = testing::make_model<ToolGeometry>(t.plugin, t.values);
  const double out = GENERATE(0.0, 0.05), up = GENERATE(0.0, -0.002);
  const CutterProfile f(*tool, out, up);
  INFO(t.plugin << ", out " << out << ", up " << up);
  CHECK(f.up() == up);
  const double a0 = tool->first_polar_angle();
  for (int k = 1; k < 64; ++k) {
    const double a = a0 + (M_PI / 2 - a0) * k / 64.0;
    const double rho = tool->section(a).x() + out;
    const CutterProfile::Point p = f.at(rho);
    INFO("alpha " << a);
    // On the surface where the section still moves out with alpha (by its own difference); past
    // a fold above it.
    const double da = 1e-7, moving = tool->section(a + da).x() - tool->section(a - da).x();
    if (rho > 0 && moving < 0 && tool->section(a).x() < tool->reach()) REQUIRE(p.on);
    if (rho > 0 && moving > 1e-4 * da) {
      REQUIRE(p.on);
      CHECK(p.depth == Approx(-tool->section(a).y()).margin(1e-12));
      CHECK(p.sin_a == Approx(std::sin(a)).margin(1e-12));
    }
    if (p.on) CHECK(p.depth >= -tool->section(a).y() - 1e-12);
    CHECK(f.hull_depth(rho) >= p.depth - 1e-15);
  }
  // Past the reach nothing; inside the ring the bottom's depth r, or no edge (an insert's hole,
  // a ball's ring moved out).
  CHECK_FALSE(f.at(f.reach() * 1.0001).on);
  // Past the reach the lag holds the tool's own at its rim (alpha = pi / 2), so that the phase
  // goes on continuously there (the walks' turns and bounds read across the rim).
  auto lag_at = [&](double rho) { return f.lag(*tool, rho, f.at(rho)); };
  CHECK(lag_at(f.reach() * 1.5) == Approx(tool->lag(M_PI / 2)).margin(1e-12));
  CHECK(lag_at(f.reach() * (1 - 1e-12)) == Approx(tool->lag(M_PI / 2)).margin(1e-5));
  if (tool->has_bottom()) {
    CHECK(f.at(0.5 * tool->ring()).depth == tool->radius());
    CHECK(f.at(0.5 * tool->ring()).on);
    CHECK(f.at(0.5 * out).on == (out == 0));  // moved out, the edge leaves the axis
  } else if (f.start() > 0) {
    CHECK_FALSE(f.at(0.999 * f.start()).on);
  }
  // The hull never deepens outwards, and is continuous: between samples dr apart it rises by at
  // most the tube's sagitta over dr, sqrt(2 r dr) (the rim's), or dr past the reach.
  const double dr = 1.2 * f.reach() / 4000;
  double last = INFINITY, worst_deepening = 0, worst_step = 0;
  for (int k = 0; k <= 4000; ++k) {
    const double d = f.hull_depth(dr * k);
    if (k > 0)
      worst_deepening = std::max(worst_deepening, d - last),
      worst_step = std::max(worst_step, (last - d) / (std::sqrt(2 * f.tube() * dr) + dr));
    last = d;
  }
  CHECK(worst_deepening <= 1e-15);
  CHECK(worst_step <= 1.0);
}

TEST_CASE("the profile's lag slope and steepness are the central differences", "[tooth_passage]") {
  const Tool t = GENERATE(from_range(tools()));
  const auto tool = testing::make_model<ToolGeometry>(t.plugin, t.values);
  const CutterProfile f(*tool);
  INFO(t.plugin);
  const double h = 1e-6;
  for (int k = 1; k < 40; ++k) {
    // Over the edge away from the tip radius and the rim, where both are smooth.
    const double rho = f.tip() + (f.rim_out(0.9) - f.tip()) * k / 40.0;
    auto lag = [&](double r) { return f.lag(*tool, r, f.at(r)); };
    const double d_lag = (lag(rho * std::exp(h)) - lag(rho * std::exp(-h))) / (2 * h);
    INFO("rho " << rho);
    CHECK(f.slope(*tool, rho, f.at(rho)) == Approx(d_lag).margin(1e-6));
    const double d_depth = (f.at(rho + h).depth - f.at(rho - h).depth) / (2 * h);
    CHECK(f.steepest(rho, rho) == Approx(std::abs(d_depth)).margin(1e-6));
  }
  // A held lag has no slope: the bottom, the loxodrome's tip.
  if (f.tip() > 0) CHECK(f.slope(*tool, 0.5 * f.tip(), f.at(0.5 * f.tip())) == 0);
}

// The row walk rules a pass out along a row by how steep the section can be below a depth
// (floor_steepness): a bound too small would keep out a pass that can lower a node.
TEST_CASE("the steepest below a depth bounds the section's slope there", "[tooth_passage]") {
  const Tool t = GENERATE(from_range(tools()));
  const auto tool = testing::make_model<ToolGeometry>(t.plugin, t.values);
  const CutterProfile f(*tool);
  INFO(t.plugin);
  // The section's points on the surface (moving out with alpha, short of a fold): their depth
  // below the tube's centre plane and their slope |dZ/dX|, by differences of the section.
  struct Point {
    double depth, slope;
  };
  std::vector<Point> points;
  const double a0 = tool->first_polar_angle(), da = 1e-7;
  constexpr int kSamples = 20000;
  for (int k = 1; k < kSamples; ++k) {
    const double a = a0 + (M_PI / 2 - a0) * k / kSamples;
    const topomill::Vec2 lo = tool->section(a - da), hi = tool->section(a + da);
    if (!(hi.x() - lo.x() > 1e-4 * da)) continue;  // at or past a fold: not the surface
    points.push_back({-tool->section(a).y(), std::abs((hi.y() - lo.y()) / (hi.x() - lo.x()))});
  }
  REQUIRE(points.size() > kSamples / 2);
  const double r = f.tube();
  for (const double part : {0.05, 0.2, 0.5, 0.8, 0.95, 1.0}) {
    const double depth = part * r;
    double steepest = 0;
    for (const Point& p : points)
      if (p.depth >= depth) steepest = std::max(steepest, p.slope);
    INFO("depth " << depth << " mm: the section's steepest below it " << steepest);
    CHECK(f.steepest_below(depth) >= steepest * (1 - 1e-6));
  }
}

TEST_CASE("the profile describes a tool whose section is its tube's circle", "[tooth_passage]") {
  for (const Tool& t : tools())
    CHECK(CutterProfile::describes(*testing::make_model<ToolGeometry>(t.plugin, t.values)));
  CHECK_FALSE(CutterProfile::describes(Squashed()));
}
