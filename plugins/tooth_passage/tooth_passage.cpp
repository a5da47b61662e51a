// A fast evaluator with the Z-map's converged answer: for each node, the moments at which a
// tooth's edge crosses the node's vertical line are solved for, and the lowest edge height at
// those moments is kept. The Z-map approximates exactly this min with finite time and edge steps
// (and its nearest-node rounding); here each crossing is found to round-off, so there is no grid
// error at all, only the grid's sampling of the true surface.
//
// For a node at horizontal offset d(t) = node - centre(t) from the ball's axis, the ball point
// above it has polar angle alpha = asin(|d| / R) and height centre_z - sqrt(R^2 - |d|^2). An edge
// of tooth j is over the node when its azimuth theta_j + Psi(alpha) + spindle(t) equals the node's
// azimuth atan2(d): a root of g_j(t) = 0 mod 2 pi, g growing at about the spindle rate. Around the
// time the ball's envelope is lowest over the node, passages are visited outwards until their
// heights rise on both sides, so only the few passages near the ball's bottom are evaluated.
#include <algorithm>
#include <cmath>
#include <thread>

#include "topomill/plugin.hpp"
#include "topomill/topography_evaluator.hpp"

namespace topomill::plugins {

namespace {
constexpr double kTwoPi = 2 * M_PI;

double wrap(double a) {
  return a - kTwoPi * std::floor(a / kTwoPi + 0.5);
}  // to (-pi, pi]
}  // namespace

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
    return s;
  }
  explicit ToothPassage(const Params& p)
      : margin_(p.number("catw_margin")), iterations_(static_cast<int>(p.integer("iterations"))) {}

  void evaluate(const EvaluationRequest& rq, HeightMap& map, WorkCounts& counts) const override {
    const Grid& g = map.grid;
    const unsigned threads = std::max(1u, std::min<unsigned>(rq.threads, 64));
    std::vector<Scratch> scratch(threads);
    std::vector<std::uint64_t> updates(threads, 0);
    // Rows are independent: any split gives the same bits.
    auto work = [&](unsigned w) {
      for (std::size_t j = w; j < g.ny && !rq.stopped(); j += threads) {
        for (std::size_t i = 0; i < g.nx; ++i) {
          double& z = map.at(i, j);
          const double low = node_height(rq, g.x(i), g.y(j), scratch[w]);
          if (low < z) z = low, ++updates[w];
        }
        if (w == 0 && rq.progress) rq.progress(static_cast<double>(j) / g.ny);
      }
    };
    std::vector<std::thread> pool;
    for (unsigned w = 1; w < threads; ++w) pool.emplace_back(work, w);
    work(0);
    for (auto& t : pool) t.join();
    std::uint64_t total_p = 0, total_u = 0;
    for (unsigned w = 0; w < threads; ++w) total_p += scratch[w].visited, total_u += updates[w];
    counts["nodes"] = g.size();
    counts["tooth_passages"] = total_p;
    counts["updates"] = total_u;
  }

 private:
  // Per-worker buffers and counts, so that the per-node work allocates nothing.
  struct Scratch {
    std::vector<std::pair<double, std::size_t>> order;  // (distance across, pass)
    std::vector<double> roots;                          // crossing times in one window
    std::uint64_t visited = 0;                          // tooth passages evaluated
  };

  // The lowest edge height over (x, y) across all passes; +inf when no edge passes over it.
  // Passes are taken nearest first; one whose ball never dips below the best height so far (its
  // envelope's minimum) cannot lower the node and is skipped without solving for passages.
  double node_height(const EvaluationRequest& rq, double x, double y, Scratch& scratch) const {
    const ToolPath& path = *rq.path;
    const double R = rq.tool->radius();
    const double reach = R + path.max_correction();
    const bool along_y = path.feed_axis() == ToolPath::FeedAxis::Y;
    auto& order = scratch.order;
    order.clear();
    for (std::size_t p = 0; p < path.passes(); ++p) {
      const Vec3 c0 = path.nominal_centre(p, 0.0);
      const double across = along_y ? std::abs(x - c0.x()) : std::abs(y - c0.y());
      if (across < reach) order.push_back({across, p});
    }
    std::sort(order.begin(), order.end());
    double best = INFINITY;
    for (const auto& entry : order) {
      const std::size_t p = entry.second;  // (C++17 lambdas cannot capture a binding)
      const double tl = path.pass(p).t_end;
      // When the centre passes the node along the feed: secant steps on a nearly linear function.
      auto along = [&](double t) {
        const Vec3 c = path.nominal_centre(p, t);
        return along_y ? c.y() - y : c.x() - x;
      };
      double t0 = 0, f0 = along(0), t1 = tl, f1 = along(tl);
      if (f0 > reach || f1 < -reach) continue;
      for (int k = 0; k < 8 && f1 != f0; ++k) {
        const double t2 = t1 - f1 * (t1 - t0) / (f1 - f0);
        t0 = t1, f0 = f1, t1 = std::clamp(t2, 0.0, tl), f1 = along(t1);
        if (std::abs(f1) < 1e-12) break;
      }
      best = std::min(best, pass_minimum(rq, p, x, y, t1, best, scratch));
    }
    return best;
  }

  // Visits tooth passages outwards from the one nearest t0 until heights rise on both sides.
  double pass_minimum(const EvaluationRequest& rq, std::size_t p, double x, double y, double t0,
                      double best_so_far, Scratch& scratch) const {
    const ToolPath& path = *rq.path;
    const ToolGeometry& tool = *rq.tool;
    const double R = tool.radius(), omega = path.spindle_rate(), tip = tool.min_polar_angle();
    const double lambda = std::abs(path.surface().inclination(path.surface_y(p, t0)));
    const double lo = std::max(0.0, lambda - margin_ * rq.kappa);
    const double hi = std::min(M_PI / 2, lambda + margin_ * rq.kappa);
    const double period = kTwoPi / std::abs(omega) / tool.teeth();

    // Height and azimuth mismatch of tooth `tooth` at time t.
    struct Probe {
      bool over;      // the node is under the ball, inside the contact range
      double g;       // edge azimuth minus node azimuth, wrapped
      double height;  // ball height above the node
    };
    auto probe = [&](int tooth, double t) {
      const Vec3 c = path.centre(p, t);
      const double dx = x - c.x(), dy = y - c.y(), rho = std::hypot(dx, dy);
      Probe out{false, 0, INFINITY};
      if (rho >= R) return out;
      const double alpha = std::asin(rho / R);
      out.over = alpha >= lo && alpha <= hi;
      out.height = c.z() - std::sqrt(R * R - rho * rho);
      out.g = wrap(tool.tooth_angle(tooth) + tool.lag(std::max(alpha, tip)) +
                   path.spindle_angle(p, t) - std::atan2(dy, dx));
      return out;
    };
    // The crossing of one tooth nearest to `t`: secant iteration on g, started with the spindle
    // rate as the slope (g's other terms, the lag and the node's azimuth, change far slower).
    auto crossing = [&](int tooth, double t) {
      double g_prev = 0, t_prev = t, slope = omega;
      for (int k = 0; k < iterations_; ++k) {
        const double gk = probe(tooth, t).g;
        if (std::abs(gk) < 1e-10) break;
        if (k > 0 && t != t_prev && std::abs(gk - g_prev) < M_PI) {
          const double sec = (gk - g_prev) / (t - t_prev);
          if (std::abs(sec) > 0.1 * std::abs(omega)) slope = sec;
        }
        g_prev = gk, t_prev = t;
        t -= gk / slope;
      }
      return t;
    };

    // Start at the bottom of the ball's envelope over the node (golden section on a height that
    // continues past the ball's rim so that it stays unimodal).
    const double t_end = path.pass(p).t_end;
    auto envelope = [&](double t) {
      const Vec3 c = path.centre(p, t);
      const double rho = std::hypot(x - c.x(), y - c.y());
      return rho < R ? c.z() - std::sqrt(R * R - rho * rho) : c.z() + (rho - R);
    };
    const double speed = std::max(path.feed_speed(), 1e-12);
    double a = std::max(0.0, t0 - 2 * R / speed), b = std::min(t_end, t0 + 2 * R / speed);
    const double ratio = 0.5 * (std::sqrt(5.0) - 1);
    double u = b - ratio * (b - a), v = a + ratio * (b - a), fu = envelope(u), fv = envelope(v);
    while (b - a > 0.05 * period) {
      if (fu < fv)
        b = v, v = u, fv = fu, u = b - ratio * (b - a), fu = envelope(u);
      else
        a = u, u = v, fu = fv, v = a + ratio * (b - a), fv = envelope(v);
    }
    const double t_bottom = 0.5 * (a + b);
    if (envelope(t_bottom) >= best_so_far) return INFINITY;  // this pass cannot lower the node

    // All crossings of one tooth within half a revolution of `guess`. Usually the secant step
    // finds the one crossing there; close to the tool's axis (the node's azimuth then turns fast,
    // at feed / distance) or where it fails, the window is scanned for every sign change of g
    // (skipping the jumps of its wrap at +-pi) and each bracket bisected.
    const double rev = kTwoPi / std::abs(omega);
    const double near_axis = 10 * path.feed_speed() / std::abs(omega);
    auto& roots = scratch.roots;
    auto passages_near = [&](int tooth, double guess) {
      roots.clear();
      const double t = crossing(tooth, guess);
      const Vec3 c = path.centre(p, t);
      const double rho = std::hypot(x - c.x(), y - c.y());
      if (std::abs(probe(tooth, t).g) < 1e-9 && rho > near_axis) {
        roots.push_back(t);
        return;
      }
      constexpr int kSamples = 48;
      double ta = guess - rev / 2, ga = probe(tooth, ta).g;
      for (int k = 1; k <= kSamples; ++k) {
        const double tb = guess - rev / 2 + rev * k / kSamples, gb = probe(tooth, tb).g;
        if ((ga < 0) != (gb < 0) && std::abs(gb - ga) < M_PI) {
          double lo_t = ta, hi_t = tb, lo_g = ga;
          for (int it = 0; it < 50 && hi_t - lo_t > 1e-13 * rev; ++it) {
            const double mid = 0.5 * (lo_t + hi_t), gm = probe(tooth, mid).g;
            if ((gm < 0) == (lo_g < 0))
              lo_t = mid, lo_g = gm;
            else
              hi_t = mid;
          }
          roots.push_back(0.5 * (lo_t + hi_t));
        }
        ta = tb, ga = gb;
      }
    };

    double best = INFINITY;
    for (int tooth = 0; tooth < tool.teeth(); ++tooth) {
      const double t_first = crossing(tooth, t_bottom);
      for (int dir : {+1, -1}) {
        double last = INFINITY;
        int rising = 0;
        for (int m = (dir > 0 ? 0 : 1); m < 100000 && rising < 2; ++m) {
          const double guess = t_first + dir * m * rev;
          if (guess < -rev / 2 || guess > t_end + rev / 2) break;
          passages_near(tooth, guess);
          double lowest = INFINITY;
          for (double t : roots) {
            if (t < 0 || t > t_end) continue;
            const Probe q = probe(tooth, t);
            ++scratch.visited;
            if (!std::isfinite(q.height)) continue;
            if (q.over) best = std::min(best, q.height);
            lowest = std::min(lowest, q.height);
          }
          if (!std::isfinite(lowest)) {  // off the ball: past the node
            if (++rising >= 2) break;
            continue;
          }
          rising = lowest > last ? rising + 1 : 0;
          last = lowest;
        }
      }
    }
    return best;
  }

  double margin_;
  int iterations_;
};

}  // namespace topomill::plugins

TOPOMILL_PLUGIN("tooth_passage", "0.1.0") {
  registrar.add<topomill::TopographyEvaluator, topomill::plugins::ToothPassage>(
      "tooth_passage",
      "Fast evaluator: per node, solves for the tooth passages over it and keeps "
      "the lowest (the Z-map's converged limit, no grid error)");
}
