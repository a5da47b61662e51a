// Surface shapes: normal, residual and arc length checked against their definitions, by
// numerical differentiation and by construction, for every built-in shape.
#include <catch2/catch.hpp>
#include <cmath>

#include "support/builtin_models.hpp"
#include "topomill/surface_shape.hpp"

using testing::make_model;
using topomill::SurfaceShape;

namespace {
struct Case {
  std::string name;
  std::vector<std::pair<std::string, double>> params;
  double lambda;  // rad, where to probe
};
}  // namespace

TEST_CASE("inclination, residual and arc coordinate agree with the surface's geometry",
          "[surface]") {
  const std::vector<Case> cases = {
      {"convex_arc", {{"radius", 50}}, 0.5},
      {"convex_arc", {{"radius", 3}}, -1.2},
      {"concave_arc", {{"radius", 20}}, 0.3},
      {"inclined_plane", {{"angle", 25}}, 25 * M_PI / 180},
  };
  for (const auto& c : cases) {
    DYNAMIC_SECTION(c.name << " at " << c.lambda) {
      auto s = make_model<SurfaceShape>(c.name, c.params);
      const double y = s->y_at_inclination(c.lambda);
      CHECK(s->inclination(y) == Approx(c.lambda).epsilon(1e-12));
      // The normal (0, sin l, cos l) is perpendicular to the tangent (1, v'(y)).
      const double h = 1e-6;
      const double slope = (s->height(y + h) - s->height(y - h)) / (2 * h);
      CHECK(std::atan2(-slope, 1.0) == Approx(c.lambda).epsilon(1e-7));
      // A point d along the normal from the cut surface (depth 0.3 below) has residual d.
      const double z = s->height(y);
      for (double d : {-0.01, 0.0, 0.002}) {
        const double off = d - 0.3;
        CHECK(s->normal_residual(y + off * std::sin(c.lambda), z + off * std::cos(c.lambda), 0.3) ==
              Approx(d).margin(1e-12));
      }
      // ds/dy = sqrt(1 + v'^2): the arc coordinate is arc length.
      const double ds = (s->arc_coordinate(y + h, s->height(y + h)) -
                         s->arc_coordinate(y - h, s->height(y - h))) /
                        (2 * h);
      CHECK(ds == Approx(std::sqrt(1 + slope * slope)).epsilon(1e-6));
    }
  }
}

TEST_CASE("curvature radius is signed: convex positive, concave negative, plane infinite",
          "[surface]") {
  CHECK(make_model<SurfaceShape>("convex_arc", {{"radius", 50}})->curvature_radius() == 50);
  CHECK(make_model<SurfaceShape>("concave_arc", {{"radius", 20}})->curvature_radius() == -20);
  CHECK(std::isinf(make_model<SurfaceShape>("inclined_plane", {{"angle", 0}})->curvature_radius()));
}
