// Only the effects a scene calls for run: their libraries are opened, their stages timed, and
// nothing else is computed.
#include <dlfcn.h>

#include <algorithm>
#include <catch2/catch.hpp>

#include "support/scenes.hpp"

namespace {
bool is_loaded(const std::string& model) {
  const std::string path = topomill::PluginCatalog::builtin_dir() + "/libtopomill_" + model + ".so";
  void* h = dlopen(path.c_str(), RTLD_NOW | RTLD_NOLOAD);
  if (h) dlclose(h);
  return h != nullptr;
}

std::vector<std::string> stage_names(const topomill::RunResult& r) {
  std::vector<std::string> out;
  for (const auto& s : r.stages) out.push_back(s.name);
  return out;
}

bool has(const std::vector<std::string>& v, const std::string& s) {
  return std::find(v.begin(), v.end(), s) != v.end();
}

const char* kForce = "[force]\nplugin = 'armarego'\n";
const char* kModes =
    "modes = [{axis = 'x', frequency = 785.0, damping = 0.0246, stiffness = 1.74e7},"
    " {axis = 'y', frequency = 800.0, damping = 0.0263, stiffness = 1.71e7},"
    " {axis = 'z', frequency = 753.0, damping = 0.0215, stiffness = 1.21e7}]\n";

std::string scene(const std::string& extra) {
  return testing::paper_scene("plugin = 'convex_arc'\nradius = 50.0", 30.0, 0.1, 0.1, 0.02) + extra;
}
}  // namespace

TEST_CASE("without an enabled effect the force library is never opened", "[effects]") {
  // [force] and a disabled effect are present, yet nothing of them runs.
  const auto r = testing::run_scene(
      scene(std::string(kForce) + "[vibration]\nenabled = false\nplugin = 'modal_rk4'\n"));
  CHECK_FALSE(is_loaded("armarego"));
  CHECK_FALSE(is_loaded("modal_rk4"));
  const auto stages = stage_names(r);
  CHECK_FALSE(has(stages, "force"));
  CHECK_FALSE(has(stages, "dynamics"));
  CHECK(r.effects.empty());
  CHECK(r.work.count("force_samples") == 0);
}

TEST_CASE("springback alone computes forces but integrates no vibration", "[effects]") {
  const auto r = testing::run_scene(
      scene(std::string(kForce) +
            "[springback]\nplugin = 'plastic_exponential'\nyield_strength = 3000.0\n"
            "hardening_exponent = 0.2\nplastic_depth = 0.005\nrake_angle = 5.0\nae_ratio = 0.9\n"
            "[vibration]\nenabled = false\nplugin = 'modal_rk4'\n" +
            kModes));
  const auto stages = stage_names(r);
  CHECK(has(stages, "force"));
  CHECK(has(stages, "deformation"));
  CHECK_FALSE(has(stages, "dynamics"));
  CHECK_FALSE(is_loaded("modal_rk4"));
  CHECK(r.effects == std::vector<std::string>{"springback"});
}

TEST_CASE("vibration and deflection run, change the surface, and stay finite", "[effects]") {
  const std::string base = scene("");
  const auto ideal = testing::run_scene(base);
  const auto dyn =
      testing::run_scene(scene(std::string(kForce) + "[vibration]\nplugin = 'modal_exact'\n" +
                               kModes + "[deflection]\nplugin = 'cantilever'\n"));
  const auto stages = stage_names(dyn);
  CHECK(has(stages, "force"));
  CHECK(has(stages, "dynamics"));
  CHECK(has(stages, "deformation"));
  CHECK(dyn.effects == std::vector<std::string>{"vibration", "deflection"});
  for (double z : dyn.residual.z) REQUIRE(std::isfinite(z));
  CHECK(dyn.roughness.Sa != ideal.roughness.Sa);
  // The dynamics' own step, not the Z-map's: 40 steps a period of the fastest mode (800 Hz),
  // finer than the force's 64 a tooth passage (7.5 ms / 64).
  CHECK(dyn.dynamics_step == Approx(1.0 / 800 / 40).epsilon(1e-12));
}
