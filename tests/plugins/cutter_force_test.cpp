// The Armarego force on the cutters other than the ball end: the classical mean slotting force of
// a cylindrical end mill (Altintas, Manufacturing Automation, Sec. 2.4, integrated over a
// revolution), the ball end's force at r = D/2, and what a per-edge runout moves.
#include <catch2/catch.hpp>
#include <cmath>

#include "support/builtin_models.hpp"
#include "topomill/force_model.hpp"
#include "topomill/tool_geometry.hpp"

using testing::make_model;
using topomill::CutState;
using topomill::ForceModel;
using topomill::ToolGeometry;
using topomill::Vec3;

namespace {
constexpr double kKtc = 2000, kKrc = 800, kKac = 500, kKte = 30, kKre = 20, kKae = 10;

std::shared_ptr<ForceModel> force() {
  return make_model<ForceModel>("armarego", {{"Ktc", kKtc},
                                             {"Krc", kKrc},
                                             {"Kac", kKac},
                                             {"Kte", kKte},
                                             {"Kre", kKre},
                                             {"Kae", kKae},
                                             {"element_angle", 0.5}});
}

// A full slot fed along +Y: every element facing the feed cuts (no material test).
CutState slot(double spindle_rate, double ap) {
  CutState st;
  st.feed_direction = Vec3(0, 1, 0);
  st.feed_per_tooth = 0.05;
  st.alpha_min = 0;
  st.alpha_max = M_PI / 2;
  st.spindle_rate = spindle_rate;
  st.depth_of_cut = ap;
  return st;
}

// The force averaged over a revolution, sampled evenly.
Vec3 mean_force(const ForceModel& f, const ToolGeometry& tool, CutState st) {
  constexpr int kSamples = 7200;
  Vec3 sum = Vec3::Zero();
  for (int k = 0; k < kSamples; ++k) {
    st.spindle_angle = 2 * M_PI * k / kSamples;
    sum += f.evaluate(tool, st).force;
  }
  return sum / kSamples;
}
}  // namespace

TEST_CASE("a sharp flat end's mean slotting force is the classical closed form",
          "[force][cutter]") {
  // An element at immersion phi (chip fz sin(phi) over phi in [0, pi]) pushes the tool by
  // -(Ktc fz sin + Kte) v - (Krc fz sin + Kre) n - (Kac fz sin + Kae) z per mm of flute; averaged
  // over a revolution for N teeth and ap mm (straight flutes, where the edge is the axial length):
  // N ap / (2 pi) (s (pi/2 Ktc fz + 2 Kte), -(pi/2 Krc fz + 2 Kre), -(2 Kac fz + pi Kae)), with
  // s the spindle's sense, the feed along +Y.
  const double ap = 1.2, fz = 0.05;
  auto tool =
      make_model<ToolGeometry>("flat_end", {{"diameter", 8}, {"teeth", 3}, {"helix_angle", 0}});
  for (const double s : {1.0, -1.0}) {
    INFO("sense " << s);
    const Vec3 f = mean_force(*force(), *tool, slot(s * 100, ap));
    const double k = 3 * ap / (2 * M_PI);
    CHECK(f.x() == Approx(k * s * (M_PI / 2 * kKtc * fz + 2 * kKte)).epsilon(2e-3));
    CHECK(f.y() == Approx(-k * (M_PI / 2 * kKrc * fz + 2 * kKre)).epsilon(2e-3));
    CHECK(f.z() == Approx(-k * (2 * kKac * fz + M_PI * kKae)).epsilon(2e-3));
  }
}

TEST_CASE("a helix leaves the mean slotting force's chip part alone", "[force][cutter]") {
  // A helix turns each slice of the flute by its own angle: over a revolution the chip's part of
  // the mean is the same; the edge's part grows with the edge's length, 1 / cos(helix).
  auto straight =
      make_model<ToolGeometry>("flat_end", {{"diameter", 8}, {"teeth", 2}, {"helix_angle", 0}});
  auto helical =
      make_model<ToolGeometry>("flat_end", {{"diameter", 8}, {"teeth", 2}, {"helix_angle", 30}});
  auto chip_only = make_model<ForceModel>(
      "armarego",
      {{"Ktc", kKtc}, {"Krc", kKrc}, {"Kac", kKac}, {"Kte", 0}, {"Kre", 0}, {"Kae", 0}});
  const Vec3 a = mean_force(*chip_only, *straight, slot(-100, 2.0));
  const Vec3 b = mean_force(*chip_only, *helical, slot(-100, 2.0));
  CHECK((a - b).norm() == Approx(0).margin(2e-3 * a.norm()));
}

TEST_CASE("a bull-nose with r = D/2 pushes as the ball end does, to the bit", "[force][cutter]") {
  auto ball = make_model<ToolGeometry>("ball_end_constant_lead",
                                       {{"radius", 4}, {"teeth", 2}, {"helix_angle", 30}});
  auto bull = make_model<ToolGeometry>(
      "bull_nose", {{"diameter", 8}, {"corner_radius", 4}, {"teeth", 2}, {"helix_angle", 30}});
  CutState st = slot(-100, 0.5);
  st.alpha_max = 0.6;
  for (double angle : {0.0, 0.4, 2.9}) {
    st.spindle_angle = angle;
    const auto a = force()->evaluate(*ball, st), b = force()->evaluate(*bull, st);
    CHECK(a.force == b.force);
    CHECK(a.load_centre == b.load_centre);
  }
}

TEST_CASE("a per-edge radial step moves chip from one edge to the next, not the mean",
          "[force][cutter][runout]") {
  // Edge 1 eps_r farther out than edge 0 cuts eps_r more chip, edge 0 eps_r less: over a
  // revolution of a 2-tooth slot the chip's sum is the same while both still cut. Edge 1 alone
  // in cut at immersion 90 deg: its tangential force grows by Ktc eps_r ap.
  auto tool =
      make_model<ToolGeometry>("flat_end", {{"diameter", 8}, {"teeth", 2}, {"helix_angle", 0}});
  auto chip_only = make_model<ForceModel>(
      "armarego", {{"Ktc", kKtc}, {"Krc", 0}, {"Kac", 0}, {"Kte", 0}, {"Kre", 0}, {"Kae", 0}});
  CutState even = slot(100, 1.0), stepped = slot(100, 1.0);
  stepped.edge_radial = 0.01;
  CHECK((mean_force(*chip_only, *tool, even) - mean_force(*chip_only, *tool, stepped)).norm() ==
        Approx(0).margin(1e-3 * mean_force(*chip_only, *tool, even).norm()));
  // Turned so that edge 1 points along the feed (+Y): its chip is fz + eps_r, and edge 0,
  // pointing back, cuts none.
  even.spindle_angle = stepped.spindle_angle = -M_PI / 2;
  const double grow = chip_only->evaluate(*tool, stepped).force.norm() -
                      chip_only->evaluate(*tool, even).force.norm();
  CHECK(grow == Approx(kKtc * 0.01 * 1.0).epsilon(1e-9));
}

TEST_CASE("a bull-nose's edge force is Kte times the length of its edge in cut",
          "[force][cutter]") {
  // Edge forces alone: each element in cut (phi in [0, pi]) pushes Kte ds against the cutting
  // direction, which averages to 2 s / (2 pi) along +X over a revolution; so the mean is
  // s N Kte L / pi, L the edge's length over [0, alpha_max]: on the corner's tube, whose element
  // runs r d(alpha) along the section and rho dPsi round the axis (rho = c + r sin(alpha), Psi =
  // tan(gamma) r cos(alpha) / (D/2)), integrated here by the midpoint rule on a fine grid.
  const double D = 8, r = 2, c = D / 2 - r, gamma = 40 * M_PI / 180, top = 0.8;
  auto tool = make_model<ToolGeometry>(
      "bull_nose", {{"diameter", D}, {"corner_radius", r}, {"teeth", 3}, {"helix_angle", 40}});
  auto edge_only = make_model<ForceModel>("armarego", {{"Ktc", 0},
                                                       {"Krc", 0},
                                                       {"Kac", 0},
                                                       {"Kte", kKte},
                                                       {"Kre", 0},
                                                       {"Kae", 0},
                                                       {"element_angle", 0.1}});
  double length = 0;
  constexpr int kSteps = 100000;
  for (int k = 0; k < kSteps; ++k) {
    const double a = (k + 0.5) * top / kSteps, rho = c + r * std::sin(a);
    const double turn = std::tan(gamma) * r * std::sin(a) / (D / 2);  // |dPsi / d(alpha)|
    length += std::hypot(r, rho * turn) * top / kSteps;
  }
  CutState st = slot(-100, 0.5);
  st.alpha_max = top;
  const Vec3 f = mean_force(*edge_only, *tool, st);
  CHECK(f.x() == Approx(-3 * kKte * length / M_PI).epsilon(2e-3));
}
