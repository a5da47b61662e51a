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
    return time_fraction_ * cell /
           (omega * rq.tool->radius() * std::max(std::sin(phi_max_all), 1e-12));
  }

  // Memory: one map per thread. Time: every edge point of every tooth at every step, 30 ns
  // each (measured: 368e6 points in 11.2 s on the paper's lambda = 30 deg scene, one thread),
  // the edge points per tooth from Eq. 44 over the widened contact range at the steepest lambda.
  bool follows(const ToolPath::Posture&) const override { return true; }  // any: it turns points
  bool follows_curves() const override { return true; }  // any: it moves them with the centre

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
    const double points =
        std::ceil((hi - lo) * rq.tool->radius() / (edge_fraction_ * std::min(g.dx, g.dy))) + 1;
    c.seconds = 30e-9 * steps * rq.tool->teeth() * points;
    c.seconds_key = time_step_ > 0 ? "evaluator.time_step"
                                   : "region.spacing (the time step follows it, Eq. 46)";
    return c;
  }

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
      std::vector<double> ring, depth, lag;  // per edge point: R sin(alpha), -R cos(alpha), Psi
      const double tip = tool.min_polar_angle();
      const std::size_t begin = total_steps * w / threads, end = total_steps * (w + 1) / threads;
      std::size_t p = static_cast<std::size_t>(std::upper_bound(first.begin(), first.end(), begin) -
                                               first.begin() - 1);
      for (std::size_t s = begin; s < end && !rq.stopped(); ++s) {
        while (s >= first[p + 1]) ++p;
        const double t = static_cast<double>(s - first[p]) * dt;
        const Vec3 centre = path.centre(p, t);
        const double spindle = path.spindle_angle(p, t);
        // The contact's polar angle about the axis: |lambda| for the paper's vertical tool.
        const double lambda = path.contact_angle(p, t);
        const double lo = std::max(0.0, lambda - margin_ * rq.kappa);
        const double hi = std::min(M_PI / 2, lambda + margin_ * rq.kappa);
        const int n = std::max(1, static_cast<int>(std::ceil((hi - lo) * R / dw)));  // Eq. 44
        ring.resize(n + 1), depth.resize(n + 1), lag.resize(n + 1);
        for (int e = 0; e <= n; ++e) {
          const double alpha = lo + (hi - lo) * e / n;
          ring[e] = R * std::sin(alpha);
          depth[e] = -R * std::cos(alpha);
          lag[e] = tool.lag(std::max(alpha, tip));
        }
        // A tilted tool's edge points are turned from its frame (identity when vertical).
        const bool vertical = path.pass(p).posture.vertical();
        const Eigen::Matrix3d frame = path.tool_frame(p, t);
        for (int tooth = 0; tooth < tool.teeth(); ++tooth) {
          const double theta = tool.tooth_angle(tooth) + spindle;
          for (int e = 0; e <= n; ++e) {
            // Same point as tool.edge_point(tooth, alpha, spindle), with per-alpha terms hoisted.
            const double phi = theta + lag[e];
            double qx = ring[e] * std::cos(phi), qy = ring[e] * std::sin(phi), qz = depth[e];
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
