// tooth_passage's centre table: the length of the correction's path in plan over a span (from
// prefix sums, the end pieces in proportion), which bounds how far a correction's jerks can turn
// the phase over a piece (PassageGeometry::Span::sweep). Checked against the path summed here in
// small steps: never shorter (a bound), and no longer than round-off.
#include <catch2/catch.hpp>
#include <cmath>
#include <memory>
#include <random>

#include "fixtures/flat_surface.hpp"
#include "tooth_passage/centre_table.hpp"

using topomill::Vec3;

TEST_CASE("centre table: the correction's path length over any span equals a fine sum",
          "[tooth_passage]") {
  // One straight pass of 0.01 s along X; a correction of 200 samples 50 us apart whose steps
  // are mostly small with a few jerks (a hundred times longer), as deflection steps are.
  std::vector<topomill::ToolPath::Pass> passes(1);
  passes[0].waypoints = {{Vec3(0, 0, 1), Vec3::UnitZ(), 10.0},
                         {Vec3(0.1, 0, 1), Vec3::UnitZ(), 10.0}};
  topomill::ToolPath path(std::make_shared<fixtures::FlatSurface>(), 1.0, 10.0, 400.0, passes);
  std::mt19937 rng(11);
  std::normal_distribution<double> step(0, 1e-4);
  const double dt = 5e-5;
  std::vector<Vec3> samples{Vec3::Zero()};
  for (int k = 1; k < 200; ++k) {
    const double scale = k % 37 == 0 ? 100 : 1;
    samples.push_back(samples.back() + scale * Vec3(step(rng), step(rng), step(rng)));
  }
  path.set_correction(0, dt, samples);
  const topomill::plugins::CentreTable table(path, 0, 0.0, path.pass(0).t_end, 1e-7);
  // The plan path from ta to tb in steps of a hundredth of a sample: exact on the linear pieces
  // but for the one step across each knot, which cuts its corner (shorter).
  auto fine = [&](double ta, double tb) {
    double sum = 0;
    Vec3 prev = path.correction(0, ta);
    const int n = std::max(1, static_cast<int>(std::ceil((tb - ta) / (dt / 100))));
    for (int i = 1; i <= n; ++i) {
      const Vec3 c = path.correction(0, ta + (tb - ta) * i / n);
      sum += std::hypot(c.x() - prev.x(), c.y() - prev.y());
      prev = c;
    }
    return sum;
  };
  std::uniform_real_distribution<double> time(-2e-3, 0.012);  // before the first, past the last
  for (int q = 0; q < 300; ++q) {
    double ta = time(rng), tb = q % 3 == 0 ? ta + 0.3 * dt : time(rng);  // within one piece too
    if (ta > tb) std::swap(ta, tb);
    const double want = fine(ta, tb), got = table.correction_length(ta, tb);
    INFO("[" << ta << ", " << tb << "]: summed " << want << ", table " << got);
    CHECK(got >= want);
    // The fine sum cuts each knot's corner by at most a hundredth of the pieces either side:
    // 2 % of the length in all.
    CHECK(got <= want / 0.98 + 1e-9);
  }
  CHECK(table.correction_length(3e-3, 3e-3) == 0);
  CHECK(table.correction_length(0.02, 0.03) < 1e-9);  // held beyond the last sample
}
