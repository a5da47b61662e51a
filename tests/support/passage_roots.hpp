// What the tests of tooth_passage's pieces
// (tests/plugins/tooth_passage/passage_geometry_*_test.cpp) share: the paper's scene at lambda 0 on
// a given workpiece, prepared, and its PassageSetup; the scenes about a pass's line; the pass whose
// line is nearest the patch's middle; and a window's crossings found with no bound and no rule, by
// sampling a tooth's phase and bisecting each sign change with probes.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "run/pipeline.hpp"
#include "scene.hpp"
#include "support/scenes.hpp"
#include "tooth_passage/passage_geometry.hpp"

namespace testing {

// The paper's scene on `workpiece` (its [workpiece] table's keys) at lambda 0, 0.2 mm square at
// 10 um, with `extra` (TOML tables) appended and `overrides` ("table.key=value") applied.
inline topomill::Prepared paper_patch(const std::string& workpiece, const std::string& extra = "",
                                      const std::vector<std::string>& overrides = {}) {
  auto doc = topomill::SceneDocument::parse_string(
      paper_scene(workpiece, 0.0, 0.2, 0.2, 0.01) + extra, "passage.toml");
  for (const auto& o : overrides) doc.apply_override(o);
  topomill::PluginCatalog catalog({{topomill::PluginCatalog::builtin_dir(), "built-in"}});
  return topomill::prepare(doc.resolve(catalog), catalog);
}

// The same on the convex arc (r 50).
inline topomill::Prepared paper_arc(const std::string& extra = "",
                                    const std::vector<std::string>& overrides = {}) {
  return paper_patch("plugin = 'convex_arc'\nradius = 50.0", extra, overrides);
}

// tooth_passage's setup of a prepared scene, as the evaluator builds it (margin 0.1, 12 steps).
inline topomill::plugins::PassageSetup passage_setup(const topomill::Prepared& m) {
  topomill::EvaluationRequest rq;
  rq.tool = m.tool.get(), rq.path = m.layout.path.get(), rq.kappa = m.layout.kappa;
  return topomill::plugins::PassageSetup(rq, 0.1, 12);
}

// A scene of the tests about a pass's line (passage_geometry_bounds_test,
// passage_geometry_lined_test): paper_patch's workpiece and overrides.
struct LineCase {
  const char* name;
  std::string workpiece;
  std::vector<std::string> overrides;
};
// The four they share: the paper's arc (loxodrome 30, both spindle directions) and a flat plate
// (constant lead 0 and 30 deg).
inline std::vector<LineCase> line_cases() {
  const std::string arc = "plugin = 'convex_arc'\nradius = 50.0",
                    flat = "plugin = 'inclined_plane'";
  return {{"convex arc, loxodrome 30, cw", arc, {}},
          {"convex arc, loxodrome 30, ccw", arc, {"cutting.spindle_direction=ccw"}},
          {"flat, constant lead 0, ccw",
           flat,
           {"tool.plugin=ball_end_constant_lead", "tool.helix_angle=0",
            "cutting.spindle_direction=ccw"}},
          {"flat, constant lead 30, cw",
           flat,
           {"tool.plugin=ball_end_constant_lead", "tool.helix_angle=30"}}};
}

// The pass whose line is nearest the patch's middle (the line at 0).
inline std::size_t nearest_pass(const topomill::plugins::PassageSetup& s) {
  std::size_t p = 0;
  for (std::size_t k = 1; k < s.window.size(); ++k)
    if (std::abs(s.window[k].line) < std::abs(s.window[p].line)) p = k;
  return p;
}

// The node `d` across the line of pass p and `along` on it, under that pass: where it is, its
// level time, and its geometry (the contact range from the level time, as the walks take it).
struct NodeOnLine {
  double x, y, t0;
  topomill::plugins::PassageGeometry geo;
};
inline NodeOnLine node_by_line(const topomill::plugins::PassageSetup& s, std::size_t p, double d,
                               double along) {
  const double x = s.along_y ? s.window[p].line + d : along,
               y = s.along_y ? along : s.window[p].line + d;
  const double t0 = s.level_time(p, x, y);
  const auto radii = s.contact_radii(p, t0);
  return {x, y, t0, topomill::plugins::PassageGeometry(s, p, x, y, radii.first, radii.second)};
}

// Tooth `tooth`'s crossings in [a, b]: the phase sampled every `step`, each sign change (not a
// wrap) bisected with probes until its bracket is under `width`.
inline std::vector<double> sampled_roots(const topomill::plugins::PassageGeometry& geo, int tooth,
                                         double a, double b, double step, double width) {
  std::vector<double> roots;
  double lo = a, g_lo = geo.probe(tooth, a).g;
  for (double hi = a + step; hi <= b; lo = hi, hi += step) {
    const double g_hi = geo.probe(tooth, hi).g, g_was = g_lo;
    g_lo = g_hi;
    if (!topomill::plugins::PassageGeometry::crosses(g_was, g_hi)) continue;
    double l = lo, h = hi;
    for (int k = 0; k < 200 && h - l > width; ++k) {
      const double mid = 0.5 * (l + h);
      ((geo.probe(tooth, mid).g < 0) == (g_was < 0) ? l : h) = mid;
    }
    roots.push_back(0.5 * (l + h));
  }
  return roots;
}

}  // namespace testing
