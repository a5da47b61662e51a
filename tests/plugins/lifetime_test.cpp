// A model keeps its library loaded for as long as it lives, and a run opens only the libraries
// its scene names.
#include <dlfcn.h>

#include <catch2/catch.hpp>

#include "plugin_catalog.hpp"
#include "run/pipeline.hpp"
#include "scene.hpp"
#include "support/run_command.hpp"

namespace {
std::string builtin(const std::string& model) {
  return topomill::PluginCatalog::builtin_dir() + "/libtopomill_" + model + ".so";
}

// Whether the dynamic loader has the library open (without opening it).
bool is_loaded(const std::string& path) {
  void* h = dlopen(path.c_str(), RTLD_NOW | RTLD_NOLOAD);
  if (h) dlclose(h);
  return h != nullptr;
}
}  // namespace

TEST_CASE("an object outlives the catalogue that loaded its plugin", "[plugins][lifetime]") {
  std::shared_ptr<topomill::SurfaceShape> surface;
  {
    topomill::PluginCatalog catalog({{topomill::PluginCatalog::builtin_dir(), "built-in"}});
    const topomill::ModelEntry* entry = catalog.find("convex_arc");
    REQUIRE(entry);
    topomill::Params p;
    p.set("radius", 20.0);
    surface = catalog.create<topomill::SurfaceShape>(*entry, p);
  }
  REQUIRE(is_loaded(builtin("convex_arc")));
  // Calls into the plugin's code after the catalogue is gone: r - sqrt(r^2 - y^2) below the crown.
  CHECK(surface->height(12.0) == Approx(std::sqrt(400.0 - 144.0) - 20.0));
  CHECK(surface->curvature_radius() == 20.0);
  surface.reset();
  CHECK_FALSE(is_loaded(builtin("convex_arc")));  // the last owner closed it
}

TEST_CASE("resolving and preparing a scene opens only the libraries it names", "[plugins][lazy]") {
  auto doc =
      topomill::SceneDocument::parse_file(testing::source_dir() + "/configs/examples/quick.toml");
  topomill::PluginCatalog catalog({{topomill::PluginCatalog::builtin_dir(), "built-in"}});
  topomill::Scene scene = doc.resolve(catalog);
  topomill::Prepared prepared = topomill::prepare(scene, catalog);
  for (const std::string used : {"ball_end_loxodrome", "convex_arc", "tooth_passage"})
    CHECK(is_loaded(builtin(used)));
  for (const std::string unused :
       {"ball_end_constant_lead", "concave_arc", "inclined_plane", "zmap"})
    CHECK_FALSE(is_loaded(builtin(unused)));
}
