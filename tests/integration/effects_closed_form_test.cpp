// What vibration, deflection and springback do to the surface, under one fixed load (the
// fixture_constant_force plugin): each moves the tool path by a constant that Eq. 22-33 give in
// closed form, computed here from docs/model.md's formulas. The pipeline's surface must be the
// surface of the ideal path moved by exactly that vector, with its sign, on an inclined plane.
#include <catch2/catch.hpp>
#include <cmath>
#include <sstream>

#include "support/run_command.hpp"
#include "support/scenes.hpp"

namespace {

constexpr double kDeg = M_PI / 180;
constexpr double kR = 5.0, kLambda = 20 * kDeg;  // the ball, the plane's inclination
constexpr double kFx = 30, kFy = -50, kFz = 20;  // N, on the tool

std::string scene(double load_centre, const std::string& effects) {
  std::ostringstream s;
  s.precision(17);
  s << testing::paper_scene("plugin = 'inclined_plane'\nangle = 20.0", 20.0, 0.2, 0.2, 0.01)
    << "[evaluator]\nplugin = 'tooth_passage'\n"
    << "[force]\nplugin = 'fixture_constant_force'\nfx = " << kFx << "\nfy = " << kFy
    << "\nfz = " << kFz << "\nload_centre = " << load_centre << "\n"
    << effects;
  return s.str();
}

// The same scene without effects, its path moved by `d` (mm) everywhere, evaluated as the
// pipeline evaluates.
topomill::HeightMap moved_ideal(const std::string& toml, const topomill::Vec3& d) {
  auto doc = topomill::SceneDocument::parse_string(toml, "moved.toml");
  for (const char* effect : {"vibration", "deflection", "springback"})
    doc.apply_override(std::string(effect) + ".enabled=false");
  topomill::PluginCatalog catalog({{testing::fixture_dir("constant_force"), "--plugin-path"},
                                   {topomill::PluginCatalog::builtin_dir(), "built-in"}});
  topomill::Prepared m = topomill::prepare(doc.resolve(catalog), catalog);
  auto& path = *m.layout.path;
  for (std::size_t p = 0; p < path.passes(); ++p)
    path.set_correction(p, 1e-3, std::vector<topomill::Vec3>(4, d));
  topomill::HeightMap map(m.layout.grid);
  for (std::size_t j = 0; j < map.grid.ny; ++j)
    for (std::size_t i = 0; i < map.grid.nx; ++i) map.at(i, j) = m.surface->height(map.grid.y(j));
  topomill::WorkCounts counts;
  m.evaluator->evaluate(topomill::evaluation_request(m, 2), map, counts);
  return map;
}

double largest_difference(const topomill::HeightMap& a, const topomill::HeightMap& b) {
  REQUIRE(a.z.size() == b.z.size());
  double worst = 0;
  for (std::size_t i = 0; i < a.z.size(); ++i) worst = std::max(worst, std::abs(a.z[i] - b.z[i]));
  return worst;
}

// The pipeline's surface against the ideal one moved by `d`; also that `d` matters (the ideal
// surface unmoved is far off) and that the opposite sign would be caught.
void check_moved_by(const std::string& toml, const topomill::Vec3& d) {
  const auto run = testing::run_scene(toml, {}, 2, {testing::fixture_dir("constant_force")});
  const double error = largest_difference(run.raw, moved_ideal(toml, d));
  const double unmoved = largest_difference(run.raw, moved_ideal(toml, {0, 0, 0}));
  const double reversed = largest_difference(run.raw, moved_ideal(toml, -d));
  INFO("expected path correction (um) " << d.transpose() * 1e3 << "; surface off by " << error * 1e6
                                        << " nm; by " << unmoved * 1e6 << " nm unmoved, by "
                                        << reversed * 1e6 << " nm moved the other way");
  CHECK(error < 1e-9);
  CHECK(unmoved > 1e-4);
  CHECK(reversed > 1e-4);
}

// Cantilever (Eq. 27, docs/model.md): deflection per newton at height z above the tip, load at rx,
// overhang L, stiffness EI. Beyond the load (z <= rx) docs/model.md's cubic; between clamp and load
// the clamped beam's own s^2 (3 sF - s) / 6 EI.
double cantilever(double z, double rx, double L, double ei) {
  if (z <= rx)
    return (std::pow(rx - z, 3) - std::pow(L - z, 3) + 3 * std::pow(L - z, 2) * (L - rx)) /
           (6 * ei);
  const double s = L - z, sf = L - rx;
  return s * s * (3 * sf - s) / (6 * ei);
}

topomill::Vec3 deflection(double load_centre) {
  const double L = 40, ei = 580e3 * M_PI * std::pow(0.8 * 2 * kR, 4) / 64;  // defaults
  const double z = kR * (1 - std::cos(kLambda));  // the contact point under a vertical tool
  const double c = cantilever(z, load_centre, L, ei);
  return {c * kFx, c * kFy, 0};
}

// Eq. 30-31 as docs/model.md restates them, for the springback table below: the plastically
// compressed layer recovers, so the surface ends above where the tool cut (+z), by
// dd = J1 / J2 (1 - exp(-J2 d)).
const char* kSpringback =
    "[springback]\nplugin = 'plastic_exponential'\nyield_strength = 3000.0\n"
    "hardening_exponent = 0.2\nplastic_depth = 0.005\nrake_angle = 5.0\nae_ratio = 0.9\n";
double springback_lift() {
  const double K = 3000, n1 = 0.2, depth = 0.005, a0 = 5 * kDeg, phi = std::asin(0.9);
  const double ae = 0.3, ap = 0.3;
  const double j1 = std::cos(a0) / (std::sqrt(3.0) * std::sin(phi) * std::cos(phi - a0));
  const double A = 1 - (n1 + 1) * (kFx * std::cos(phi) - kFy * std::sin(phi)) *
                           std::pow(std::sqrt(3.0) * std::sin(phi), n1 + 1) *
                           std::pow(std::cos(phi - a0), n1) /
                           (K * ae * ap * std::pow(std::cos(a0), n1));
  const double j2 = -std::log(A) / ((n1 + 1) * depth);
  return j1 / j2 * (1 - std::exp(-j2 * depth));
}

}  // namespace

TEST_CASE("a fixed load deflects the cantilever tool by Eq. 27 at the contact point",
          "[effects][closed-form]") {
  // Load above the contact point (0.302 mm above the tip at 20 deg) and below it: both branches.
  for (double load_centre : {1.0, 0.1}) {
    INFO("load centre " << load_centre << " mm above the tip");
    check_moved_by(scene(load_centre, "[deflection]\nplugin = 'cantilever'\n"),
                   deflection(load_centre));
  }
}

TEST_CASE("a fixed load moves a damped tool by F / k per mode once the start has died away",
          "[effects][closed-form]") {
  // Eq. 22-26 at rest: every mode of an axis gives F / k; heavy damping (0.7 at 3-5 kHz) ends the
  // start-up transient within the run-in (0.7 mm, 50 ms; the transient is e^-13000 t).
  const std::string modes =
      "modes = [{axis = 'x', frequency = 3000.0, damping = 0.7, stiffness = 2e7},"
      " {axis = 'x', frequency = 5000.0, damping = 0.7, stiffness = 4e7},"
      " {axis = 'y', frequency = 3000.0, damping = 0.7, stiffness = 3e7},"
      " {axis = 'z', frequency = 4000.0, damping = 0.7, stiffness = 1e7}]\n";
  const topomill::Vec3 d =
      1e3 * topomill::Vec3(kFx / 2e7 + kFx / 4e7, kFy / 3e7, kFz / 1e7);  // m -> mm
  for (const char* plugin : {"modal_exact", "modal_rk4"}) {
    INFO(plugin);
    check_moved_by(scene(0.5, std::string("[vibration]\nplugin = '") + plugin + "'\n" + modes), d);
  }
}

TEST_CASE("springback lifts the cut surface by Eq. 29-31's displacement",
          "[effects][closed-form]") {
  const double dd = springback_lift();
  REQUIRE(dd > 0);
  check_moved_by(scene(0.5, kSpringback), {0, 0, dd});
}

TEST_CASE("vibration, deflection and springback add (Eq. 32-33)", "[effects][closed-form]") {
  const std::string modes =
      "modes = [{axis = 'x', frequency = 3000.0, damping = 0.7, stiffness = 2e7},"
      " {axis = 'z', frequency = 4000.0, damping = 0.7, stiffness = 1e7}]\n";
  const std::string all = "[vibration]\nplugin = 'modal_exact'\n" + modes +
                          "[deflection]\nplugin = 'cantilever'\n" + kSpringback;
  const topomill::Vec3 vibration = 1e3 * topomill::Vec3(kFx / 2e7, 0, kFz / 1e7);
  check_moved_by(scene(1.0, all),
                 vibration + deflection(1.0) + topomill::Vec3(0, 0, springback_lift()));
}
