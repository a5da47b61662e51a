// Spindle runout ([runout]): absent or zero it changes no bit; the offset turns with the spindle
// from tooth 1; and on an inclined plane the feed marks it leaves are what the sphere says.
#include <Eigen/Geometry>
#include <catch2/catch.hpp>
#include <cmath>
#include <sstream>

#include "support/brute_force.hpp"
#include "support/scenes.hpp"

using testing::run_scene;

namespace {

const std::string kConvex = "plugin = 'convex_arc'\nradius = 50.0";

// A vertical, helix-free ball end (R 5, two teeth) on a plane inclined at `lambda_deg`, fed up
// and down the slope; the patch a thin strip along the feed through the pass line x = 0.
std::string slope(double lambda_deg, double fz, double length, double spacing) {
  std::ostringstream s;
  s.precision(17);
  s << "[tool]\nplugin = 'ball_end_constant_lead'\nradius = 5.0\nteeth = 2\nhelix_angle = 0\n"
    << "[workpiece]\nplugin = 'inclined_plane'\nangle = " << lambda_deg << "\n"
    << "[cutting]\nspindle_speed = 4000\nfeed_per_tooth = " << fz << "\ndepth_of_cut = 0.3\n"
    << "stepover = 0.3\n"
    << "[region]\nlambda = " << lambda_deg << "\nsize = [" << 2 * spacing << ", " << length
    << "]\nspacing = " << spacing << "\n";
  return s.str();
}

topomill::Prepared prepared(const std::string& scene, const std::vector<std::string>& set = {}) {
  auto doc = topomill::SceneDocument::parse_string(scene, "runout.toml");
  for (const auto& s : set) doc.apply_override(s);
  topomill::PluginCatalog catalog({{topomill::PluginCatalog::builtin_dir(), "built-in"}});
  return topomill::prepare(doc.resolve(catalog), catalog);
}

// The profile along the feed through the pass line: its nodes' plan y and their distances from
// the plane z = -y tan(l) along its normal n = (0, sin l, cos l) (mm).
struct Profile {
  double lambda;
  std::vector<double> y, d;
  // Where the point at plan y, d off the plane, lies along it (along (0, cos l, -sin l)).
  double along(double y_, double d_) const {
    const double z = (d_ - y_ * std::sin(lambda)) / std::cos(lambda);
    return y_ * std::cos(lambda) - z * std::sin(lambda);
  }
};
Profile profile(const topomill::HeightMap& raw, double lambda) {
  Profile p{lambda, {}, {}};
  const std::size_t i = raw.grid.nx / 2;
  REQUIRE(std::abs(raw.grid.x(i)) < 1e-12);
  for (std::size_t j = 0; j < raw.grid.ny; ++j) {
    const double y = raw.grid.y(j);
    p.y.push_back(y);
    p.d.push_back(raw.at(i, j) * std::cos(lambda) + y * std::sin(lambda));
  }
  return p;
}

// The profile's valleys more than `margin` (plan) from its ends, each where along the plane and
// how far off it: the vertex of the parabola through a local minimum and its neighbours (exact
// to (spacing)^2 / 2R at a circle's bottom).
struct Valley {
  double s, d;
};
std::vector<Valley> valleys(const Profile& p, double margin) {
  std::vector<Valley> out;
  for (std::size_t j = 1; j + 1 < p.d.size(); ++j) {
    if (!(p.d[j] < p.d[j - 1] && p.d[j] <= p.d[j + 1])) continue;
    if (p.y[j] - p.y.front() < margin || p.y.back() - p.y[j] < margin) continue;
    const double a = p.d[j - 1], b = p.d[j], c = p.d[j + 1], h = p.y[j + 1] - p.y[j];
    const double u = 0.5 * (a - c) / (a - 2 * b + c);  // in steps from node j
    const double d = b - 0.25 * (a - c) * u;
    out.push_back({p.along(p.y[j] + u * h, d), d});
  }
  return out;
}

}  // namespace

TEST_CASE("no runout and a zero runout give the same bits", "[runout]") {
  const std::string scene = testing::paper_scene(kConvex, 30.0, 0.2, 0.2, 0.01);
  const bool effects = GENERATE(false, true);
  const std::string s = scene + (effects ? testing::dynamics_tables() : "");
  for (const char* evaluator : {"tooth_passage", "zmap"}) {
    INFO(evaluator << (effects ? " with vibration and deflection" : ""));
    const std::string e = std::string("evaluator.plugin=") + evaluator;
    const auto none = run_scene(s, {e});
    const auto zero = run_scene(s, {e, "runout.offset=0"});
    CHECK(none.raw.z == zero.raw.z);
  }
}

TEST_CASE("the runout's offset points along tooth 1 and turns with the spindle", "[runout]") {
  // At any time the ball centre is the runout away from where it is without it, towards tooth
  // 1's edge (its zero-lag azimuth) at angle 0, and at angle 90 deg towards where that edge
  // will be a quarter turn later, whichever way the spindle turns. (The edge's azimuth comes from
  // spindle_angle and tooth_angle, which kinematics_test.cpp checks by the mirror image and the
  // start angle's translation, and tool_geometry_test.cpp against docs/model.md.)
  const std::string scene = testing::paper_scene(kConvex, 30.0, 0.2, 0.2, 0.02);
  const std::string direction = GENERATE(as<std::string>{}, "cw", "ccw");
  const double angle = GENERATE(0.0, 90.0, -30.0);
  const double e = 0.005;
  const auto plain = prepared(scene, {"cutting.spindle_direction=" + direction});
  const auto off = prepared(scene, {"cutting.spindle_direction=" + direction, "runout.offset=0.005",
                                    "runout.angle=" + std::to_string(angle)});
  const auto& a = *plain.layout.path;
  const auto& b = *off.layout.path;
  const double rev = 2 * M_PI / std::abs(a.spindle_rate());
  for (double t : {0.0, 0.0011, 0.0137, 0.05}) {
    const topomill::Vec3 d = b.nominal_centre(0, t) - a.nominal_centre(0, t);
    const double later = t + angle / 360.0 * rev;  // the edge gets there `angle` later
    const double edge = plain.tool->tooth_angle(0) + a.spindle_angle(0, later);
    INFO(direction << ", angle " << angle << " deg, t " << t << " s");
    CHECK(d.x() == Approx(e * std::cos(edge)).margin(1e-12));
    CHECK(d.y() == Approx(e * std::sin(edge)).margin(1e-12));
    CHECK(d.z() == 0.0);
  }
}

TEST_CASE("a tilted tool's runout turns in the plane normal to its axis", "[runout][posture]") {
  // The runout offsets the tool's axis from the spindle's: in the plane normal to the spindle,
  // not in the workpiece's XY plane. Built here: x_t the workpiece's X projected onto that plane,
  // y_t = a x x_t, and the offset e (cos(edge) x_t + sin(edge) y_t), edge as for a vertical tool.
  // Laid in XY instead, it is e (1 - cos 10 deg) = 76 nm off, and no longer normal to a.
  const std::string scene = testing::paper_scene(kConvex, 30.0, 0.2, 0.2, 0.02);
  const std::string posture = GENERATE(as<std::string>{}, "fixed", "normal");
  const std::vector<std::string> tilt{"path.tilt=10", "path.lead=-5", "path.posture=" + posture,
                                      "evaluator.plugin=zmap"};
  auto with_runout = tilt;
  with_runout.insert(with_runout.end(), {"runout.offset=0.005", "runout.angle=25"});
  const auto plain = prepared(scene, tilt), off = prepared(scene, with_runout);
  const auto& a = *plain.layout.path;
  const auto& b = *off.layout.path;
  REQUIRE_FALSE(a.vertical());
  const double e = 0.005, rev = 2 * M_PI / std::abs(a.spindle_rate());
  for (std::size_t p : {std::size_t{0}, a.passes() - 1})
    for (double t : {0.0, 0.0011, 0.0137}) {
      const topomill::Vec3 d = b.nominal_centre(p, t) - a.nominal_centre(p, t);
      const topomill::Vec3 axis = a.axis(p, t);
      const topomill::Vec3 x_t =
          (topomill::Vec3::UnitX() - axis.x() * axis).normalized();  // X less its part along a
      const topomill::Vec3 y_t = axis.cross(x_t);
      const double edge = plain.tool->tooth_angle(0) + a.spindle_angle(p, t + 25.0 / 360.0 * rev);
      const topomill::Vec3 expected = e * (std::cos(edge) * x_t + std::sin(edge) * y_t);
      INFO(posture << ", pass " << p << ", t " << t << " s: offset " << d.transpose()
                   << ", expected " << expected.transpose());
      CHECK((d - expected).norm() < 1e-12);
      CHECK(std::abs(d.dot(axis)) < 1e-12);
    }
}

TEST_CASE("runout's feed marks on a plane follow from the sphere", "[runout][closed-form]") {
  // On the pass line of a vertical, helix-free tool the edge lies in the vertical plane through
  // the feed each time it passes the line, so the profile is the lowest of circles of radius R
  // whose centres are the ball's at those instants: fz apart in plan, tooth after tooth, and
  // with runout e each moved along the feed by e cos(the tooth's angle from the offset).
  // With two teeth and the offset towards tooth 1, tooth 1's circles lie e sin(lambda) nearer
  // the plane (along its normal) and tooth 2's e sin(lambda) farther. The ball meets the plane
  // on the axis's -Y side (z = -y tan(lambda) falls towards +Y), so there the offset moves tooth
  // 1's centre by -e along Y and tooth 2's by +e: fed along +Y, their centres are fz + 2e apart
  // in plan from tooth 1 to tooth 2 and fz - 2e from tooth 2 to tooth 1, and the valleys (below
  // the centres along the normal) p + 2e cos(lambda) and p - 2e cos(lambda) apart along the
  // plane, p = fz / cos(lambda). Tooth 2's circles leave no mark once they pass through the
  // cusps of tooth 1's: with S = sqrt(R^2 - p^2),
  //   (2e)^2 + 2 (2e) S sin(lambda) - p^2 = 0,  e* = (sqrt(S^2 sin^2 + p^2) - S sin) / 2,
  // 1.333 um here; from there on the marks are tooth 1's alone, 2p apart along the plane, and
  // each cusp R - S above the valleys along the normal.
  const double R = 5, fz = 0.1, lambda = 30 * M_PI / 180, spacing = 0.0002;
  const double p = fz / std::cos(lambda), S = std::sqrt(R * R - p * p), sl = std::sin(lambda);
  const double e_star = 0.5 * (std::sqrt(S * S * sl * sl + p * p) - S * sl);
  REQUIRE(e_star == Approx(1.3331e-3).epsilon(1e-3));
  const std::string scene = slope(30, fz, 1.0, spacing);
  const auto none = profile(run_scene(scene).raw, lambda);
  const double base = valleys(none, 0.05).at(1).d;  // every valley alike without runout

  SECTION("below e*, both teeth's valleys, e sin(lambda) either side of none's") {
    const double e = 0.0005;
    const auto v = valleys(profile(run_scene(scene, {"runout.offset=0.0005"}).raw, lambda), 0.05);
    REQUIRE(v.size() >= 5);
    const bool first_deep = v[0].d < v[1].d;
    for (std::size_t k = 0; k < v.size(); ++k) {
      const bool deep = (k % 2 == 0) == first_deep;  // tooth 1's
      INFO("valley " << k << " at s = " << v[k].s << " mm");
      // The parabola's vertex is within 2.5e-8 um of a circle's bottom.
      CHECK(v[k].d == Approx(base + (deep ? -e : e) * sl).margin(1e-9));
      if (k == 0) continue;
      const double gap = v[k].s - v[k - 1].s, shift = 2 * e * std::cos(lambda);
      CHECK(gap == Approx(deep ? p - shift : p + shift).margin(1e-8));
    }
  }
  SECTION("at and above e*, tooth 1's marks alone: period 2 fz, cusps R - S high") {
    const double e = GENERATE_COPY(1.001 * e_star, 0.002, 0.005);
    const auto prof = profile(run_scene(scene, {"runout.offset=" + std::to_string(e)}).raw, lambda);
    const auto v = valleys(prof, 0.05);
    REQUIRE(v.size() >= 3);
    for (std::size_t k = 0; k < v.size(); ++k) {
      INFO("e " << e * 1e3 << " um, valley " << k << " at s = " << v[k].s << " mm");
      CHECK(v[k].d == Approx(base - e * sl).margin(1e-9));
      if (k > 0) CHECK(v[k].s - v[k - 1].s == Approx(2 * p).margin(1e-8));
      if (k == 0) continue;
      // The cusp between: the highest node, within its slope p / S times half a step (along the
      // plane) of the corner.
      double top = -INFINITY;
      for (std::size_t j = 0; j < prof.y.size(); ++j) {
        const double s = prof.along(prof.y[j], prof.d[j]);
        if (s > v[k - 1].s && s < v[k].s) top = std::max(top, prof.d[j]);
      }
      const double step = spacing;  // the nodes' spacing along the plane
      CHECK(top - v[k].d <= R - S + 1e-10);
      CHECK(top - v[k].d >= R - S - p / S * step / 2 - 1e-10);
    }
  }
}

TEST_CASE("tooth_passage cuts a large runout with vibration as the brute force does, to 0.1 nm",
          "[runout][fast]") {
  // The centre tables interpolate the nominal centre to 1e-7 mm; a runout of 50 um turns it on a
  // circle every revolution, where the table's steps are shortest. Against the brute force (its
  // own edge, every crossing bisected; support/brute_force.hpp) at every node of the paper's
  // slope with vibration and deflection: 0.02 nm seen. A table ten times looser gives 0.33 nm.
  const std::string scene =
      testing::paper_scene(kConvex, 30.0, 0.05, 0.05, 0.01) + testing::dynamics_tables();
  const std::vector<std::string> set{"runout.offset=0.05", "evaluator.plugin=tooth_passage"};
  const auto m = prepared(scene, set);
  const auto run = run_scene(scene, set);
  const auto& g = run.raw.grid;
  double worst = 0;
  for (std::size_t j = 0; j < g.ny; ++j)
    for (std::size_t i = 0; i < g.nx; ++i)
      worst = std::max(
          worst, std::abs(run.raw.at(i, j) -
                          testing::brute_force_height(*m.tool, *run.layout.path, g.x(i), g.y(j))));
  INFO("largest difference " << worst * 1e6 << " nm over " << g.size() << " nodes");
  CHECK(g.size() >= 36);
  CHECK(worst < 1e-7);
}
