// The Z-map against an exact brute force written here, at every node of a patch, for each cutter
// with a ring and for per-edge runout: for a vertical tool over a plate, tooth K's edge is over a
// node at distance rho from the axis when its azimuth there, theta_K + phi(t) + Psi(alpha(rho)),
// equals the node's; the phase is scanned finely over the pass (finer still next to the rim),
// every crossing is halved to round-off, and the lowest height of the edge at a crossing is the
// node's (an insert with an axial rake: the lowest of the section's points at rho, by a scan of
// the section). The Z-map samples
// time and edge: it must agree within the local slope times its cell.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <map>
#include <sstream>
#include <string>

#include "support/builtin_models.hpp"
#include "support/scenes.hpp"
#include "topomill/tool_geometry.hpp"

using testing::run_scene;
using topomill::ToolGeometry;
using topomill::ToolPath;
using topomill::Vec3;

namespace {
// Where tooth K's edge crosses rho from the axis (circular sections): its polar angle and height;
// the bottom inside the ring of an end mill is alpha = 0 with the height of the tube's lowest
// point. Where no edge of the tooth lies at rho (beyond the rim, inside an insert's inner end) the
// height is NaN and the polar angle the nearer end's, so that the phase scanned goes on
// continuously: a crossing just inside the rim, a scan step before the node leaves the edge's
// reach, is then a sign change like any other.
struct EdgeAt {
  double alpha, height;
};
EdgeAt edge_at(const ToolGeometry& tool, double rho, double out, double up) {
  const double c = tool.ring() + out, r = tool.radius();
  if (tool.has_bottom() && rho <= c) return {0.0, -r + up};
  const double s = r > 0 ? (rho - c) / r : INFINITY;
  if (s > 1) return {M_PI / 2, NAN};
  if (s < std::sin(tool.first_polar_angle())) return {tool.first_polar_angle(), NAN};
  return {std::asin(s), -r * std::sqrt(1 - s * s) + up};
}

// An insert tilted by an axial rake: its section is no circle, and may fold back on itself (what
// lies past a fold is above the rest). Its lowest point at rho, by scanning the section at 4096
// polar angles and halving each crossing of rho to round-off; NaN where the edge does not reach.
bool sheared(const ToolGeometry& tool) {
  return std::abs(tool.section(M_PI / 2).x() - tool.ring() - tool.radius()) > 1e-12;
}
double lowest_on_section(const ToolGeometry& tool, double rho, double out, double up) {
  constexpr int kSamples = 4096;
  const double a0 = tool.first_polar_angle();
  auto off = [&](double a) { return tool.section(a).x() + out - rho; };
  double best = NAN, a_prev = a0, f_prev = off(a0);
  for (int k = 1; k <= kSamples; ++k) {
    const double a = a0 + (M_PI / 2 - a0) * k / kSamples, f = off(a);
    if (f_prev * f <= 0) {
      double lo = a_prev, hi = a, f_lo = f_prev;
      for (int it = 0; it < 60; ++it) {
        const double mid = 0.5 * (lo + hi), f_mid = off(mid);
        (f_lo * f_mid <= 0 ? hi : lo) = mid;
        if (f_lo * f_mid > 0) f_lo = f_mid;
      }
      const double z = tool.section(0.5 * (lo + hi)).y() + up;
      if (!(z >= best)) best = z;
    }
    a_prev = a, f_prev = f;
  }
  return best;
}

// How far the Z-map may lie from the exact height, in steps to the nearest neighbour: half a
// cell's diagonal is 0.71 of one.
constexpr double kSlack = 0.75;

// Where the scan goes finer: polar angles past 75 deg (the rim's), by this many sub-steps.
constexpr double kRimScan = 75 * M_PI / 180;
constexpr int kFine = 32;

// The lowest height any tooth's edge passes over (x, y) along pass p, by the scan and halving.
double oracle(const ToolGeometry& tool, const ToolPath& path, std::size_t p, double x, double y) {
  const ToolPath::Runout& run = path.runout();
  const double t_end = path.pass(p).t_end;
  const double rev = 2 * M_PI / std::abs(path.spindle_rate());
  const double dt = rev / 1000;  // the phase turns far less than a quarter turn a step
  double best = INFINITY;
  // A sheared edge lies in a half-plane (round_insert.cpp): its lag is the same all along, and
  // the phase needs no polar angle; its height is scanned at the crossings alone.
  const bool shear = sheared(tool);
  if (shear) REQUIRE(tool.lag(tool.first_polar_angle()) == tool.lag(M_PI / 2));
  for (int k = 0; k < tool.teeth(); ++k) {
    const double out = k * run.edge_radial, up = k * run.edge_axial;
    // The phase of tooth k's edge against the node's azimuth at t, wrapped to (-pi, pi].
    auto phase = [&](double t, EdgeAt* at) {
      const Vec3 c = path.centre(p, t);
      const double qx = x - c.x(), qy = y - c.y();
      const double rho = std::hypot(qx, qy);
      const EdgeAt e = !shear ? edge_at(tool, rho, out, up)
                              : EdgeAt{0.0, at ? lowest_on_section(tool, rho, out, up) : NAN};
      if (at) *at = {e.alpha, e.height + c.z()};
      const double edge = tool.tooth_angle(k) + path.spindle_angle(p, t) + tool.lag(e.alpha);
      return std::remainder(edge - std::atan2(qy, qx), 2 * M_PI);
    };
    // Each sign change within a quarter turn is a crossing (a jump of nearly 2 pi is the wrap),
    // halved to round-off.
    auto crossings_in = [&](double t0, double g0, double t1, double g1) {
      if (!(g0 * g1 <= 0 && std::abs(g1 - g0) < M_PI / 2)) return;
      double a = t0, b = t1, ga = g0;
      for (int it = 0; it < 80; ++it) {
        const double m = 0.5 * (a + b), gm = phase(m, nullptr);
        (ga * gm <= 0 ? b : a) = m;
        if (ga * gm > 0) ga = gm;
      }
      EdgeAt at;
      phase(0.5 * (a + b), &at);
      if (!std::isnan(at.height)) best = std::min(best, at.height);
    };
    EdgeAt at0{0.0, NAN};
    double t0 = 0, g0 = phase(0, shear ? nullptr : &at0);
    for (double t1 = dt; t1 <= t_end; t1 += dt) {
      EdgeAt at1;
      const double g1 = phase(t1, shear ? nullptr : &at1);
      // Next to the rim the lag turns faster than the spindle, and a passage can cross the node
      // three times within a step: there (an edge at either end) the step is scanned at a 32nd
      // of itself.
      auto by_rim = [](const EdgeAt& e) { return e.alpha > kRimScan && !std::isnan(e.height); };
      if (by_rim(at0) || by_rim(at1)) {
        double ta = t0, ga = g0;
        for (int m = 1; m <= kFine; ++m) {
          const double tb = t0 + (t1 - t0) * m / kFine, gb = m == kFine ? g1 : phase(tb, nullptr);
          crossings_in(ta, ga, tb, gb);
          ta = tb, ga = gb;
        }
      } else {
        crossings_in(t0, g0, t1, g1);
      }
      t0 = t1, g0 = g1, at0 = at1;
    }
  }
  return best;
}

using Values = std::vector<std::pair<std::string, double>>;

// A vertical tool on passes along +Y, one through x = 0, over a plate inclined by `angle` (the
// next pass `stepover` away: out of reach by default), the patch centred x across it; the
// evaluator's table last (`evaluator`).
std::string plate(const std::string& plugin, const Values& tool, const std::string& extra, double x,
                  const std::string& evaluator, double angle = 0, double fz = 0.1,
                  double stepover = 50) {
  std::ostringstream s;
  s.precision(17);
  s << "[tool]\nplugin = '" << plugin << "'\n";
  for (const auto& [key, value] : tool) s << key << " = " << value << "\n";
  s << "[workpiece]\nplugin = 'inclined_plane'\nangle = " << angle << "\n"
    << "[cutting]\nspindle_speed = 4000\nfeed_per_tooth = " << fz << "\ndepth_of_cut = 0.1\n"
    << "stepover = " << stepover << "\nspindle_direction = 'ccw'\n[region]\ncentre = [" << x
    << ", 0.0]\nsize = [0.04, 0.04]\nspacing = 0.004\n"
    << extra << "[evaluator]\n"
    << evaluator;
  return s.str();
}
// The Z-map at half its usual time step.
const char* const kZmap = "plugin = 'zmap'\ntime_step_fraction = 0.5\n";

struct Case {
  const char* name;
  std::string plugin;
  Values tool;
  std::string extra;
  double x;              // the patch's centre across the pass
  double angle = 0;      // the plate's inclination along the feed (deg)
  double fz = 0.1;       // the feed per tooth (mm)
  double stepover = 50;  // between the passes (mm): out of reach unless set
};
std::vector<Case> cases() {
  return {Case{"bull-nose, on its corner",
               "bull_nose",
               {{"diameter", 2}, {"corner_radius", 0.5}},
               "",
               0.7},
          Case{"bull-nose, over its bottom's rim",
               "bull_nose",
               {{"diameter", 2}, {"corner_radius", 0.5}},
               "",
               0.5},
          Case{"flat end with a corner radius, per-edge runout",
               "flat_end",
               {{"diameter", 2}, {"corner_radius", 0.2}, {"teeth", 3}},
               "[runout]\nedge_radial_step = 0.004\nedge_axial_step = 0.001\n",
               0.85},
          Case{"round inserts, inner side, per-edge runout",
               "round_insert",
               {{"diameter", 1}, {"insert_radius", 0.5}, {"radial_rake", 5}},
               "[runout]\nedge_radial_step = -0.006\nedge_axial_step = 0.0005\n",
               0.2},
          Case{"round inserts, outer side",
               "round_insert",
               {{"diameter", 1}, {"insert_radius", 0.5}},
               "",
               0.65},
          Case{"round inserts with an axial rake, outer side",
               "round_insert",
               {{"diameter", 1}, {"insert_radius", 0.5}, {"axial_rake", 10}},
               "",
               0.65},
          Case{"ball end, per-edge runout",
               "ball_end_constant_lead",
               {{"radius", 1}},
               "[runout]\nedge_radial_step = 0.003\nedge_axial_step = -0.001\n",
               0.3}};
}

// Where only the exact evaluator is held to the brute force (the Z-map's cell error aside): the
// axis over the nodes, a sharp corner, and the centre moved by vibration and deflection (the
// brute force reads the corrected centre, ToolPath::centre).
const char* const kEffects =
    "[force]\nplugin = 'armarego'\n[vibration]\nplugin = 'modal_exact'\n"
    "modes = [{axis = 'x', frequency = 785.0, damping = 0.0246, stiffness = 1.74e7},"
    " {axis = 'y', frequency = 800.0, damping = 0.0263, stiffness = 1.71e7},"
    " {axis = 'z', frequency = 753.0, damping = 0.0215, stiffness = 1.21e7}]\n"
    "[deflection]\nplugin = 'cantilever'\noverhang = 6.0\n";
std::vector<Case> hard_cases() {
  return {
      Case{"flat end, sharp corner, the axis over the nodes",
           "flat_end",
           {{"diameter", 2}, {"corner_radius", 0}, {"teeth", 2}},
           "",
           0.0},
      Case{"flat end on a plane inclined along the feed, the axis over the nodes",
           "flat_end",
           {{"diameter", 2}, {"corner_radius", 0.2}, {"teeth", 3}},
           "",
           0.0,
           20.0},
      Case{"flat end on an inclined plane, its bottom's rim a feed from its reach",
           "flat_end",
           {{"diameter", 2}, {"corner_radius", 0.05}, {"teeth", 2}, {"helix_angle", 30}},
           "",
           0.3,
           10.0},
      Case{"flat end on a steep incline, a passage crossing three times next to the rim",
           "flat_end",
           {{"diameter", 1.16818},
            {"corner_radius", 0.0738491},
            {"teeth", 4},
            {"helix_angle", 27.1313}},
           "",
           0.382469,
           17.9193,
           0.322241},
      Case{"flat end, the axis over the nodes, vibration and deflection",
           "flat_end",
           {{"diameter", 2}, {"corner_radius", 0.1}, {"teeth", 4}},
           kEffects,
           0.0},
      Case{"bull-nose over its bottom's rim, vibration and deflection",
           "bull_nose",
           {{"diameter", 2}, {"corner_radius", 0.5}, {"teeth", 3}},
           kEffects,
           0.5},
      Case{"bull-nose, on its corner, vibration and deflection",
           "bull_nose",
           {{"diameter", 2}, {"corner_radius", 0.5}, {"teeth", 2}},
           kEffects,
           0.75},
      Case{"bull-nose on a small ring, steep helix, next to the axis",
           "bull_nose",
           {{"diameter", 2}, {"corner_radius", 0.98}, {"helix_angle", 60}, {"teeth", 2}},
           "",
           0.03},
      Case{"round inserts reaching the axis, over it",
           "round_insert",
           {{"diameter", 1}, {"insert_radius", 0.5}, {"teeth", 3}},
           "",
           0.0},
      // Small inserts, so that the folds lie within the depth of cut (0.048 mm up); for the
      // inner fold a feed so long that some nodes are crossed only there.
      Case{"round inserts, a negative axial rake, past the edge's end to its outer fold",
           "round_insert",
           {{"diameter", 1}, {"insert_radius", 0.1}, {"axial_rake", -30}, {"teeth", 3}},
           "",
           0.565},
      Case{"round inserts, a positive axial rake, its inner fold, sparse feed marks",
           "round_insert",
           {{"diameter", 1},
            {"insert_radius", 0.1},
            {"axial_rake", 30},
            {"radial_rake", -6},
            {"teeth", 1}},
           "",
           0.44,
           0.0,
           0.6},
      Case{"round inserts with an axial rake, vibration and per-edge runout",
           "round_insert",
           {{"diameter", 1}, {"insert_radius", 0.5}, {"axial_rake", 8}},
           std::string(kEffects) + "[runout]\nedge_radial_step = 0.004\nedge_axial_step = 0.0005\n",
           0.3},
      // Passes that overlap: each node under up to four, whose flat bottoms leave feed marks
      // deeper than the passes' lowest points differ by, so that a pass is ruled out only by its
      // own lowest (RowSweep's pass skip); ideal and with the effects' wiggles.
      Case{"flat end, passes 0.7 mm apart on a plate inclined 3 deg along the feed",
           "flat_end",
           {{"diameter", 4}, {"corner_radius", 0.2}, {"teeth", 2}, {"helix_angle", 30}},
           "",
           0.37,
           3.0,
           0.2,
           0.7},
      Case{"flat end, passes 0.6 mm apart, vibration and deflection",
           "flat_end",
           {{"diameter", 2}, {"corner_radius", 0.1}, {"teeth", 3}},
           kEffects,
           0.27,
           5.0,
           0.1,
           0.6},
      Case{
          "round inserts, inner side, vibration and per-edge runout",
          "round_insert",
          {{"diameter", 1}, {"insert_radius", 0.5}},
          std::string(kEffects) + "[runout]\nedge_radial_step = 0.005\nedge_axial_step = -0.0005\n",
          0.25}};
}

// The exact heights over the scene's patch, the lowest from the passes that reach its nodes;
// found once a case (the walks share the path).
const std::vector<double>& exact_patch(const topomill::RunResult& r, const Case& c) {
  static std::map<std::string, std::vector<double>> found;
  if (const auto it = found.find(c.name); it != found.end()) return it->second;
  const auto tool = testing::make_model<ToolGeometry>(c.plugin, c.tool);
  const ToolPath& path = *r.layout.path;
  const auto& g = r.raw.grid;
  // (A margin for the runout and the effects: a pass a little farther is only asked in vain.)
  const double reach = tool->reach() + 0.1;
  std::vector<double> exact(g.nx * g.ny, INFINITY);
  for (std::size_t p = 0; p < path.passes(); ++p)
    for (std::size_t j = 0; j < g.ny; ++j)
      for (std::size_t i = 0; i < g.nx; ++i) {
        const double x = g.x0 + static_cast<double>(i) * g.dx;
        if (std::abs(path.pass(p).x - x) > reach) continue;
        double& z = exact[j * g.nx + i];
        z = std::min(z, oracle(*tool, path, p, x, g.y0 + static_cast<double>(j) * g.dy));
      }
  return found[c.name] = exact;
}
}  // namespace

TEST_CASE("the Z-map cuts every cutter where an exact brute force does", "[cutter][oracle]") {
  const Case c = GENERATE(from_range(cases()));
  DYNAMIC_SECTION(c.name) {
    const auto r =
        run_scene(plate(c.plugin, c.tool, c.extra, c.x, kZmap, c.angle, c.fz, c.stepover));
    const std::vector<double>& exact = exact_patch(r, c);
    const auto& g = r.raw.grid;
    // The Z-map puts an edge point on the nearest node: off by the slope times up to half a
    // diagonal, the slope taken from the exact heights' steepest step to a neighbour.
    double worst = 0;
    for (std::size_t j = 0; j < g.ny; ++j)
      for (std::size_t i = 0; i < g.nx; ++i) {
        const double z = exact[j * g.nx + i];
        REQUIRE(std::isfinite(z));
        double step = 0;
        for (auto [di, dj] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
          const long ii = static_cast<long>(i) + di, jj = static_cast<long>(j) + dj;
          if (ii < 0 || jj < 0 || ii >= static_cast<long>(g.nx) || jj >= static_cast<long>(g.ny))
            continue;
          step = std::max(step, std::abs(exact[jj * g.nx + ii] - z));
        }
        const double off = std::abs(r.raw.at(i, j) - std::min(z, 0.0));
        worst = std::max(worst, off / (step + 1e-6));
        INFO("node (" << i << ", " << j << "): zmap " << r.raw.at(i, j) << ", exact " << z);
        CHECK(off <= kSlack * step + 1e-6);
      }
    WARN(c.name << ": worst Z-map error " << worst << " of the step to a neighbour");
  }
}

TEST_CASE("tooth_passage cuts every cutter where an exact brute force does, to 1 nm",
          "[cutter][oracle]") {
  const Case c = GENERATE(from_range(cases()), from_range(hard_cases()));
  const std::string walk = GENERATE(as<std::string>{}, "row", "node");
  DYNAMIC_SECTION(c.name << ", walk " << walk) {
    const auto r = run_scene(plate(c.plugin, c.tool, c.extra, c.x,
                                   "plugin = 'tooth_passage'\nwalk = '" + walk + "'\n", c.angle,
                                   c.fz, c.stepover));
    const std::vector<double>& exact = exact_patch(r, c);
    const auto& g = r.raw.grid;
    for (std::size_t j = 0; j < g.ny; ++j)
      for (std::size_t i = 0; i < g.nx; ++i) {
        // Not above the plate (the map starts there).
        const double top = -(g.y0 + static_cast<double>(j) * g.dy) * std::tan(c.angle * M_PI / 180);
        const double z = std::min(exact[j * g.nx + i], top);
        INFO("node (" << i << ", " << j << "): tooth_passage " << r.raw.at(i, j) << ", exact "
                      << z);
        CHECK(std::abs(r.raw.at(i, j) - z) < 1e-6);
      }
  }
}
