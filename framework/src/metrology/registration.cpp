#include "metrology/registration.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <complex>

#include "interrupt.hpp"
#include "metrology/fft.hpp"
#include "metrology/resample.hpp"
#include "topomill/error.hpp"

namespace topomill {

namespace {
using Vec2 = Eigen::Vector2d;

struct Transform {
  double tx = 0, ty = 0, angle = 0;
  Vec2 o;  // the reference's centre
  Vec2 operator()(double x, double y) const {
    const double c = std::cos(angle), s = std::sin(angle), u = x - o.x(), v = y - o.y();
    return {c * u - s * v + o.x() + tx, s * u + c * v + o.y() + ty};
  }
};

Vec2 centre(const Grid& g) {
  return {g.x0 + 0.5 * static_cast<double>(g.nx - 1) * g.dx,
          g.y0 + 0.5 * static_cast<double>(g.ny - 1) * g.dy};
}

// A field on a padded px x py array, and its spectrum.
struct Padded {
  std::size_t px, py;
  std::vector<double> a;
  Padded(std::size_t x, std::size_t y) : px(x), py(y), a(x * y, 0.0) {}
};

// sum over i of f(i) g(i + d), for every d, by FFT: d at ((d + px) % px, ...).
std::vector<double> cross(const std::vector<std::complex<double>>& F,
                          const std::vector<std::complex<double>>& G, std::size_t px,
                          std::size_t py) {
  std::vector<std::complex<double>> p(F.size());
  for (std::size_t k = 0; k < F.size(); ++k) p[k] = std::conj(F[k]) * G[k];
  auto out = fft_inverse(p, px, py);
  const double n = static_cast<double>(px * py);
  for (double& v : out) v /= n;
  return out;
}

// The measured map's box in plan turned back by `turn`'s angle about its centre o: where the
// reference's lattice nodes whose turned position falls in the measured map lie.
struct Box {
  double lo_x, hi_x, lo_y, hi_y;
};
Box turned_back(const Grid& gm, const Transform& turn) {
  double lo_x = INFINITY, hi_x = -INFINITY, lo_y = INFINITY, hi_y = -INFINITY;
  const double c = std::cos(-turn.angle), s = std::sin(-turn.angle);
  const double xs[2] = {gm.x0, gm.x0 + static_cast<double>(gm.nx - 1) * gm.dx};
  const double ys[2] = {gm.y0, gm.y0 + static_cast<double>(gm.ny - 1) * gm.dy};
  for (double x : xs)
    for (double y : ys) {
      const double u = x - turn.o.x(), v = y - turn.o.y();
      const double bx = c * u - s * v + turn.o.x(), by = s * u + c * v + turn.o.y();
      lo_x = std::min(lo_x, bx), hi_x = std::max(hi_x, bx);
      lo_y = std::min(lo_y, by), hi_y = std::max(hi_y, by);
    }
  return {lo_x, hi_x, lo_y, hi_y};
}

// A whole-node shift of the coarse step: its normalised cross-correlation, the overlap in nodes,
// and the shift in the reference's lattice (mm).
struct Candidate {
  double r, count, tx, ty;
};

// The coarse step's choice: a surface with periodic marks matches itself a period away nearly as
// well as in place, so of the shifts within kTie of the best correlation, the one that keeps the
// most overlap (the nearest in place), then the better correlated; turned into the measurement.
Registration best_shift(const std::vector<Candidate>& candidates,
                        const RegistrationOptions& options, const Surface& meas,
                        const Transform& turn) {
  constexpr double kTie = 0.01;
  double top = -INFINITY;
  for (const auto& c : candidates) top = std::max(top, c.r);
  Registration best;
  best.correlation = -INFINITY;
  double most = -1;
  for (const auto& c : candidates)
    if (c.r >= top - kTie && (c.count > most || (c.count == most && c.r > best.correlation)))
      most = c.count, best.correlation = c.r, best.tx = c.tx, best.ty = c.ty;
  if (candidates.empty())
    throw InputError(
        SourceRef{meas.source}, "",
        "no shift leaves the two maps overlapping by half of the smaller" +
            std::string(options.max_shift > 0 ? " within the largest shift allowed" : "") +
            ": expected maps of the same area of the surface (crop or widen them, "
            "or raise --max-shift)");
  // A shift along the lattice is, in the measurement, that shift turned by the angle.
  const double c = std::cos(turn.angle), s = std::sin(turn.angle);
  const double tx = best.tx, ty = best.ty;
  best.tx = c * tx - s * ty, best.ty = s * tx + c * ty;
  best.angle = turn.angle;
  return best;
}

// Step 1: the whole-node shift (in the reference's lattice) with the best normalised
// cross-correlation, the measurement first turned by `angle` about o.
Registration coarse(const Surface& ref, const Surface& meas, const Transform& turn,
                    const RegistrationOptions& options) {
  const Grid& ga = ref.map.grid;
  const Grid& gm = meas.map.grid;
  // Every k-th node, so that the padded arrays stay below 2^20 values each (18 of them, real and
  // complex: about 150 MB at most). The refinement starts within k nodes and converges from there
  // (the surfaces are smooth over a few nodes; shown on the paper's patch at 1 and 2 um in the
  // commit that set this).
  std::size_t k = 1;
  while ((ga.nx / k + gm.nx / k) * (ga.ny / k + gm.ny / k) * 1.5 > double(1 << 20)) ++k;
  const double hx = ga.dx * static_cast<double>(k), hy = ga.dy * static_cast<double>(k);
  const std::size_t nxa = (ga.nx - 1) / k + 1, nya = (ga.ny - 1) / k + 1;
  // The measurement on the reference's lattice, sampled where the lattice node lands when turned
  // by the angle about o (no shift yet): the lattice nodes whose turned position falls in the
  // measured map's box, found by turning that box back.
  Transform turned = turn;
  turned.tx = turned.ty = 0;
  const Box box = turned_back(gm, turn);
  const double lo_x = box.lo_x, hi_x = box.hi_x, lo_y = box.lo_y, hi_y = box.hi_y;
  const auto ib0 = static_cast<std::ptrdiff_t>(std::floor((lo_x - ga.x0) / hx));
  const auto jb0 = static_cast<std::ptrdiff_t>(std::floor((lo_y - ga.y0) / hy));
  const auto nxb =
      static_cast<std::size_t>(std::ceil((hi_x - ga.x0) / hx) - static_cast<double>(ib0)) + 1;
  const auto nyb =
      static_cast<std::size_t>(std::ceil((hi_y - ga.y0) / hy) - static_cast<double>(jb0)) + 1;
  const std::size_t px = fft_size(nxa + nxb), py = fft_size(nya + nyb);
  Padded A(px, py), A2(px, py), mA(px, py), B(px, py), B2(px, py), mB(px, py);
  double sum = 0, n = 0;
  for (std::size_t j = 0; j < nya; ++j)
    for (std::size_t i = 0; i < nxa; ++i)
      if (const std::size_t q = ga.index(i * k, j * k); ref.is_valid(q))
        sum += ref.map.z[q], n += 1;
  const double mean_a = n > 0 ? sum / n : 0.0;
  const double valid_a = n;
  for (std::size_t j = 0; j < nya; ++j)
    for (std::size_t i = 0; i < nxa; ++i)
      if (const std::size_t q = ga.index(i * k, j * k); ref.is_valid(q)) {
        const double z = ref.map.z[q] - mean_a;
        A.a[j * px + i] = z, A2.a[j * px + i] = z * z, mA.a[j * px + i] = 1;
      }
  const CubicSampler sample(meas);
  double valid_b = 0;
  sum = 0;
  std::vector<double> zb(nxb * nyb, NAN);
  for (std::size_t j = 0; j < nyb; ++j)
    for (std::size_t i = 0; i < nxb; ++i) {
      const double x = ga.x0 + static_cast<double>(ib0 + static_cast<std::ptrdiff_t>(i)) * hx;
      const double y = ga.y0 + static_cast<double>(jb0 + static_cast<std::ptrdiff_t>(j)) * hy;
      const Vec2 m = turned(x, y);
      if (const auto z = sample.at(m.x(), m.y())) zb[j * nxb + i] = *z, sum += *z, valid_b += 1;
    }
  const double mean_b = valid_b > 0 ? sum / valid_b : 0.0;
  for (std::size_t j = 0; j < nyb; ++j)
    for (std::size_t i = 0; i < nxb; ++i)
      if (const double z = zb[j * nxb + i]; !std::isnan(z)) {
        B.a[j * px + i] = z - mean_b, B2.a[j * px + i] = (z - mean_b) * (z - mean_b);
        mB.a[j * px + i] = 1;
      }
  throw_if_interrupted();
  const auto FA = fft_forward(A.a, px, py), FA2 = fft_forward(A2.a, px, py),
             FmA = fft_forward(mA.a, px, py), FB = fft_forward(B.a, px, py),
             FB2 = fft_forward(B2.a, px, py), FmB = fft_forward(mB.a, px, py);
  const auto N = cross(FmA, FmB, px, py), SA = cross(FA, FmB, px, py), SB = cross(FmA, FB, px, py),
             SAA = cross(FA2, FmB, px, py), SBB = cross(FmA, FB2, px, py),
             SAB = cross(FA, FB, px, py);
  const double need = 0.5 * std::min(valid_a, valid_b);
  // Every admissible shift's correlation and overlap; then the choice among them (best_shift).
  std::vector<Candidate> candidates;
  for (std::size_t j = 0; j < py; ++j)
    for (std::size_t i = 0; i < px; ++i) {
      const std::size_t q = j * px + i;
      const double count = std::round(N[q]);
      if (count < need || count < 4) continue;
      // The shift d in array nodes, then in the reference's lattice: a = d + ib0.
      const auto di =
          static_cast<std::ptrdiff_t>(i) - (i >= nxb ? static_cast<std::ptrdiff_t>(px) : 0);
      const auto dj =
          static_cast<std::ptrdiff_t>(j) - (j >= nyb ? static_cast<std::ptrdiff_t>(py) : 0);
      const double tx = static_cast<double>(di + ib0) * hx, ty = static_cast<double>(dj + jb0) * hy;
      if (options.max_shift > 0 && std::hypot(tx, ty) > options.max_shift) continue;
      const double va = SAA[q] - SA[q] * SA[q] / count, vb = SBB[q] - SB[q] * SB[q] / count;
      if (!(va > 0 && vb > 0)) continue;
      candidates.push_back({(SAB[q] - SA[q] * SB[q] / count) / std::sqrt(va * vb), count, tx, ty});
    }
  return best_shift(candidates, options, meas, turn);
}

// MEAS(T(p)) - REF(p) - offset over a set of the reference's nodes where the measurement has a
// height: their sum, sum of squares and count.
struct Residuals {
  double sum = 0, squares = 0;
  std::size_t n = 0;
  double mean() const { return n > 0 ? sum / static_cast<double>(n) : 0.0; }
  double mean_square() const { return n > 0 ? squares / static_cast<double>(n) : INFINITY; }
};
}  // namespace

Registration register_surfaces(const Surface& ref, const Surface& meas,
                               const RegistrationOptions& options) {
  Transform T;
  T.o = centre(ref.map.grid);
  T.angle = options.rotation ? options.angle_guess : 0.0;
  Registration r = coarse(ref, meas, T, options);
  T.tx = r.tx, T.ty = r.ty, T.angle = r.angle;

  // Step 2: Gauss-Newton over (tx, ty[, angle], offset) on at most 2^17 of the reference's
  // valid nodes, spread evenly.
  const Grid& g = ref.map.grid;
  std::vector<std::size_t> nodes;
  for (std::size_t q = 0; q < g.size(); ++q)
    if (ref.is_valid(q)) nodes.push_back(q);
  const std::size_t stride = std::max<std::size_t>(1, nodes.size() >> 17);
  std::vector<std::size_t> used;
  for (std::size_t k = 0; k < nodes.size(); k += stride) used.push_back(nodes[k]);
  const CubicSampler sample(meas);
  const int np = options.rotation ? 3 : 2;  // besides the offset
  const double h = std::min(g.dx, g.dy);
  const double step[3] = {0.01 * h, 0.01 * h, 1e-5};
  auto params = [&](const Transform& t, int p) { return p == 0 ? t.tx : p == 1 ? t.ty : t.angle; };
  auto with = [&](Transform t, int p, double v) {
    (p == 0 ? t.tx : p == 1 ? t.ty : t.angle) = v;
    return t;
  };
  auto residuals = [&](const Transform& t, double offset, const std::vector<std::size_t>& set) {
    Residuals sums;
    for (std::size_t q : set) {
      const Vec2 m = t(g.x(q % g.nx), g.y(q / g.nx));
      if (const auto z = sample.at(m.x(), m.y())) {
        const double d = *z - ref.map.z[q] - offset;
        sums.sum += d, sums.squares += d * d, sums.n += 1;
      }
    }
    return sums;
  };
  auto cost = [&](const Transform& t, double offset) {
    return residuals(t, offset, used).mean_square();
  };
  // The offset's least-squares value at the start: the mean difference.
  double offset = residuals(T, 0.0, used).mean();
  double now = cost(T, offset);
  for (r.iterations = 0; r.iterations < 50; ++r.iterations) {
    throw_if_interrupted();
    Eigen::Matrix4d JtJ = Eigen::Matrix4d::Zero();
    Eigen::Vector4d Jtr = Eigen::Vector4d::Zero();
    for (std::size_t q : used) {
      const double x = g.x(q % g.nx), y = g.y(q / g.nx);
      const Vec2 m = T(x, y);
      const auto z = sample.at(m.x(), m.y());
      if (!z) continue;
      Eigen::Vector4d J = Eigen::Vector4d::Zero();
      bool ok = true;
      for (int p = 0; p < np && ok; ++p) {
        const Vec2 a = with(T, p, params(T, p) + step[p])(x, y);
        const Vec2 b = with(T, p, params(T, p) - step[p])(x, y);
        const auto za = sample.at(a.x(), a.y()), zb = sample.at(b.x(), b.y());
        ok = za && zb;
        if (ok) J[p] = (*za - *zb) / (2 * step[p]);
      }
      if (!ok) continue;
      J[3] = -1;  // d(residual)/d(offset)
      const double res = *z - ref.map.z[q] - offset;
      JtJ += J * J.transpose(), Jtr += J * res;
    }
    if (np == 2) JtJ(2, 2) = 1, Jtr[2] = 0;  // the angle held
    const Eigen::Vector4d delta = -JtJ.ldlt().solve(Jtr);
    if (!delta.allFinite()) break;
    // Halve the step until it lowers the cost (far from the minimum a full step can overshoot).
    double scale = 1;
    Transform next = T;
    double next_offset = offset, next_cost = INFINITY;
    for (int halving = 0; halving < 12; ++halving, scale *= 0.5) {
      next = T;
      next.tx += scale * delta[0], next.ty += scale * delta[1], next.angle += scale * delta[2];
      next_offset = offset + scale * delta[3];
      next_cost = cost(next, next_offset);
      if (next_cost <= now) break;
    }
    if (!(next_cost <= now)) {
      r.converged = true;  // no step lowers the cost: at its minimum to round-off
      break;
    }
    const bool small = std::hypot(scale * delta[0], scale * delta[1]) < 1e-4 * h &&
                       std::abs(scale * delta[2]) < 1e-7;
    T = next, offset = next_offset, now = next_cost;
    if (small) {
      r.converged = true;
      break;
    }
  }
  r.tx = T.tx, r.ty = T.ty, r.angle = T.angle, r.offset = offset;
  // The overlap and the residual over every node of the reference.
  const Residuals all = residuals(T, offset, nodes);
  r.overlap = all.n;
  r.rms = all.n > 0 ? std::sqrt(all.mean_square()) : 0.0;
  return r;
}

Surface align(const Surface& meas, const Surface& ref, const Registration& r) {
  Transform T;
  T.o = centre(ref.map.grid);
  T.tx = r.tx, T.ty = r.ty, T.angle = r.angle;
  Surface out = resample(meas, ref.map.grid, [&](double x, double y) {
    const Vec2 m = T(x, y);
    return std::pair<double, double>{m.x(), m.y()};
  });
  for (std::size_t k = 0; k < out.map.z.size(); ++k)
    if (out.is_valid(k)) out.map.z[k] -= r.offset;
  return out;
}

}  // namespace topomill
