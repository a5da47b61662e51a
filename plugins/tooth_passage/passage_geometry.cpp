#include "passage_geometry.hpp"

#include <algorithm>

namespace topomill::plugins {

namespace {
// Interpolated centres agree with the path to a nanometre's tenth: far below any grid.
constexpr double kTableTolerance = 1e-7;  // mm
}  // namespace

PassageSetup::PassageSetup(const EvaluationRequest& rq, double margin_, int iterations_)
    : path(rq.path),
      tool(rq.tool),
      R(rq.tool->radius()),
      R2(R * R),
      omega(rq.path->spindle_rate()),
      speed(std::max(rq.path->feed_speed(), 1e-12)),
      rev(kTwoPi / std::abs(omega)),
      period(rev / rq.tool->teeth()),
      near_axis(10 * rq.path->feed_speed() / std::abs(omega)),
      reach(R + rq.path->max_correction()),
      reach_xy(std::sqrt(2.0) * rq.path->max_correction()),
      margin(margin_),
      kappa(rq.kappa),
      iterations(iterations_),
      teeth(rq.tool->teeth()),
      along_y(rq.path->feed_axis() == ToolPath::FeedAxis::Y) {
  for (int j = 0; j < teeth; ++j) tooth_angle.push_back(tool->tooth_angle(j));
  sin_tip = std::sin(tool->min_polar_angle());
  lag_tip = tool->lag(tool->min_polar_angle());
  // A probe may look a revolution beyond either end of a pass.
  const double pad = 2 * rev;
  for (std::size_t p = 0; p < path->passes(); ++p) {
    centre.emplace_back(*path, p, -pad, path->pass(p).t_end + pad, kTableTolerance);
    const Vec3 c0 = path->nominal_centre(p, 0.0);
    line.push_back(along_y ? c0.x() : c0.y());
    // The correction is linear between its samples: its range is that of the samples.
    Vec3 lo = Vec3::Zero(), hi = Vec3::Zero();
    if (const double step = path->correction_step(p); step > 0) {
      lo = hi = path->correction(p, 0.0);
      for (std::size_t k = 1; static_cast<double>(k - 1) * step <= path->pass(p).t_end; ++k) {
        const Vec3 d = path->correction(p, static_cast<double>(k) * step);
        lo = lo.cwiseMin(d), hi = hi.cwiseMax(d);
      }
    }
    shift_lo.push_back(lo), shift_hi.push_back(hi);
    lowest_centre.push_back(centre.back().lowest_z(0.0, path->pass(p).t_end));
    const auto& values = path->correction_samples(p).values;
    piece_speed.emplace_back();
    for (std::size_t k = 0; k + 1 < values.size(); ++k) {
      const Vec3 d = (values[k + 1] - values[k]) / path->correction_step(p);
      piece_speed.back().emplace_back(std::hypot(d.x(), d.y()), std::abs(d.z()));
    }
    nominal_speed.push_back(centre.back().top_speed());
    // The largest speeds over each run of kSpeedWindow + 1 pieces: the fall-rate bound asks for
    // such a run at every root it bounds, where a loop over it cost as much as the rest.
    const auto& pieces = piece_speed.back();
    window_speed.emplace_back(pieces.size());
    for (std::size_t k = 0; k < pieces.size(); ++k) {
      auto m = pieces[k];
      for (std::size_t i = k + 1; i <= std::min(k + kSpeedWindow, pieces.size() - 1); ++i)
        m.first = std::max(m.first, pieces[i].first),
        m.second = std::max(m.second, pieces[i].second);
      window_speed.back()[k] = m;
    }
  }
}

std::pair<double, double> PassageSetup::top_speed(std::size_t p, double ta, double tb) const {
  auto [h, v] = nominal_speed[p];
  const auto& pieces = piece_speed[p];
  if (pieces.empty()) return {h, v};
  const double dt = path->correction_step(p);
  const auto last = static_cast<double>(pieces.size() - 1);
  const auto k0 = static_cast<std::size_t>(std::clamp(std::floor(ta / dt), 0.0, last));
  const auto k1 = static_cast<std::size_t>(std::clamp(std::floor(tb / dt), 0.0, last));
  if (k1 == k0 + kSpeedWindow) {
    const auto& w = window_speed[p][k0];
    return {h + w.first, v + w.second};
  }
  double ch = 0, cv = 0;
  for (std::size_t k = k0; k <= k1; ++k)
    ch = std::max(ch, pieces[k].first), cv = std::max(cv, pieces[k].second);
  return {h + ch, v + cv};
}

double PassageSetup::level_time(std::size_t p, double x, double y) const {
  const double tl = path->pass(p).t_end;
  auto along = [&](double t) {
    const Vec3 c = centre[p].nominal(t);
    return along_y ? c.y() - y : c.x() - x;
  };
  double t0 = 0, f0 = along(0), t1 = tl, f1 = along(tl);
  if (f0 > reach || f1 < -reach) return NAN;  // the pass never comes level with the node
  for (int k = 0; k < 8 && f1 != f0; ++k) {
    const double t2 = t1 - f1 * (t1 - t0) / (f1 - f0);
    t0 = t1, f0 = f1, t1 = std::clamp(t2, 0.0, tl), f1 = along(t1);
    if (std::abs(f1) < 1e-12) break;
  }
  return t1;
}

std::pair<double, double> PassageSetup::contact_radii(std::size_t p, double t) const {
  const double lambda = std::abs(path->surface().inclination(path->surface_y(p, t)));
  const double lo = std::max(0.0, lambda - margin * kappa);
  const double hi = std::min(M_PI / 2, lambda + margin * kappa);
  return {R * std::sin(lo), R * std::sin(hi)};
}

double PassageGeometry::crossing(int tooth, double t, double& slope, Probe& last) const {
  double g_prev = 0, t_prev = t;
  last = {false, INFINITY, INFINITY, INFINITY};
  for (int k = 0; k < s_.iterations; ++k) {
    last = probe(tooth, t);
    const double gk = last.g;
    if (converged(last)) break;
    if (k > 0 && t != t_prev && std::abs(gk - g_prev) < M_PI) {
      const double sec = (gk - g_prev) / (t - t_prev);
      if (std::abs(sec) > 0.1 * std::abs(s_.omega)) slope = sec;
    }
    g_prev = gk, t_prev = t;
    t -= gk / slope;
  }
  return t;
}

// Usually the secant step finds the one crossing there; where the axis comes close to the node
// anywhere in the window (the node's azimuth then turns fast, at feed / distance, and several
// crossings may come in one passage) or where it fails, the window is scanned for every sign
// change of g (skipping the jumps of its wrap at +-pi) and each bracket bisected.
bool PassageGeometry::crossings_near(int tooth, double guess, std::vector<double>& roots,
                                     double below) const {
  roots.clear();
  double slope = s_.omega;
  Probe last{};
  const double t = crossing(tooth, guess, slope, last);
  if (converged(last) && last.rho > s_.near_axis &&
      closest(guess - s_.rev / 2, guess + s_.rev / 2) > s_.near_axis) {
    roots.push_back(t);
    return true;
  }
  // Samples: 48 a revolution on an ideal path; on a corrected one the correction's knots
  // (between them the centre moves smoothly, at a knot its velocity jumps and g can turn back),
  // and the window's ends.
  const double w0 = guess - s_.rev / 2, w1 = guess + s_.rev / 2;
  const double step = s_.path->correction_step(pass_);
  const double k0 = step > 0 ? std::floor(w0 / step) + 1 : 0;  // the first knot after w0
  const int knots = step > 0 ? static_cast<int>(std::ceil(w1 / step) - k0) : 0;  // before w1
  const int kSamples = step > 0 ? knots + 1 : 48, kChunk = 16;
  auto at = [&](int k) {
    if (step <= 0) return w0 + s_.rev * k / kSamples;
    return k == 0 ? w0 : k == kSamples ? w1 : (k0 + k - 1) * step;
  };
  // A span over which the ball's surface above the node (at least the centre's lowest height
  // less the ball's depth below its centre at the node's least distance from the axis) cannot
  // come below `below` holds no crossing that matters and is not probed: near the axis that is
  // most of the window. Spans of 16 samples are ruled out first, then the steps of those that
  // are not.
  auto cannot_lower = [&](double ta, double tb) {
    const double rho = std::max(0.0, closest(ta, tb));
    return rho >= s_.R || table_.lowest_z(ta, tb) - std::sqrt(s_.R2 - rho * rho) >= below;
  };
  double ga = NAN;
  for (int k = 1; k <= kSamples; ++k) {
    if ((k - 1) % kChunk == 0 && cannot_lower(at(k - 1), at(std::min(k - 1 + kChunk, kSamples)))) {
      k += kChunk - 1, ga = NAN;
      continue;
    }
    const double ta = at(k - 1), tb = at(k);
    if (cannot_lower(ta, tb)) {
      ga = NAN;
      continue;
    }
    if (std::isnan(ga)) ga = probe(tooth, ta).g;
    const double gb = probe(tooth, tb).g;
    // Where the axis passes the node within the step, the node's azimuth swings round fast
    // enough that g can dip through zero and back between two samples: g is sampled at the
    // closest approach too (the centre moving straight over a step).
    const double tc = closest_time(ta, tb);
    if (tc > ta && tc < tb) {
      const double gc = probe(tooth, tc).g;
      if (crosses(ga, gc)) roots.push_back(bisect(tooth, ta, tc, ga));
      if (crosses(gc, gb)) roots.push_back(bisect(tooth, tc, tb, gc));
    } else if (crosses(ga, gb)) {
      roots.push_back(bisect(tooth, ta, tb, ga));
    }
    ga = gb;
  }
  return false;
}

double PassageGeometry::bisect(int tooth, double lo, double hi, double g_lo) const {
  for (int it = 0; it < 200 && hi - lo > 1e-13 * s_.rev; ++it) {
    const double mid = 0.5 * (lo + hi), g_mid = probe(tooth, mid).g;
    if ((g_mid < 0) == (g_lo < 0))
      lo = mid, g_lo = g_mid;
    else
      hi = mid;
  }
  return 0.5 * (lo + hi);
}

double PassageGeometry::walk(double t_b, std::vector<double>& roots, std::uint64_t& visited,
                             double below) const {
  const double t_end = this->t_end(), rev = s_.rev;
  // Heights rising twice end a walk only on an ideal path, where they follow the envelope; a
  // correction makes them jump from passage to passage, and only the floor ends the walk.
  const bool by_rise = !s_.path->corrected();
  double best = INFINITY;
  for (int tooth = 0; tooth < s_.teeth; ++tooth) {
    // The windows of a revolution each are laid from the crossing nearest t_b; from t_b itself
    // where the secant went astray (near the axis it can run off anywhere).
    double slope = s_.omega;
    Probe first{};
    double t_first = crossing(tooth, t_b, slope, first);
    if (!converged(first) || std::abs(t_first - t_b) > s_.rev) t_first = t_b;
    for (int dir : {+1, -1}) {
      RiseCount rise;
      bool regular = true;
      for (int m = (dir > 0 ? 0 : 1); m < 100000 && !(by_rise && regular && rise.done()); ++m) {
        const double guess = t_first + dir * m * rev;
        if (guess < -rev / 2 || guess > t_end + rev / 2) break;
        // This window and all later ones lie beyond its near edge: past the bound's bottom (t_b
        // is within a 20th of a tooth period of it), if the bound is too high there, nothing
        // from here on can lower the node.
        const double edge = guess - dir * rev / 2;
        if (m > 0 && dir * (edge - t_b) >= 0.05 * s_.period && bound(edge) >= std::min(best, below))
          break;
        regular = crossings_near(tooth, guess, roots, std::min(best, below)) && regular;
        double lowest = INFINITY;
        for (double t : roots) {
          if (t < 0 || t > t_end) continue;
          const Probe q = probe(tooth, t);
          ++visited;
          if (!std::isfinite(q.height)) continue;
          if (q.over) best = std::min(best, q.height);
          lowest = std::min(lowest, q.height);
        }
        rise.add(lowest);
      }
    }
  }
  return best;
}

}  // namespace topomill::plugins
