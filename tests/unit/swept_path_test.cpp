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
  // jump out.
  const auto& w = path.pass(0).waypoints;
  double t = 0;
  for (int k = 0; k < 36; ++k) t += (w[k + 1].centre - w[k].centre).norm();
  const Vec3 centre = w[36].centre;
  const auto cut = swept.before(0, t, 0.5, centre, 0.5);
  // The first loop's segments near (1.3, 0, 1): those within 0.5 of it that the centre left
  // more than 0.5 (the trail, at speed 1) before t, by the distances and times here. (The last
  // of the loop, 340 to 350 deg, is left 0.33 before t, across the jump out: the trail.)
  std::size_t expected = 0;
  double left = 0;
  for (int k = 0; k < 36; ++k) {
    left += (w[k + 1].centre - w[k].centre).norm();
    expected += left <= t - 0.5 &&
                topomill::SweptPath::distance(centre, w[k].centre, w[k + 1].centre) < 0.5;
  }
  CHECK(expected >= 3);
  CHECK(cut.size() == expected);
  for (const auto& s : cut) CHECK(std::abs(s.first.norm() - std::sqrt(2.0)) < 1e-12);  // r = 1
  // With the whole pass before as "recent", nothing of it counts; the later pass never does.
  CHECK(swept.before(0, t, 1e9, centre, 0.5).empty());
  CHECK(swept.before(0, 1e9, 0.5, Vec3(5, 0, 1), 0.5).empty());
  // From the second pass, the first is all before it: near (5, 0, 1) none of it is within 0.5,
  // within 4 the outer loop's nearest segments are.
  CHECK(swept.before(1, 0.0, 0.5, Vec3(5, 0, 1), 0.5).empty());
  CHECK_FALSE(swept.before(1, 0.0, 0.5, Vec3(5, 0, 1), 4.0).empty());
}

TEST_CASE("swept path: distance to a segment", "[cl]") {
  const Vec3 a(0, 0, 0), b(2, 0, 0);
  CHECK(topomill::SweptPath::distance(Vec3(1, 1, 0), a, b) == Approx(1.0));
  CHECK(topomill::SweptPath::distance(Vec3(-3, 4, 0), a, b) == Approx(5.0));  // past an end
  CHECK(topomill::SweptPath::distance(Vec3(5, 0, 4), a, b) == Approx(5.0));
  CHECK(topomill::SweptPath::distance(Vec3(1, 0, 0), a, a) == Approx(1.0));  // a point
}
