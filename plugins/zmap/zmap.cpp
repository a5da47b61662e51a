// The paper's Z-map evaluator (Sec. 4.2-4.3), kept as the reference every faster evaluator is
// checked against: at each time step every edge point inside the CATW is moved to the workpiece
// frame and lowers its nearest node.
#include <algorithm>
#include <cmath>
#include <thread>

#include "topomill/error.hpp"
#include "topomill/plugin.hpp"
#include "topomill/topography_evaluator.hpp"

namespace topomill::plugins {

class ZMap : public TopographyEvaluator {
 public:
  static Schema schema() {
    Schema s;
    s.add_number("catw_margin",
                 "Widening a of the contact angle range (Eq. 43), for vibration "
                 "and deflection")
        .at_least(1)
        .at_most(10)
        .with_default(1.5);
    s.add_number("time_step", "Time step; 0 = the paper's rule (Eq. 46) times time_step_fraction")
        .with_unit("s")
        .at_least(0)
        .with_default(0.0);
    s.add_number("time_step_fraction", "Fraction of Eq. 46's largest step used when time_step = 0")
        .above(0)
        .at_most(1)
        .with_default(0.9);
    s.add_number("edge_step_fraction",
                 "Edge point spacing dw as a fraction of the grid spacing (Eq. 44 needs <= 1)")
        .above(0)
        .at_most(1)
        .with_default(1.0);
    return s;
  }

  // Eq. 46: an edge point moves less than one cell per step.
  double time_step(const EvaluationRequest& rq, const Grid& g) const {
    if (time_step_ > 0) return time_step_;
    const double cell = std::min(g.dx, g.dy);
    const double omega = std::abs(rq.path->spindle_rate());
    const double phi_max_all = std::min(M_PI / 2, rq.lambda_max + margin_ * rq.kappa);
    // The fastest edge point: at the CATW's widest on a ball (the paper's expression, to the bit),
    // at the rim on any other cutter; a per-edge step adds to either.
    if (windowed(*rq.tool) && !rq.path->runout().per_edge())
      return time_fraction_ * cell /
             (omega * rq.tool->radius() * std::max(std::sin(phi_max_all), 1e-12));
    const double rim =
        (windowed(*rq.tool) ? rq.tool->radius() * std::sin(phi_max_all) : rq.tool->reach()) +
        max_edge_step(rq);
    return time_fraction_ * cell / (omega * std::max(rim, 1e-12 * rq.tool->radius()));
  }

  // A ball's edge points are taken within the CATW (the paper's); any other cutter's all along
  // its edge: the CATW's polar angles hold for the ball's sphere, not for a tube on a ring, where
  // the points in contact differ from one azimuth to the next.
  static bool windowed(const ToolGeometry& tool) { return tool.ring() == 0; }
  static double max_edge_step(const EvaluationRequest& rq) {
    const ToolPath::Runout& r = rq.path->runout();
    return std::abs(r.edge_radial) * (rq.tool->teeth() - 1);
  }
  // The most an edge point moves per radian of alpha (the section's speed): R on a circle, more
  // on a tilted insert's section; sampled, with the circle's R as its floor.
  static double section_speed(const ToolGeometry& tool) {
    constexpr int kSamples = 256;
    const double lo = tool.first_polar_angle(), step = (M_PI / 2 - lo) / kSamples;
    double speed = tool.radius();
    for (int k = 0; k < kSamples; ++k) {
      const Vec2 a = tool.section(lo + k * step), b = tool.section(lo + (k + 1) * step);
      speed = std::max(speed, (b - a).norm() / step * kSpeedMargin);
    }
    return speed;
  }
  static constexpr double kSpeedMargin = 1.01;   // a chord is shorter than its arc
  static constexpr double kBeyondMargin = 1.01;  // round-off, squared distances

  // Memory: one map per thread. Time: every edge point of every tooth at every step, 30 ns
  // each (measured: 368e6 points in 11.2 s on the paper's lambda = 30 deg scene, one thread),
  // the edge points per tooth from Eq. 44 over the widened contact range at the steepest lambda.
  bool follows(const ToolPath::Posture&) const override { return true; }  // any: it turns points
  bool follows_curves() const override { return true; }  // any: it moves them with the centre
  bool follows_cutter(const ToolGeometry&, const ToolPath::Runout&,
                      const ToolPath::Posture&) const override {
    return true;  // any: its points are the edges'
  }

  EvaluationCost estimate_cost(const EvaluationRequest& rq, const Grid& g) const override {
    EvaluationCost c;
    const double threads = std::max(1u, std::min<unsigned>(rq.threads, 64));
    c.bytes = threads * static_cast<double>(g.nx) * static_cast<double>(g.ny) * 8;
    c.bytes_key = "region.spacing";
    const double dt = time_step(rq, g);
    double steps = 0;
    for (std::size_t p = 0; p < rq.path->passes(); ++p) steps += rq.path->pass(p).t_end / dt + 1;
    const double lo = std::max(0.0, rq.lambda_max - margin_ * rq.kappa);
    const double hi = std::min(M_PI / 2, rq.lambda_max + margin_ * rq.kappa);
    const double dw = edge_fraction_ * std::min(g.dx, g.dy);
    const double points =
        windowed(*rq.tool)
            ? std::ceil((hi - lo) * rq.tool->radius() / dw) + 1
            : std::ceil((M_PI / 2 - rq.tool->first_polar_angle()) * section_speed(*rq.tool) / dw) +
                  1 + (rq.tool->has_bottom() ? std::ceil(rq.tool->ring() / dw) : 0.0);
    c.seconds = 30e-9 * steps * rq.tool->teeth() * points;
    c.seconds_key = time_step_ > 0 ? "evaluator.time_step"
                                   : "region.spacing (the time step follows it, Eq. 46)";
    return c;
  }

  // The edge points one step lowers nodes with, per point its distance from the axis, height and
  // lag (R sin(alpha), -R cos(alpha), Psi on a ball).
  struct EdgePoints {
    const ToolGeometry& tool;
    std::vector<double> ring, depth, lag;
    explicit EdgePoints(const ToolGeometry& t) : tool(t) {}
    // n + 1 points evenly over alpha in [lo, hi].
    void fill(double lo, double hi, int n) {
      const double tip = tool.min_polar_angle();
      ring.resize(n + 1), depth.resize(n + 1), lag.resize(n + 1);
      for (int e = 0; e <= n; ++e) {
        const double alpha = lo + (hi - lo) * e / n;
        const Vec2 section = tool.section(alpha);
        ring[e] = section.x();
        depth[e] = section.y();
        lag[e] = tool.lag(std::max(alpha, tip));
      }
    }
    // A cutter with a ring: its whole edge at most dw apart (the section moving at `speed` per
    // radian), and the flat bottom inside the ring, radially at the lag of the edge's lowest point.
    void whole(double speed, double dw) {
      const double lo = tool.first_polar_angle();
      fill(lo, M_PI / 2, std::max(1, static_cast<int>(std::ceil((M_PI / 2 - lo) * speed / dw))));
      if (!tool.has_bottom()) return;
      const int nb = static_cast<int>(std::ceil(tool.ring() / dw));
      for (int e = 0; e < nb; ++e) {
        ring.push_back(tool.ring() * e / nb);
        depth.push_back(depth[0]);
        lag.push_back(lag[0]);
      }
    }
  };

  // No edge point lies farther from the centre than `extent` (at most reach() from the axis and r
  // below the tube's centre plane, and the per-edge steps): a step whose centre is farther from
  // the grid (a pass beyond a face mill's reach) lowers nothing, and is skipped.
  struct GridReach {
    double extent, x_lo, x_hi, y_lo, y_hi;
    GridReach(const EvaluationRequest& rq, const Grid& g)
        : extent(std::hypot(rq.tool->reach(), rq.tool->radius()) + max_edge_step(rq) +
                 std::abs(rq.path->runout().edge_axial) * (rq.tool->teeth() - 1)),
          x_lo(g.x0 - g.dx / 2),
          x_hi(g.x0 + (static_cast<double>(g.nx) - 0.5) * g.dx),
          y_lo(g.y0 - g.dy / 2),
          y_hi(g.y0 + (static_cast<double>(g.ny) - 0.5) * g.dy) {}
    bool beyond(const Vec3& c) const {
      const double ox = std::max({0.0, x_lo - c.x(), c.x() - x_hi}),
                   oy = std::max({0.0, y_lo - c.y(), c.y() - y_hi});
      return ox * ox + oy * oy > extent * extent * kBeyondMargin;
    }
  };

  explicit ZMap(const Params& p)
      : margin_(p.number("catw_margin")),
        time_step_(p.number("time_step")),
        time_fraction_(p.number("time_step_fraction")),
        edge_fraction_(p.number("edge_step_fraction")) {}

  void evaluate(const EvaluationRequest& rq, HeightMap& map, WorkCounts& counts) const override {
    const ToolGeometry& tool = *rq.tool;
    const ToolPath& path = *rq.path;
    const Grid& g = map.grid;
    const double R = tool.radius();
    const double cell = std::min(g.dx, g.dy);
    const double dt = time_step(rq, g);
    const double dw = edge_fraction_ * cell;
    const double speed = windowed(tool) ? R : section_speed(tool);
    const ToolPath::Runout& runout = path.runout();
    const bool per_edge = runout.per_edge();
    const GridReach reach(rq, g);

    // Steps are numbered across passes: pass p holds steps first[p] .. first[p + 1] - 1, at
    // t = (s - first[p]) dt. (A table of every step cost 16 bytes each, 199 GiB at a 1e-10 s
    // step, and 13 s to build while a Ctrl-C waited.)
    std::vector<std::size_t> first{0};
    for (std::size_t p = 0; p < path.passes(); ++p)
      first.push_back(first.back() + static_cast<std::size_t>(std::ceil(path.pass(p).t_end / dt)) +
                      1);
    const std::size_t total_steps = first.back();

    const unsigned threads = std::max(1u, std::min<unsigned>(rq.threads, 64));
    std::vector<HeightMap> maps(threads, map);
    std::vector<std::uint64_t> points(threads, 0), updates(threads, 0);
    auto work = [&](unsigned w) {
      HeightMap& m = maps[w];
      EdgePoints edge(tool);
      if (!windowed(tool)) edge.whole(speed, dw);
      const std::size_t begin = total_steps * w / threads, end = total_steps * (w + 1) / threads;
      std::size_t p = static_cast<std::size_t>(std::upper_bound(first.begin(), first.end(), begin) -
                                               first.begin() - 1);
      for (std::size_t s = begin; s < end && !rq.stopped(); ++s) {
        while (s >= first[p + 1]) ++p;
        const double t = static_cast<double>(s - first[p]) * dt;
        const Vec3 centre = path.centre(p, t);
        if (reach.beyond(centre)) continue;
        const double spindle = path.spindle_angle(p, t);
        if (windowed(tool)) {
          // The contact's polar angle about the axis: |lambda| for the paper's vertical tool.
          const double lambda = path.contact_angle(p, t);
          const double lo = std::max(0.0, lambda - margin_ * rq.kappa);
          const double hi = std::min(M_PI / 2, lambda + margin_ * rq.kappa);
          edge.fill(lo, hi,
                    std::max(1, static_cast<int>(std::ceil((hi - lo) * R / dw))));  // Eq. 44
        }
        // A tilted tool's edge points are turned from its frame (identity when vertical).
        const bool vertical = path.pass(p).posture.vertical();
        const Eigen::Matrix3d frame = path.tool_frame(p, t);
        for (int tooth = 0; tooth < tool.teeth(); ++tooth) {
          const double theta = tool.tooth_angle(tooth) + spindle;
          // Per-edge runout: edge K farther out and higher by K steps (none: no change at all).
          const double out = runout.edge_radial * tooth, up = runout.edge_axial * tooth;
          for (std::size_t e = 0; e < edge.ring.size(); ++e) {
            // Same point as tool.edge_point(tooth, alpha, spindle), with per-alpha terms hoisted.
            const double phi = theta + edge.lag[e];
            const double rho = per_edge ? edge.ring[e] + out : edge.ring[e];
            double qx = rho * std::cos(phi), qy = rho * std::sin(phi),
                   qz = per_edge ? edge.depth[e] + up : edge.depth[e];
            if (!vertical) {
              const Vec3 turned = frame * Vec3(qx, qy, qz);
              qx = turned.x(), qy = turned.y(), qz = turned.z();
            }
            qx += centre.x(), qy += centre.y(), qz += centre.z();
            ++points[w];
            const double fi = std::round((qx - g.x0) / g.dx);
            const double fj = std::round((qy - g.y0) / g.dy);
            if (fi < 0 || fj < 0 || fi >= static_cast<double>(g.nx) ||
                fj >= static_cast<double>(g.ny))
              continue;
            double& z = m.at(static_cast<std::size_t>(fi), static_cast<std::size_t>(fj));
            if (qz < z) {
              z = qz;
              ++updates[w];
            }
          }
        }
        if (w == 0 && rq.progress && (s - begin) % 4096 == 0)
          rq.progress(static_cast<double>(s - begin) / static_cast<double>(end - begin + 1));
      }
    };
    std::vector<std::thread> pool;
    for (unsigned w = 1; w < threads; ++w) pool.emplace_back(work, w);
    work(0);
    for (auto& th : pool) th.join();

    // Min-reduction: exact, so the map is the same for any thread count.
    for (std::size_t i = 0; i < map.z.size(); ++i)
      for (const auto& m : maps) map.z[i] = std::min(map.z[i], m.z[i]);
    std::uint64_t total_points = 0, total_updates = 0;
    for (unsigned w = 0; w < threads; ++w) total_points += points[w], total_updates += updates[w];
    counts["time_steps"] = total_steps;
    counts["edge_points"] = total_points;
    counts["updates"] = total_updates;
    counts["time_step_ns"] = static_cast<std::uint64_t>(dt * 1e9);
  }

 private:
  double margin_, time_step_, time_fraction_, edge_fraction_;
};

}  // namespace topomill::plugins

TOPOMILL_PLUGIN("zmap", "0.1.0") {
  registrar.add<topomill::TopographyEvaluator, topomill::plugins::ZMap>(
      "zmap",
      "The paper's Z-map: nearest node, CATW-limited edge points, Eq. 46 time step "
      "(reference evaluator)");
}
