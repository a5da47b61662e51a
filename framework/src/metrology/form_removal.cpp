#include "metrology/form_removal.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <vector>

#include "topomill/error.hpp"
#include "topomill/interrupt.hpp"

namespace topomill {

Form Form::parse(const std::string& text, const std::string& option) {
  Form f;
  if (text == "none") return f;
  if (text == "plane") {
    f.kind = Kind::Plane;
    return f;
  }
  if (text == "arc") {
    f.kind = Kind::Arc;
    return f;
  }
  if (text.rfind("poly:", 0) == 0) {
    try {
      f.order = std::stoi(text.substr(5));
    } catch (...) {
      f.order = 0;
    }
    if (f.order >= 1 && f.order <= 6) {
      f.kind = Kind::Polynomial;
      return f;
    }
  }
  throw InputError(SourceRef{"command line"}, option,
                   "expected none, plane, poly:N (N = 1 to 6) or arc, got '" + text + "'");
}

std::string Form::name() const {
  switch (kind) {
    case Kind::None:
      return "none";
    case Kind::Plane:
      return "plane";
    case Kind::Polynomial:
      return "poly:" + std::to_string(order);
    case Kind::Arc:
      return "arc";
  }
  return "?";
}

namespace {

// Coordinates centred and scaled to [-1, 1] keep the normal equations well conditioned.
struct Frame {
  double cx, cy, sx, sy;
  explicit Frame(const Grid& g)
      : cx(g.x0 + 0.5 * g.dx * (g.nx - 1)),
        cy(g.y0 + 0.5 * g.dy * (g.ny - 1)),
        sx(std::max(0.5 * g.dx * (g.nx - 1), 1e-300)),
        sy(std::max(0.5 * g.dy * (g.ny - 1), 1e-300)) {}
};

// Rows of the least-squares problem reduced at a time (remove_polynomial).
constexpr std::size_t kRowsPerBlock = std::size_t{1} << 16;

Surface remove_polynomial(const Surface& in, int order) {
  const Grid& g = in.map.grid;
  const Frame f(g);
  std::vector<std::pair<int, int>> terms;  // x^a y^b, a + b <= order
  for (int total = 0; total <= order; ++total)
    for (int a = total; a >= 0; --a) terms.push_back({a, total - a});
  const std::size_t n = in.valid_count();
  if (n < terms.size())
    throw InputError(SourceRef{in.source}, "",
                     "too few valid points for a polynomial of order " + std::to_string(order));
  auto basis = [&](std::size_t i, std::size_t j) {
    const double u = (g.x(i) - f.cx) / f.sx, v = (g.y(j) - f.cy) / f.sy;
    Eigen::RowVectorXd r(terms.size());
    for (std::size_t t = 0; t < terms.size(); ++t)
      r(t) = std::pow(u, terms[t].first) * std::pow(v, terms[t].second);
    return r;
  };
  // Least squares by QR a block of rows at a time (TSQR): each block's rows are stacked under the
  // R and Q^T b of the blocks before and reduced again. Orthogonal throughout, as one QR of the
  // whole is, in memory for a block, and a stop request is honoured between blocks (one QR of
  // 5.8 M rows takes 2 s).
  const auto t = static_cast<Eigen::Index>(terms.size());
  const auto block = static_cast<Eigen::Index>(std::min(n, kRowsPerBlock));
  Eigen::MatrixXd R(0, t), A(block, t);
  Eigen::VectorXd y(0), b(block);
  auto reduce = [&](Eigen::Index rows) {
    throw_if_interrupted();
    Eigen::MatrixXd M(R.rows() + rows, t);
    Eigen::VectorXd rhs(M.rows());
    M << R, A.topRows(rows);
    rhs << y, b.head(rows);
    const Eigen::HouseholderQR<Eigen::MatrixXd> qr(M);
    const Eigen::Index keep = std::min(t, M.rows());
    R = qr.matrixQR().topRows(keep).triangularView<Eigen::Upper>();
    y = (qr.householderQ().transpose() * rhs).head(keep);
  };
  Eigen::Index k = 0;
  for (std::size_t j = 0; j < g.ny; ++j)
    for (std::size_t i = 0; i < g.nx; ++i)
      if (in.is_valid(g.index(i, j))) {
        A.row(k) = basis(i, j);
        b(k) = in.map.at(i, j);
        if (++k == block) reduce(k), k = 0;
      }
  if (k > 0) reduce(k);
  const Eigen::VectorXd c = R.colPivHouseholderQr().solve(y);
  Surface out = in;
  for (std::size_t j = 0; j < g.ny; ++j)
    for (std::size_t i = 0; i < g.nx; ++i) out.map.at(i, j) -= basis(i, j).dot(c);
  return out;
}

// The arc of the cross-section (axis along X) as the curve A (y^2 + z^2) + B y + C z + D = 0,
// normalised so that B^2 + C^2 - 4 A D = 1 (Pratt). A = 0 is a straight line: a flat or tilted
// profile is the limit of the family, not a singular fit (the centre-and-radius form fitted a
// wrong circle of huge radius to a flat surface and reported Sa 25 um). A point's signed
// distance from the curve is 2 P / (1 + sqrt(1 + 4 A P)), P the left side (Chernov and Lesort),
// which stays exact as A -> 0. Coordinates are centred and scaled to a unit spread first.
struct Curve {
  double A = 0, B = 0, C = 1, D = 0;
  double distance(double y, double z) const {
    const double P = A * (y * y + z * z) + B * y + C * z + D;
    return 2 * P / (1 + std::sqrt(std::max(0.0, 1 + 4 * A * P)));
  }
  // From the three free parameters (A, D, theta): B = s cos(theta), C = s sin(theta).
  static Curve from(const Eigen::Vector3d& p) {
    const double s = std::sqrt(std::max(0.0, 1 + 4 * p(0) * p(1)));
    return {p(0), s * std::cos(p(2)), s * std::sin(p(2)), p(1)};
  }
};

// Pratt's algebraic fit: the eigenvector of N^-1 M with the smallest non-negative eigenvalue,
// M the moments of (w, y, z, 1), w = y^2 + z^2, N the constraint's matrix.
Curve algebraic_fit(const std::vector<double>& ys, const std::vector<double>& zs) {
  Eigen::Matrix4d M = Eigen::Matrix4d::Zero();
  for (std::size_t k = 0; k < ys.size(); ++k) {
    const Eigen::Vector4d v(ys[k] * ys[k] + zs[k] * zs[k], ys[k], zs[k], 1.0);
    M += v * v.transpose();
  }
  Eigen::Matrix4d Ninv = Eigen::Matrix4d::Zero();
  Ninv(0, 3) = Ninv(3, 0) = -0.5, Ninv(1, 1) = Ninv(2, 2) = 1;
  const Eigen::EigenSolver<Eigen::Matrix4d> es(Ninv * M);
  int best = -1;
  for (int e = 0; e < 4; ++e) {
    const auto lambda = es.eigenvalues()(e);
    if (std::abs(lambda.imag()) > 1e-12 * (1 + std::abs(lambda.real())) ||
        lambda.real() < -1e-12 * M.norm())
      continue;
    if (best < 0 || lambda.real() < es.eigenvalues()(best).real()) best = e;
  }
  Curve c;
  if (best < 0) return c;
  const Eigen::Vector4d a = es.eigenvectors().col(best).real();
  const double norm = a(1) * a(1) + a(2) * a(2) - 4 * a(0) * a(3);
  if (!(norm > 0)) return c;
  const double f = 1 / std::sqrt(norm);
  return {a(0) * f, a(1) * f, a(2) * f, a(3) * f};
}

Surface remove_arc(const Surface& in) {
  const Grid& g = in.map.grid;
  const std::size_t n = in.valid_count();
  if (n < 4) throw InputError(SourceRef{in.source}, "", "too few valid points to fit an arc");
  std::vector<double> ys, zs;
  for (std::size_t j = 0; j < g.ny; ++j)
    for (std::size_t i = 0; i < g.nx; ++i)
      if (in.is_valid(g.index(i, j))) ys.push_back(g.y(j)), zs.push_back(in.map.at(i, j));
  double ym = 0, zm = 0;
  for (std::size_t k = 0; k < n; ++k) ym += ys[k] / n, zm += zs[k] / n;
  double scale = 0;
  for (std::size_t k = 0; k < n; ++k)
    scale = std::max({scale, std::abs(ys[k] - ym), std::abs(zs[k] - zm)});
  if (!(scale > 0)) scale = 1;
  for (std::size_t k = 0; k < n; ++k) ys[k] = (ys[k] - ym) / scale, zs[k] = (zs[k] - zm) / scale;

  // Geometric refinement: Levenberg-Marquardt on the distances over (A, D, theta).
  const Curve start = algebraic_fit(ys, zs);
  Eigen::Vector3d p(start.A, start.D, std::atan2(start.C, start.B));
  auto residuals = [&](const Eigen::Vector3d& q) {
    throw_if_interrupted();  // a pass over every point: a stop is looked at between passes
    const Curve c = Curve::from(q);
    Eigen::VectorXd e(static_cast<Eigen::Index>(n));
    for (std::size_t k = 0; k < n; ++k) e(static_cast<Eigen::Index>(k)) = c.distance(ys[k], zs[k]);
    return e;
  };
  Eigen::VectorXd e = residuals(p);
  double mu = 1e-3;
  for (int it = 0; it < 100; ++it) {
    Eigen::MatrixXd J(static_cast<Eigen::Index>(n), 3);
    for (int a = 0; a < 3; ++a) {
      const double h = 1e-7 * (1 + std::abs(p(a)));
      Eigen::Vector3d hi = p, lo = p;
      hi(a) += h, lo(a) -= h;
      J.col(a) = (residuals(hi) - residuals(lo)) / (2 * h);
    }
    const Eigen::Matrix3d JtJ = J.transpose() * J;
    const Eigen::Vector3d g_ = J.transpose() * e;
    bool improved = false;
    for (int tries = 0; tries < 20 && !improved; ++tries) {
      Eigen::Matrix3d H = JtJ;
      H.diagonal() *= 1 + mu;
      const Eigen::Vector3d step = H.ldlt().solve(-g_);
      const Eigen::VectorXd e_new = residuals(p + step);
      if (e_new.squaredNorm() < e.squaredNorm()) {
        p += step, e = e_new, mu = std::max(mu / 10, 1e-12), improved = true;
        if (step.norm() < 1e-15 * (1 + p.norm())) it = 100;
      } else {
        mu *= 10;
      }
    }
    if (!improved) break;
  }
  const Curve c = Curve::from(p);
  if (!std::isfinite(c.A + c.B + c.C + c.D))
    throw InputError(SourceRef{in.source}, "", "no arc fits these points");
  // Positive residual = above the arc: the sign of the distance's growth with z at the centroid.
  // (At the centroid, the origin, dP/dz is C.)
  const double up = c.C >= 0 ? 1.0 : -1.0;
  Surface out = in;
  for (std::size_t j = 0; j < g.ny; ++j)
    for (std::size_t i = 0; i < g.nx; ++i) {
      const double y = (g.y(j) - ym) / scale, z = (in.map.at(i, j) - zm) / scale;
      out.map.at(i, j) = up * c.distance(y, z) * scale;
    }
  return out;
}

}  // namespace

Surface remove_form(const Surface& surface, const Form& form) {
  switch (form.kind) {
    case Form::Kind::None:
      return surface;
    case Form::Kind::Plane:
      return remove_polynomial(surface, 1);
    case Form::Kind::Polynomial:
      return remove_polynomial(surface, form.order);
    case Form::Kind::Arc:
      return remove_arc(surface);
  }
  return surface;
}

HeightMap unroll_residual(const HeightMap& raw, const SurfaceShape& surface, double depth,
                          double s_lo, double s_hi, double spacing) {
  const Grid& g = raw.grid;
  Grid out_grid = g;
  out_grid.ny = static_cast<std::size_t>(std::llround((s_hi - s_lo) / spacing)) + 1;
  out_grid.dy = (s_hi - s_lo) / static_cast<double>(out_grid.ny - 1);
  out_grid.y0 = s_lo;
  HeightMap out(out_grid);

  std::vector<double> s(g.ny), h(g.ny);
  for (std::size_t i = 0; i < g.nx; ++i) {
    for (std::size_t j = 0; j < g.ny; ++j) {
      const double y = g.y(j), z = raw.at(i, j);
      s[j] = surface.arc_coordinate(y, z);  // where the normal through the point meets the surface
      h[j] = surface.normal_residual(y, z, depth);
    }
    std::size_t j = 0;
    for (std::size_t k = 0; k < out_grid.ny; ++k) {
      const double sk = out_grid.y(k);
      while (j + 2 < g.ny && s[j + 1] < sk) ++j;
      const double w = std::clamp((sk - s[j]) / (s[j + 1] - s[j]), 0.0, 1.0);
      out.at(i, k) = (1 - w) * h[j] + w * h[j + 1];
    }
  }
  return out;
}

}  // namespace topomill
