// Scene loading: defaults, overrides, and effects that cost nothing when off.
#include <catch2/catch.hpp>

#include "scene.hpp"
#include "support/run_command.hpp"

using topomill::InputError;
using topomill::PluginCatalog;
using topomill::SceneDocument;

namespace {
const char* kBase = R"(
[tool]
plugin = "ball_end_loxodrome"
radius = 5.0
[workpiece]
plugin = "convex_arc"
radius = 50.0
[cutting]
spindle_speed = 4000
feed_per_tooth = 0.1
depth_of_cut = 0.3
stepover = 0.3
[region]
lambda = 30.0
size = [0.2, 0.2]
spacing = 0.02
)";

PluginCatalog builtin_catalog() {
  return PluginCatalog({{PluginCatalog::builtin_dir(), "built-in"}});
}
}  // namespace

TEST_CASE("defaults are filled in and the evaluator defaults to tooth_passage", "[scene]") {
  auto catalog = builtin_catalog();
  auto scene = SceneDocument::parse_string(kBase, "base.toml").resolve(catalog);
  CHECK(scene.slot("tool").params.integer("teeth") == 2);
  CHECK(scene.slot("tool").params.number("helix_angle") == 30.0);
  CHECK(scene.slot("evaluator").plugin == "tooth_passage");
  CHECK(scene.table("cutting").string("spindle_direction") == "cw");
  CHECK(scene.enabled_effects().empty());
  CHECK(scene.slot("force").model == nullptr);
}

TEST_CASE("overrides replace values, create tables and are checked like the file", "[scene]") {
  auto catalog = builtin_catalog();
  auto doc = SceneDocument::parse_string(kBase, "base.toml");
  doc.apply_override("tool.teeth=4");
  doc.apply_override("cutting.spindle_direction=ccw");  // not TOML: taken as a string
  doc.apply_override("scene.name=\"from the command line\"");
  auto scene = doc.resolve(catalog);
  CHECK(scene.slot("tool").params.integer("teeth") == 4);
  CHECK(scene.table("cutting").string("spindle_direction") == "ccw");
  CHECK(scene.table("scene").string("name") == "from the command line");

  auto bad = SceneDocument::parse_string(kBase, "base.toml");
  bad.apply_override("tool.teeth=0");
  CHECK_THROWS_WITH(bad.resolve(catalog),
                    "--set tool.teeth=0: error: key 'tool.teeth': value 0 is out of range: "
                    "expected an integer >= 1 and <= 64");
  auto malformed = SceneDocument::parse_string(kBase, "base.toml");
  CHECK_THROWS_AS(malformed.apply_override("no_equals_sign"), InputError);
}

TEST_CASE("a disabled effect is not resolved by a run, but check validates it",
          "[scene][effects]") {
  const std::string text = std::string(kBase) +
                           "[vibration]\nenabled = false\nplugin = \"not_installed\"\n"
                           "[force]\nplugin = \"also_not_installed\"\n";
  auto catalog = builtin_catalog();
  auto scene = SceneDocument::parse_string(text, "s.toml").resolve(catalog);
  CHECK_FALSE(scene.enabled("vibration"));
  CHECK_FALSE(scene.enabled("force"));  // no effect needs it
  CHECK(scene.slot("vibration").model == nullptr);

  auto catalog2 = builtin_catalog();
  CHECK_THROWS_WITH(SceneDocument::parse_string(text, "s.toml").resolve(catalog2, true),
                    Catch::Contains("unknown force model 'also_not_installed'") ||
                        Catch::Contains("unknown dynamics model 'not_installed'"));
}

TEST_CASE("plugin_paths are taken relative to the scene file", "[scene]") {
  auto doc = SceneDocument::parse_string("plugin_paths = ['plugins', '/abs']\n", "/data/s/x.toml");
  CHECK(doc.plugin_paths() == std::vector<std::string>{"/data/s/plugins", "/abs"});
}
