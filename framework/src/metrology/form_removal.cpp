#include "metrology/form_removal.hpp"

#include <Eigen/Dense>
#include <cmath>

#include "topomill/error.hpp"

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
  Eigen::MatrixXd A(n, terms.size());
  Eigen::VectorXd b(n);
  auto basis = [&](std::size_t i, std::size_t j) {
    const double u = (g.x(i) - f.cx) / f.sx, v = (g.y(j) - f.cy) / f.sy;
    Eigen::RowVectorXd r(terms.size());
    for (std::size_t t = 0; t < terms.size(); ++t)
      r(t) = std::pow(u, terms[t].first) * std::pow(v, terms[t].second);
    return r;
  };
  std::size_t k = 0;
  for (std::size_t j = 0; j < g.ny; ++j)
    for (std::size_t i = 0; i < g.nx; ++i)
      if (in.is_valid(g.index(i, j))) {
        A.row(k) = basis(i, j);
        b(k++) = in.map.at(i, j);
      }
  const Eigen::VectorXd c = A.colPivHouseholderQr().solve(b);
  Surface out = in;
  for (std::size_t j = 0; j < g.ny; ++j)
    for (std::size_t i = 0; i < g.nx; ++i) out.map.at(i, j) -= basis(i, j).dot(c);
  return out;
}

// Circle (yc, zc, radius) through the (y, z) points: algebraic fit (Kasa), then Gauss-Newton on
// the geometric distances.
Surface remove_arc(const Surface& in) {
  const Grid& g = in.map.grid;
  const std::size_t n = in.valid_count();
  if (n < 4) throw InputError(SourceRef{in.source}, "", "too few valid points to fit an arc");
  std::vector<double> ys, zs;
  for (std::size_t j = 0; j < g.ny; ++j)
    for (std::size_t i = 0; i < g.nx; ++i)
      if (in.is_valid(g.index(i, j))) ys.push_back(g.y(j)), zs.push_back(in.map.at(i, j));
  const double y0 = g.y0 + 0.5 * g.dy * (g.ny - 1);
  double z0 = 0;
  for (double z : zs) z0 += z / static_cast<double>(n);
  Eigen::MatrixXd A(n, 3);
  Eigen::VectorXd b(n);
  for (std::size_t k = 0; k < n; ++k) {
    const double y = ys[k] - y0, z = zs[k] - z0;
    A.row(k) << y, z, 1.0;
    b(k) = -(y * y + z * z);
  }
  const Eigen::Vector3d s = A.colPivHouseholderQr().solve(b);
  double yc = -s(0) / 2, zc = -s(1) / 2, r = std::sqrt(std::max(0.0, yc * yc + zc * zc - s(2)));
  if (!(r > 0) || !std::isfinite(r))
    throw InputError(SourceRef{in.source}, "", "no arc fits these points (a plane? use plane)");
  for (int it = 0; it < 50; ++it) {
    Eigen::MatrixXd J(n, 3);
    Eigen::VectorXd e(n);
    for (std::size_t k = 0; k < n; ++k) {
      const double dy = ys[k] - y0 - yc, dz = zs[k] - z0 - zc, d = std::hypot(dy, dz);
      e(k) = d - r;
      J.row(k) << -dy / d, -dz / d, -1.0;
    }
    const Eigen::Vector3d step = J.colPivHouseholderQr().solve(-e);
    yc += step(0), zc += step(1), r += step(2);
    if (step.norm() < 1e-15 * (1 + r)) break;
  }
  const bool convex = zc < 0;  // the centre below the surface
  Surface out = in;
  for (std::size_t j = 0; j < g.ny; ++j)
    for (std::size_t i = 0; i < g.nx; ++i) {
      const double d = std::hypot(g.y(j) - y0 - yc, in.map.at(i, j) - z0 - zc);
      out.map.at(i, j) = convex ? d - r : r - d;
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

}  // namespace topomill
