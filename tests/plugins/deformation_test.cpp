// Tool deflection against the textbook cantilever, and the springback's formulas and refusals.
#include <catch2/catch.hpp>
#include <cmath>

#include "support/builtin_models.hpp"
#include "topomill/deformation.hpp"
#include "topomill/error.hpp"
#include "topomill/tool_geometry.hpp"

using testing::make_model;

TEST_CASE("cantilever deflection: F L^3 / 3EI at the tip, F a^2 (3L - a) / 6EI beyond the load",
          "[deflection]") {
  auto tool = make_model<topomill::ToolGeometry>("ball_end_loxodrome", {{"radius", 5}});
  auto beam = make_model<topomill::Deformation>(
      "cantilever", {{"overhang", 40}, {"young_modulus", 580}, {"diameter_ratio", 0.8}});
  const double E = 580e3, I = M_PI * std::pow(8.0, 4) / 64, L = 40;  // N/mm^2, mm^4, mm
  topomill::CutState st;  // lambda = 0: the surface is generated at the tip
  topomill::CuttingForce f;
  f.force = {100, -50, 30};
  f.load_centre = 0;
  auto u = beam->correction(f, *tool, st);
  CHECK(u.x() == Approx(100 * L * L * L / (3 * E * I)).epsilon(1e-12));  // 18.3 um
  CHECK(u.y() == Approx(-50 * L * L * L / (3 * E * I)).epsilon(1e-12));
  CHECK(u.z() == 0.0);
  // Load 2 mm above the tip (a = 38 mm from the clamp), deflection read at the tip (s = L).
  f.load_centre = 2;
  u = beam->correction(f, *tool, st);
  const double a = 38;
  CHECK(u.x() == Approx(100 * a * a * (3 * L - a) / (6 * E * I)).epsilon(1e-12));
}

TEST_CASE("springback: J1 of Eq. 30, the J2 -> 0 limit, and a clear refusal", "[springback]") {
  auto tool = make_model<topomill::ToolGeometry>("ball_end_loxodrome", {{"radius", 5}});
  auto sb = make_model<topomill::Deformation>("plastic_exponential", {{"yield_strength", 1500},
                                                                      {"hardening_exponent", 0.2},
                                                                      {"plastic_depth", 0.02},
                                                                      {"rake_angle", 5},
                                                                      {"ae_ratio", 0.9}});
  topomill::CutState st;
  st.stepover = 0.3;
  st.depth_of_cut = 0.3;
  const double phi = std::asin(0.9), a0 = 5 * M_PI / 180;
  const double j1 = std::cos(a0) / (std::sqrt(3.0) * std::sin(phi) * std::cos(phi - a0));
  topomill::CuttingForce f;  // no force: A = 1, J2 = 0, the strain is J1 throughout the depth
  CHECK(sb->correction(f, *tool, st).z() == Approx(j1 * 0.02).epsilon(1e-12));
  // A moderate force: dd = (J1 / J2)(1 - exp(-J2 d)) with J2 from Eq. 30, computed here.
  f.force = {20, -10, 0};
  const double n1 = 0.2;
  const double A = 1 - (n1 + 1) * (20 * std::cos(phi) + 10 * std::sin(phi)) *
                           std::pow(std::sqrt(3.0) * std::sin(phi), n1 + 1) *
                           std::pow(std::cos(phi - a0), n1) /
                           (1500 * 0.3 * 0.3 * std::pow(std::cos(a0), n1));
  const double j2 = -std::log(A) / ((n1 + 1) * 0.02);
  CHECK(sb->correction(f, *tool, st).z() ==
        Approx(j1 / j2 * (1 - std::exp(-j2 * 0.02))).epsilon(1e-12));
  // A large force leaves the logarithm nothing to take: refused, naming the inputs.
  f.force = {400, -300, 0};
  CHECK_THROWS_AS(sb->correction(f, *tool, st), topomill::ParamError);
  CHECK_THROWS_WITH(sb->correction(f, *tool, st), Catch::Contains("non-positive argument") &&
                                                      Catch::Contains("Fx = 400 N") &&
                                                      Catch::Contains("K = 1500 MPa"));
}

TEST_CASE("the cantilever's section is the cutter's diameter, whatever its corner",
          "[deflection][cutter]") {
  // F L^3 / 3EI with I = pi (0.8 D)^4 / 64: a bull-nose and a flat end of D = 10 mm bend as the
  // ball end of R = 5 mm does, not as a beam of their corner's radius.
  auto beam = make_model<topomill::Deformation>(
      "cantilever", {{"overhang", 40}, {"young_modulus", 580}, {"diameter_ratio", 0.8}});
  const double E = 580e3, I = M_PI * std::pow(8.0, 4) / 64, L = 40;
  topomill::CutState st;
  topomill::CuttingForce f;
  f.force = {100, 0, 0};
  for (const auto& [name, values] :
       std::vector<std::pair<std::string, std::vector<std::pair<std::string, double>>>>{
           {"bull_nose", {{"diameter", 10}, {"corner_radius", 2}}},
           {"flat_end", {{"diameter", 10}}}}) {
    INFO(name);
    auto tool = make_model<topomill::ToolGeometry>(name, values);
    CHECK(beam->correction(f, *tool, st).x() ==
          Approx(100 * L * L * L / (3 * E * I)).epsilon(1e-12));
  }
}
