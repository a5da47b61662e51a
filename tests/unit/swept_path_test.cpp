// What cutter-location data has cut before a moment (SweptPath, the force model's material test
// over CL passes): every earlier pass near the tool, the pass's own earlier loops, never its
// recent trail or a later pass. Checked against the distances written out here.
#include <catch2/catch.hpp>
#include <cmath>
#include <memory>

#include "fixtures/flat_surface.hpp"
#include "swept_path.hpp"

using topomill::Vec3;

namespace {

// Two loops of a circle about the origin at z = 1, radii 1 and 1.3 (one pass), then a line
// (a second pass) far off along X.
topomill::ToolPath loops() {
  std::vector<topomill::ToolPath::Pass> passes(2);
  for (int k = 0; k <= 72; ++k) {
    const double a = 2 * M_PI * (k % 36) / 36, r = k < 36 ? 1.0 : 1.3;
    passes[0].waypoints.push_back(
        {Vec3(r * std::cos(a), r * std::sin(a), 1.0), Vec3::UnitZ(), 1.0});
  }
  passes[1].waypoints = {{Vec3(5, -1, 1), Vec3::UnitZ(), 1.0}, {Vec3(5, 1, 1), Vec3::UnitZ(), 1.0}};
  return topomill::ToolPath(std::make_shared<fixtures::FlatSurface>(), 1.0, 1.0, 100.0, passes);
}

}  // namespace

TEST_CASE("swept path: the pass's earlier loop counts, its recent trail does not", "[cl]") {
  const topomill::ToolPath path = loops();
  const topomill::SweptPath swept(path);
  // On the second loop at angle 0 (waypoint 36): the time is the first loop's length and the
  // jump out; the trail is the last 0.5 of it (at speed 1).
  const auto& w = path.pass(0).waypoints;
  double t = 0;
  for (int k = 0; k < 36; ++k) t += (w[k + 1].centre - w[k].centre).norm();
  const double until = t - 0.5;
  // Points about (1.3, 0, 1) within the ball's reach: swept when within R = 0.5 of a segment of
  // the first loop that the centre left by `until`, by the distances and times here. (The last
  // of the loop, 340 to 350 deg, is left 0.33 before t, across the jump out: the trail.)
  int swept_points = 0, kept_points = 0;
  for (double dx = -0.6; dx <= 0.6; dx += 0.05)
    for (double dy = -0.6; dy <= 0.6; dy += 0.05) {
      const Vec3 x = w[36].centre + Vec3(dx, dy, 0.1);
      bool expected = false;
      double left = 0;
      for (int k = 0; k < 36; ++k) {
        left += (w[k + 1].centre - w[k].centre).norm();
        expected = expected || (left <= until && topomill::SweptPath::distance(
                                                     x, w[k].centre, w[k + 1].centre) < 0.5);
      }
      INFO("point " << x.transpose());
      CHECK(swept.swept(0, until, x, 0.5) == expected);
      ++(expected ? swept_points : kept_points);
    }
  CHECK(swept_points > 50);
  CHECK(kept_points > 50);
  // With the whole pass as the trail, nothing of it counts; the later pass never does.
  CHECK_FALSE(swept.swept(0, -1.0, Vec3(1.0, 0.1, 1), 0.5));
  CHECK_FALSE(swept.swept(0, 1e9, Vec3(5, 0, 1), 0.5));
  // From the second pass, the first is all before it: near (5, 0, 1) none of it is within 0.5,
  // within 4 the outer loop's nearest segments are.
  CHECK_FALSE(swept.swept(1, 0.0, Vec3(5, 0, 1), 0.5));
  CHECK(swept.swept(1, 0.0, Vec3(5, 0, 1), 4.0));
}

TEST_CASE("swept path: distance to a segment", "[cl]") {
  const Vec3 a(0, 0, 0), b(2, 0, 0);
  CHECK(topomill::SweptPath::distance(Vec3(1, 1, 0), a, b) == Approx(1.0));
  CHECK(topomill::SweptPath::distance(Vec3(-3, 4, 0), a, b) == Approx(5.0));  // past an end
  CHECK(topomill::SweptPath::distance(Vec3(5, 0, 4), a, b) == Approx(5.0));
  CHECK(topomill::SweptPath::distance(Vec3(1, 0, 0), a, a) == Approx(1.0));  // a point
}
