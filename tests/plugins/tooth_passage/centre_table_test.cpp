// tooth_passage's centre table: the length of the correction's path in plan over a span (from
// prefix sums, the end pieces in proportion), which bounds how far a correction's jerks can turn
// the phase over a piece (PassageGeometry::Span::sweep), checked against the path summed here in
// small steps: never shorter (a bound), and no longer than round-off. The correction's box and
// top speeds over a span (one range-table query), checked against a scan of its samples. And the
// nominal centre's lowest height over a span, the exact windows' floor, against a dense scan.
#include <catch2/catch.hpp>
#include <cmath>
#include <memory>
#include <random>
#include <string>

#include "fixtures/flat_surface.hpp"
#include "support/builtin_models.hpp"
#include "tooth_passage/centre_table.hpp"

using topomill::Vec3;

namespace {
// One straight pass of 0.01 s along X; a correction of 200 samples 50 us apart whose steps are
// mostly small with a jerk (a hundred times longer) every `jerk` samples, as deflection steps are.
struct JerkyPass {
  static constexpr double dt = 5e-5;
  topomill::ToolPath path;
  std::vector<Vec3> samples{Vec3::Zero()};
  std::mt19937 rng;
  JerkyPass(unsigned seed, int jerk)
      : path(std::make_shared<fixtures::FlatSurface>(), 1.0, 10.0, 400.0, passes()), rng(seed) {
    std::normal_distribution<double> step(0, 1e-4);
    for (int k = 1; k < 200; ++k) {
      const double scale = k % jerk == 0 ? 100 : 1;
      samples.push_back(samples.back() + scale * Vec3(step(rng), step(rng), step(rng)));
    }
    path.set_correction(0, dt, samples);
  }
  static std::vector<topomill::ToolPath::Pass> passes() {
    std::vector<topomill::ToolPath::Pass> p(1);
    p[0].waypoints = {{Vec3(0, 0, 1), Vec3::UnitZ(), 10.0}, {Vec3(0.1, 0, 1), Vec3::UnitZ(), 10.0}};
    return p;
  }
};
}  // namespace

TEST_CASE("centre table: the correction's path length over any span equals a fine sum",
          "[tooth_passage]") {
  JerkyPass jp(11, 37);
  const topomill::ToolPath& path = jp.path;
  std::mt19937& rng = jp.rng;
  const double dt = JerkyPass::dt;
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

TEST_CASE("centre table: the correction's box and top speeds over any span equal a scan",
          "[tooth_passage]") {
  // The box and the speeds over a span come from one walk of the range table
  // (CentreTable::correction_bounds). Expected: the correction's extremes over the span, from its
  // samples inside and its values at the ends (it is linear between samples), and the largest
  // slope of the pieces the span overlaps, both found here by a scan. A piece that starts where
  // the span ends is not in it.
  JerkyPass jp(5, 29);
  const topomill::ToolPath& path = jp.path;
  const std::vector<Vec3>& samples = jp.samples;
  std::mt19937& rng = jp.rng;
  const double dt = JerkyPass::dt;
  const topomill::plugins::CentreTable table(path, 0, 0.0, path.pass(0).t_end, 1e-7);
  // (Pieces within `slack` of the span count as overlapping it: a knot's time over the step may
  // round to just past the knot, and the table then takes the piece after it too.)
  auto scan = [&](double ta, double tb, Vec3& lo, Vec3& hi, double& v_xy, double& v_z,
                  double slack) {
    lo = hi = path.correction(0, ta);
    auto take = [&](const Vec3& c) { lo = lo.cwiseMin(c), hi = hi.cwiseMax(c); };
    take(path.correction(0, tb));
    v_xy = v_z = 0;
    for (std::size_t k = 0; k < samples.size(); ++k) {
      const double t = static_cast<double>(k) * dt;
      if (t > ta && t < tb) take(samples[k]);
      // Piece k, [t, t + dt], overlaps the span.
      if (k + 1 < samples.size() && t < tb + slack && t + dt > ta - slack) {
        const Vec3 d = (samples[k + 1] - samples[k]) / dt;
        v_xy = std::max(v_xy, std::hypot(d.x(), d.y())), v_z = std::max(v_z, std::abs(d.z()));
      }
    }
  };
  std::uniform_real_distribution<double> time(-2e-3, 0.012);
  std::uniform_int_distribution<int> knot(0, 199);
  for (int q = 0; q < 400; ++q) {
    double ta = time(rng), tb = time(rng);
    if (q % 4 == 1) ta = knot(rng) * dt;  // ends on knots, as crossings_in cuts
    if (q % 4 == 2) tb = knot(rng) * dt;
    if (q % 4 == 3) tb = ta + 0.3 * dt;  // within one piece
    if (ta > tb) std::swap(ta, tb);
    Vec3 lo, hi, unused_lo, unused_hi;
    double v_xy, v_z, v_xy_wide, v_z_wide;
    scan(ta, tb, lo, hi, v_xy, v_z, 0.0);
    scan(ta, tb, unused_lo, unused_hi, v_xy_wide, v_z_wide, 1e-9 * dt);  // its speeds only
    const topomill::plugins::CorrectionBounds got = table.correction_bounds(ta, tb);
    INFO("[" << ta / dt << ", " << tb / dt << "] samples");
    // The table's box holds the scan's (it is the samples' range, the ends rounded out to
    // samples), its speeds the scan's top speeds.
    for (int c = 0; c < 3; ++c) {
      CHECK(got.lo[c] <= lo[c]);
      CHECK(got.hi[c] >= hi[c]);
    }
    CHECK(got.speed_xy >= v_xy * (1 - 1e-12));
    CHECK(got.speed_z >= v_z * (1 - 1e-12));
    // Tight: a span inside one piece has that piece's speed; a span from knot to knot its
    // pieces' top speed (not the next piece's, but where the knot's time rounds past it).
    CHECK(got.speed_xy <= v_xy_wide * (1 + 1e-12) + 1e-12);
    CHECK(got.speed_z <= v_z_wide * (1 + 1e-12) + 1e-12);
  }
}

TEST_CASE("centre table: the nominal centre's lowest height over a span bounds a dense scan",
          "[tooth_passage]") {
  // A pass over the curvature of a convex arc of radius 2 mm, and of a concave one of 3 mm (its
  // lowest heights inside spans): the centre's height is a circle's, tabulated as cubics. Over any
  // span the lowest height must lie at or below every height the table gives inside it (the floor
  // the exact windows rule pieces out by); within one cubic it is that cubic's own least, to
  // round-off (an end or where its slope vanishes), so that next to the tip a piece's floor equals
  // the tip's height. Expected: the least of 2001 heights taken evenly over the span.
  const std::string shape = GENERATE(std::string("convex_arc"), std::string("concave_arc"));
  const auto arc = testing::make_model<topomill::SurfaceShape>(
      shape, {{"radius", shape == "convex_arc" ? 2.0 : 3.0}});
  std::vector<topomill::ToolPath::Pass> passes(1);
  passes[0].y_start = -1.47, passes[0].t_end = 0.3, passes[0].dx = 0, passes[0].dy = 1;
  const topomill::ToolPath path(arc, 1.0, 10.0, 400.0, passes);
  const topomill::plugins::CentreTable table(path, 0, 0.0, 0.3, 1e-7);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> time(0.0, 0.3), length(0.0, 1.0);
  // Half the spans start within three cubics before the centre's lowest point on the pass (the
  // concave arc's bottom, 0.147 s in: not on a knot), so that many hold it.
  double t_low = 0;
  for (int i = 0; i <= 3000; ++i)
    if (const double t = 0.3 * i / 3000; table.nominal(t).z() < table.nominal(t_low).z()) t_low = t;
  const double cubic = table.cubic_span(t_low).second - table.cubic_span(t_low).first;
  int inside = 0, holds = 0;
  for (int q = 0; q < 600; ++q) {
    const double ta = q % 2 ? time(rng) : std::max(0.0, t_low - 3 * cubic * length(rng));
    const auto [c0, c1] = table.cubic_span(ta);
    // A third of the spans within ta's cubic, a third up to ten cubics long, the rest longer.
    const double tb = std::min(0.3, q % 3 == 0   ? ta + (c1 - ta) * length(rng)
                                    : q % 3 == 1 ? ta + 10 * (c1 - c0) * length(rng)
                                                 : ta + 0.05 * length(rng));
    double dense = INFINITY;
    for (int i = 0; i <= 2000; ++i)
      dense = std::min(dense, table.nominal(ta + (tb - ta) * i / 2000).z());
    const double got = table.nominal_lowest_z(ta, tb, table.nominal(ta).z(), table.nominal(tb).z());
    INFO(shape << ", span [" << ta << ", " << tb << "] s, cubic [" << c0 << ", " << c1 << "]");
    CHECK(got <= dense + 1e-15);
    if (tb <= c1) {
      ++inside;
      holds += ta < t_low && tb > t_low;
      CHECK(got >= dense - 1e-11);  // the scan may step over the least by its curvature
    }
  }
  CHECK(inside >= 200);
  if (shape == "concave_arc") CHECK(holds >= 10);  // spans within one cubic holding the bottom
}
