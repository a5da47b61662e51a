// tooth_passage where the tool's axis passes over the nodes (lambda near 0), against a brute force
// written here: every node, every pass, every tooth, the time the ball can be below the uncut
// surface sampled finely (finer near the axis, where the node's azimuth turns at v / rho), the
// edge taken from ToolGeometry::edge_point (MODEL.md Eq. 1-7, not the evaluator's own formula),
// every sign change of the edge-minus-node azimuth bisected. No bound, no stopping rule.
#include <catch2/catch.hpp>
#include <cmath>

#include "support/scenes.hpp"

namespace {

constexpr double kTwoPi = 2 * M_PI;
double wrap(double a) {
  return a - kTwoPi * std::floor(a / kTwoPi + 0.5);
}

// The lowest edge height over (x, y) on the run's (corrected) path, or the uncut surface.
double brute_force_height(const topomill::ToolGeometry& tool, const topomill::ToolPath& path,
                          double x, double y) {
  const double R = tool.radius(), rev = kTwoPi / std::abs(path.spindle_rate());
  const double uncut = path.surface().height(y);
  // Fastest the centre moves in plan: the feed (plus the offset's turn on a curve, within 10 %)
  // and the correction's steepest piece.
  double v =
      1.1 * path.feed_speed() * (1 + path.offset() / std::abs(path.surface().curvature_radius()));
  for (std::size_t p = 0; p < path.passes(); ++p) {
    const auto& c = path.correction_samples(p);
    for (std::size_t k = 0; k + 1 < c.values.size(); ++k)
      v = std::max(v, path.feed_speed() + std::hypot(c.values[k + 1].x() - c.values[k].x(),
                                                     c.values[k + 1].y() - c.values[k].y()) /
                                              c.dt);
  }
  double best = uncut;
  auto phase = [&](std::size_t p, int tooth, double t, double& height, double& rho) {
    const topomill::Vec3 c = path.centre(p, t);
    const double qx = x - c.x(), qy = y - c.y();
    rho = std::hypot(qx, qy);
    if (rho >= R) return height = INFINITY, 0.0;
    height = c.z() - std::sqrt(R * R - rho * rho);
    const topomill::Vec3 e = tool.edge_point(tooth, std::asin(rho / R), path.spindle_angle(p, t));
    return wrap(std::atan2(e.y(), e.x()) - std::atan2(qy, qx));
  };
  for (std::size_t p = 0; p < path.passes(); ++p) {
    const double t_end = path.pass(p).t_end;
    for (int tooth = 0; tooth < tool.teeth(); ++tooth) {
      // Revolution by revolution, those in which the ball can reach below the uncut surface.
      for (double r0 = 0; r0 < t_end; r0 += rev) {
        const topomill::Vec3 c = path.centre(p, r0 + rev / 2);
        const double reach = std::hypot(x - c.x(), y - c.y()) - v * rev / 2;
        if (reach >= R ||
            c.z() - std::sqrt(R * R - std::pow(std::max(reach, 0.0), 2)) >= best + 1e-3)
          continue;
        double t0 = r0, h0 = 0, rho0 = 0, g0 = phase(p, tooth, t0, h0, rho0);
        const double r1 = std::min(r0 + rev, t_end);
        while (t0 < r1) {
          // A fiftieth of a radian of the node's azimuth, a 4096th of a revolution: a step of a
          // fiftieth (1024th) lost a pair of crossings 24 nm below the rest with vibration.
          const double step = std::clamp(0.005 * rho0 / v, 1e-10 * rev, rev / 4096);
          const double t1 = std::min(t0 + step, r1);
          double h1 = 0, rho1 = 0;
          const double g1 = phase(p, tooth, t1, h1, rho1);
          if ((g0 < 0) != (g1 < 0) && std::abs(g1 - g0) < M_PI) {
            double lo = t0, hi = t1, glo = g0;
            for (int it = 0; it < 60; ++it) {
              const double mid = 0.5 * (lo + hi);
              double hm = 0, rm = 0;
              const double gm = phase(p, tooth, mid, hm, rm);
              ((gm < 0) == (glo < 0) ? lo : hi) = mid;
              if ((gm < 0) == (glo < 0)) glo = gm;
            }
            double hr = 0, rr = 0;
            phase(p, tooth, 0.5 * (lo + hi), hr, rr);
            best = std::min(best, hr);
          }
          // The tip is a point of every edge: a node on the pass's line is cut by it.
          if (std::abs(x - path.pass(p).x) < 1e-9 && rho1 < v * step) best = std::min(best, h1);
          t0 = t1, g0 = g1, rho0 = rho1;
        }
      }
    }
  }
  return best;
}

const std::string kDynamics = testing::dynamics_tables();

}  // namespace

TEST_CASE("tooth_passage equals a brute force where the axis passes over the nodes",
          "[fast][near-axis]") {
  struct Case {
    const char* name;
    std::string workpiece;
    double lambda, size_x, size_s, spacing;
    std::vector<std::string> overrides;
    std::string extra;
  };
  const std::string flat = "plugin = 'inclined_plane'",
                    convex = "plugin = 'convex_arc'\nradius = 50.0";
  const std::vector<std::string> vertical_flat = {"tool.plugin=ball_end_constant_lead",
                                                  "tool.helix_angle=0", "cutting.depth_of_cut=0.02",
                                                  "cutting.spindle_direction=ccw"};
  const Case c = GENERATE_COPY(
      // The case: a vertical ball end on a flat plate, across a pass line at 1 um.
      Case{"flat, helix 0, ccw, 2 teeth", flat, 0.0, 0.04, 0.02, 0.001, vertical_flat, ""},
      Case{"convex, loxodrome 30, cw, 3 teeth, ap 0.3",
           convex,
           0.0,
           0.05,
           0.03,
           0.002,
           {"tool.teeth=3"},
           ""},
      Case{"convex at 2 deg, 1 tooth, ap 0.005, ccw",
           convex,
           2.0,
           0.02,
           0.02,
           0.0005,
           {"tool.teeth=1", "cutting.depth_of_cut=0.005", "cutting.spindle_direction=ccw"},
           ""},
      Case{"flat, constant lead 30, 4 teeth, phase 90",
           flat,
           0.0,
           0.3,
           0.05,
           0.005,
           {"tool.plugin=ball_end_constant_lead", "tool.teeth=4", "path.phase_shift=90",
            "cutting.depth_of_cut=0.05"},
           ""},
      Case{"convex, vibration and deflection", convex, 0.0, 0.03, 0.03, 0.0025, {}, kDynamics});
  INFO(c.name);
  const std::string scene =
      testing::paper_scene(c.workpiece, c.lambda, c.size_x, c.size_s, c.spacing) + c.extra;
  auto doc = topomill::SceneDocument::parse_string(scene, "near-axis.toml");
  for (const auto& o : c.overrides) doc.apply_override(o);
  topomill::PluginCatalog catalog({{topomill::PluginCatalog::builtin_dir(), "built-in"}});
  const topomill::Prepared tool_only = topomill::prepare(doc.resolve(catalog), catalog);
  std::vector<double> expected;
  for (const char* walk : {"row", "node"}) {
    auto o = c.overrides;
    o.push_back("evaluator.plugin=tooth_passage");
    o.push_back(std::string("evaluator.walk=") + walk);
    const auto run = testing::run_scene(scene, o, 2);
    const auto& g = run.raw.grid;
    if (expected.empty())
      for (std::size_t j = 0; j < g.ny; ++j)
        for (std::size_t i = 0; i < g.nx; ++i)
          expected.push_back(brute_force_height(*tool_only.tool, *run.layout.path, g.x(i), g.y(j)));
    double worst = 0;
    std::size_t wi = 0, wj = 0;
    for (std::size_t j = 0; j < g.ny; ++j)
      for (std::size_t i = 0; i < g.nx; ++i)
        if (const double d = std::abs(run.raw.at(i, j) - expected[j * g.nx + i]); d > worst)
          worst = d, wi = i, wj = j;
    INFO(walk << " walk: largest difference " << worst * 1e6 << " nm at node (" << wi << ", " << wj
              << ") of " << g.nx << " x " << g.ny);
    CHECK(worst <= 1e-6);
  }
}
