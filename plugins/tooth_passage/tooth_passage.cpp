// A fast evaluator with the Z-map's converged answer: for each node, the moments at which a
// tooth's edge crosses the node's vertical line are solved for, and the lowest edge height at
// those moments is kept. The Z-map approximates exactly this min with finite time and edge steps
// (and its nearest-node rounding); here each crossing is found to round-off, so there is no grid
// error at all, only the grid's sampling of the true surface.
//
// Two walks give the same heights: "row" (default) follows every passage from node to node
// along a row (row_sweep.hpp); "node" solves each node from scratch (the reference it is tested
// against). A third, "scan", finds every crossing by brute force, to check both walks' rules
// (node_walk.hpp). Rows are independent, so any split of rows over threads gives the same bits.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <string>
#include <thread>

#include "row_sweep.hpp"
#include "topomill/plugin.hpp"
#include "topomill/topography_evaluator.hpp"

namespace topomill::plugins {

class ToothPassage : public TopographyEvaluator {
 public:
  static Schema schema() {
    Schema s;
    s.add_number("catw_margin", "Widening a of the contact angle range (Eq. 43), as for zmap")
        .at_least(1)
        .at_most(10)
        .with_default(1.5);
    s.add_integer("iterations", "Secant steps per tooth passage, at most (converges in 3-5)")
        .at_least(1)
        .at_most(50)
        .with_default(std::int64_t{12});
    s.add_choice("walk", {"row", "node", "scan"},
                 "row: follow each tooth passage from node to node along a row (fast); node: "
                 "solve every node from scratch (the reference, same heights to round-off); "
                 "scan: every crossing by brute force, to check the others' stopping rules "
                 "(thousands of times slower)")
        .with_default(std::string("row"));
    return s;
  }
  explicit ToothPassage(const Params& p)
      : margin_(p.number("catw_margin")),
        iterations_(static_cast<int>(p.integer("iterations"))),
        walk_(p.string("walk") == "row"    ? Walk::Row
              : p.string("walk") == "node" ? Walk::Node
                                           : Walk::Scan) {}

  // Every posture: fixed, tilted or not; along the normal, whose frame turns about X with the
  // inclination over the curvature; the axis cutter-location data give, turning between their
  // points (BlendFrame). The bounds follow a turning frame's rate (PassageSetup::Turn).
  bool follows(const ToolPath::Posture&) const override { return true; }
  // Any path: a bent pass is taken as straight windows (PassageSetup::Window).
  bool follows_curves() const override { return true; }
  // The ball at any posture; every cutter whose section is its tube's circle, sheared by an axial
  // rake or not, and per-edge runout (each edge walked as a cutter of its own), with a vertical
  // axis: the profile over a node is then a function of its distance from the axis
  // (cutter_profile.hpp).
  bool follows_cutter(const ToolGeometry& tool, const ToolPath::Runout& runout,
                      const ToolPath::Posture& posture) const override {
    if (tool.ring() == 0 && !runout.per_edge()) return true;
    return posture.vertical() && CutterProfile::describes(tool);
  }

  // Memory: the centre tables, about 4 KB a pass (measured: 30 MB for 8 600 passes at a 0.1 um
  // step-over). Time, for the row walk on one thread (measured on the paper's lambda = 30 deg
  // patch, 87 x 87 nodes): 1.5 us a node, plus 12 ns a node for each pass whose ball reaches
  // it (2 R sin(kappa) / ae of them: 3.2 s at ae = 0.1 um). The feed adds little down to the
  // schema's 1 nm (0.06 s at fz = 1e-8 mm). The node and scan walks are slower (not estimated).
  EvaluationCost estimate_cost(const EvaluationRequest& rq, const Grid& g) const override {
    EvaluationCost c;
    const ToolPath& path = *rq.path;
    double windows = 0;  // at most a window per segment of a bent pass
    for (std::size_t p = 0; p < path.passes(); ++p)
      windows += std::max<double>(1.0, static_cast<double>(path.pass(p).waypoints.size()) - 1);
    c.bytes = 4096.0 * windows;
    c.bytes_key = "cutting.stepover";
    if (walk_ != Walk::Row) return c;
    // A ringed cutter has no contact window: all of its width reaches. Each edge of a per-edge
    // runout is walked alone.
    const double reach = rq.tool->ring() > 0
                             ? 2 * rq.tool->reach()
                             : 2 * rq.tool->radius() * std::sin(std::min(rq.kappa, M_PI / 2));
    const double edges = rq.path->runout().per_edge() ? rq.tool->teeth() : 1;
    double ae = 0;  // the step between the first two passes, along the step direction
    if (path.passes() > 1)
      ae = path.feed_axis() == ToolPath::FeedAxis::Y
               ? std::abs(path.pass(1).x - path.pass(0).x)
               : std::abs(path.pass(1).y_start - path.pass(0).y_start);
    const double node = 1.5e-6;
    const double passes = ae > 0 ? 12e-9 * reach / ae : 0;
    c.seconds = edges * static_cast<double>(g.nx) * static_cast<double>(g.ny) * (node + passes);
    c.seconds_key = node >= passes ? "region.spacing" : "cutting.stepover";
    return c;
  }

  // With a per-edge runout each edge is a cutter of its own (its ring and height moved:
  // PassageSetup's `edge`), walked alone; the map keeps the lowest of all.
  void evaluate(const EvaluationRequest& rq, HeightMap& map, WorkCounts& counts) const override {
    const bool per_edge = rq.path->runout().per_edge();
    const int edges = per_edge ? rq.tool->teeth() : 1;
    NodeCounts total;
    for (int edge = 0; edge < edges && !rq.stopped(); ++edge)
      total += sweep(PassageSetup(rq, margin_, iterations_, per_edge ? edge : -1), rq, map,
                     static_cast<double>(edge) / edges, 1.0 / edges);
    const Grid& g = map.grid;
    counts["nodes"] = g.size();
    counts["tooth_passages"] = total.passages;
    counts["updates"] = total.updates;
    if (walk_ == Walk::Row) {
      counts["fallbacks"] = total.fallbacks;
      counts["exact_windows"] = total.exact_windows;
      counts["nodes_followed"] = total.nodes_followed;
      counts["nodes_exact"] = total.nodes_exact;
      counts["nodes_fallback"] = total.nodes_fallback;
    }
  }

 private:
  // One setup's walks over every row, lowering the map where they go lower; the progress reported
  // runs from `done` over `share` of the whole.
  NodeCounts sweep(const PassageSetup& setup, const EvaluationRequest& rq, HeightMap& map,
                   double done, double share) const {
    // The scan samples a tooth period 256 times, and a correction's linear piece 4 times.
    double scan_step = setup.rev / rq.tool->teeth() / 256;
    for (std::size_t p = 0; p < rq.path->passes(); ++p)
      if (const double dt = rq.path->correction_step(p); dt > 0)
        scan_step = std::min(scan_step, dt / 4);
    const Grid& g = map.grid;
    const unsigned threads = std::max(1u, std::min<unsigned>(rq.threads, 64));
    std::vector<NodeCounts> done_by(threads);
    std::vector<double> xs(g.nx);
    for (std::size_t i = 0; i < g.nx; ++i) xs[i] = g.x(i);
    std::atomic<std::size_t> next_row{0};
    auto work = [&](unsigned w) {
      NodeCounts mine;  // counted here, not in done_by[w]: neighbours in one cache line would
                        // make the threads take turns
      RowSweep row_sweep(setup);
      std::vector<std::pair<double, std::size_t>> order;
      std::vector<PassageGeometry::Crossing> roots;
      // Rows are handed out one at a time, so that a thread slowed by anything else on the
      // machine takes fewer; each row is computed alone, so the bits do not depend on who.
      for (std::size_t j = next_row++; j < g.ny && !rq.stopped(); j = next_row++) {
        double* z = &map.at(0, j);
        if (walk_ == Walk::Row) {
          row_sweep.row(g.y(j), xs, z, mine);
        } else {
          for (std::size_t i = 0; i < g.nx; ++i) {
            const double low = walk_ == Walk::Node
                                   ? node_height_reference(setup, xs[i], g.y(j), mine, order, roots)
                                   : node_height_scan(setup, xs[i], g.y(j), scan_step, mine);
            if (low < z[i]) z[i] = low, ++mine.updates;
          }
        }
        if (w == 0 && rq.progress) rq.progress(done + share * static_cast<double>(j) / g.ny);
      }
      done_by[w] = mine;
    };
    std::vector<std::thread> pool;
    for (unsigned w = 1; w < threads; ++w) pool.emplace_back(work, w);
    work(0);
    for (auto& t : pool) t.join();
    NodeCounts total;
    for (const auto& d : done_by) total += d;
    return total;
  }

  double margin_;
  int iterations_;
  enum class Walk { Row, Node, Scan } walk_;  // the schema's choice, read once
};

}  // namespace topomill::plugins

TOPOMILL_PLUGIN("tooth_passage", "0.2.0") {
  registrar.add<topomill::TopographyEvaluator, topomill::plugins::ToothPassage>(
      "tooth_passage",
      "Fast evaluator: per node, solves for the tooth passages over it and keeps "
      "the lowest (the Z-map's converged limit, no grid error)");
}
