// Deliberately broken plugins are refused with precise messages, and the program goes on.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <utility>
#include <vector>
#include "topomill/version.hpp"

#include "plugin_catalog.hpp"
#include "support/run_command.hpp"

using testing::fixture_dir;
using testing::run_topomill;

namespace {
bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// A scene whose workpiece is `plugin` (no keys besides), found through `plugin_paths` (none when
// `plugin_dir` is empty).
std::string scene_with_workpiece(const std::string& name, const std::string& plugin,
                                 const std::string& plugin_dir) {
  const std::string path = testing::temp_dir(name) + ".toml";
  std::ofstream(path) << (plugin_dir.empty() ? "" : "plugin_paths = ['" + plugin_dir + "']\n")
                      << "[tool]\nplugin = 'ball_end_loxodrome'\nradius = 5.0\n"
                      << "[workpiece]\nplugin = '" << plugin << "'\n"
                      << "[cutting]\nspindle_speed = 4000\nfeed_per_tooth = 0.1\n"
                      << "depth_of_cut = 0.3\nstepover = 0.3\n"
                      << "[region]\nlambda = 0.0\nsize = [0.1, 0.1]\nspacing = 0.02\n";
  return path;
}
}  // namespace

TEST_CASE("a third-party plugin is found by --plugin-path, the environment and the scene",
          "[plugins]") {
  const auto listed = run_topomill("plugins -P '" + fixture_dir("good") + "'");
  REQUIRE(listed.exit_code == 0);
  CHECK(contains(listed.out, "fixture_good"));
  CHECK(contains(listed.out, "fixture_good 9.9.9"));

  const auto env =
      run_topomill("describe fixture_good", "TOPOMILL_PLUGIN_PATH='" + fixture_dir("good") + "'");
  CHECK(env.exit_code == 0);
  CHECK(contains(env.out, "height_offset"));

  const auto scene = scene_with_workpiece("scene_paths", "fixture_good", fixture_dir("good"));
  const auto checked = run_topomill("check '" + scene + "' -v");
  INFO(checked.err);
  CHECK(checked.exit_code == 0);
  CHECK(contains(checked.err, "workpiece: fixture_good from " + fixture_dir("good")));
}

TEST_CASE("a library without the entry point is refused and the listing goes on", "[plugins]") {
  const auto r = run_topomill("plugins -P '" + fixture_dir("no_entry") + "'");
  CHECK(r.exit_code == 0);
  CHECK(contains(r.out, "refused libraries"));
  CHECK(contains(r.out,
                 "libtopomill_fixture_no_entry.so: not a topomill plugin: it exports no "
                 "entry point 'topomill_plugin_entry_v1'"));
  CHECK(contains(r.out, "zmap"));  // the built-in ones are still there
}

TEST_CASE("the ABI handshake refuses a plugin built for another ABI, naming both", "[plugins]") {
  const auto r = run_topomill("plugins -P '" + fixture_dir("wrong_abi") + "'");
  CHECK(r.exit_code == 0);
  CHECK(contains(r.out, fixture_dir("wrong_abi") +
                            "/libtopomill_fixture_wrong_abi.so: built for "
                            "topomill plugin ABI 999, this program provides ABI " +
                            std::to_string(topomill::kAbiVersion)));
  // Asked for by name, the refusal is the error.
  const auto scene =
      scene_with_workpiece("wrong_abi", "fixture_wrong_abi", fixture_dir("wrong_abi"));
  const auto run = run_topomill("check '" + scene + "'");
  CHECK(run.exit_code == 2);
  CHECK(contains(run.err, "key 'workpiece.plugin': model 'fixture_wrong_abi' cannot be loaded"));
  CHECK(contains(run.err, "built for topomill plugin ABI 999"));
}

TEST_CASE("the record-size handshake refuses a mismatched layout", "[plugins]") {
  const auto r = run_topomill("plugins -P '" + fixture_dir("wrong_size") + "'");
  CHECK(r.exit_code == 0);
  CHECK(
      contains(r.out, "record size mismatch for ModelInfo: the plugin has 1 bytes, this program"));
}

TEST_CASE("a registration that throws is refused", "[plugins]") {
  const auto r = run_topomill("plugins -P '" + fixture_dir("bad_registration") + "'");
  CHECK(r.exit_code == 0);
  CHECK(contains(r.out, "registration failed: fixture: registration refuses"));
}

TEST_CASE("a library registering a model not named after its file is refused", "[plugins]") {
  const auto r = run_topomill("plugins -P '" + fixture_dir("misnamed") + "'");
  CHECK_FALSE(r.crashed);
  CHECK(r.exit_code == 0);
  CHECK(contains(r.out, fixture_dir("misnamed") +
                            "/libtopomill_fixture_misnamed.so: registers 'fixture_other', "
                            "'fixture_misnamed': expected exactly one model, named after its "
                            "file ('fixture_misnamed' for libtopomill_fixture_misnamed.so)"));
  CHECK_FALSE(contains(r.out, "  fixture_other"));
}

// Issue 18, defect 12: a scene ran native code it never named.
TEST_CASE("a scene's model name opens only the library of that name", "[plugins][trust]") {
  const std::string mark = testing::temp_dir("loud_opened");
  const std::string env = "TOPOMILL_FIXTURE_MARK='" + mark + "'";
  // A misspelt name: refused from the file names alone, the library beside it never opened.
  const auto misspelt = scene_with_workpiece("loud_misspelt", "fixture_lod", fixture_dir("loud"));
  const auto r = run_topomill("check '" + misspelt + "'", env);
  INFO(r.err);
  CHECK(r.exit_code == 2);
  CHECK(contains(r.err, "unknown surface shape 'fixture_lod'; did you mean 'fixture_loud'?"));
  CHECK_FALSE(std::filesystem::exists(mark));
  // A name that is not an identifier is refused before any path is formed from it.
  const auto escape =
      scene_with_workpiece("loud_escape", "../loud/libtopomill_fixture_loud", fixture_dir("good"));
  const auto e = run_topomill("check '" + escape + "'", env);
  CHECK(e.exit_code == 2);
  CHECK(contains(e.err, "is not a model name: expected letters, digits and underscores"));
  CHECK_FALSE(std::filesystem::exists(mark));
  // The right name opens it.
  const auto named = scene_with_workpiece("loud_named", "fixture_loud", fixture_dir("loud"));
  CHECK(run_topomill("check '" + named + "'", env).exit_code == 0);
  CHECK(std::filesystem::exists(mark));
}

TEST_CASE("scene plugin paths can be refused for scenes one did not write", "[plugins][trust]") {
  const std::string mark = testing::temp_dir("loud_refused_opened");
  const std::string env = "TOPOMILL_FIXTURE_MARK='" + mark + "'";
  const auto scene = scene_with_workpiece("loud_untrusted", "fixture_loud", fixture_dir("loud"));
  for (const auto& [args, extra_env] : std::vector<std::pair<std::string, std::string>>{
           {"check '" + scene + "' --no-scene-plugin-paths", ""},
           {"check '" + scene + "'", " TOPOMILL_NO_SCENE_PLUGIN_PATHS=1"},
           {"run '" + scene + "' --no-scene-plugin-paths --out '" +
                testing::temp_dir("loud_untrusted_out") + "/o'",
            ""}}) {
    const auto r = run_topomill(args, env + extra_env);
    INFO(args << extra_env << ": " << r.err);
    CHECK(r.exit_code == 2);
    CHECK(contains(r.err, scene + ":1:16: error: key 'plugin_paths': this scene names plugin "
                                  "directories, and scene plugin paths are refused"));
    CHECK_FALSE(std::filesystem::exists(mark));
  }
  // The same directory given by the user (--plugin-path) stays trusted under the refusal.
  const auto own = scene_with_workpiece("loud_own_path", "fixture_loud", "");
  const auto trusted = run_topomill(
      "check '" + own + "' -v --no-scene-plugin-paths -P '" + fixture_dir("loud") + "'",
      env + " TOPOMILL_NO_SCENE_PLUGIN_PATHS=1");
  INFO(trusted.err);
  CHECK(trusted.exit_code == 0);
  CHECK(contains(trusted.err, "workpiece: fixture_loud from " + fixture_dir("loud")));
  CHECK(std::filesystem::exists(mark));
}

TEST_CASE("a plugin named like a built-in shadows it in run, check and plugins alike",
          "[plugins]") {
  // One rule (plugin_catalog.hpp): the library named after the model, then the earlier
  // directory. Before, `plugins` said "registered twice" (exit 2) while run and check used it.
  const std::string dir = fixture_dir("shadow");
  const std::string builtin = topomill::PluginCatalog::builtin_dir();
  const auto listed = run_topomill("plugins -P '" + dir + "'");
  INFO(listed.err);
  REQUIRE(listed.exit_code == 0);
  CHECK(contains(listed.out,
                 "inclined_plane  - fixture: shadows the built-in inclined_plane\n"
                 "      from " +
                     dir + "/libtopomill_inclined_plane.so"));
  CHECK(contains(listed.out, "  inclined_plane from " + builtin +
                                 "/libtopomill_inclined_plane.so\n      shadowed by " + dir +
                                 "/libtopomill_inclined_plane.so"));
  const auto json = run_topomill("plugins --json -P '" + dir + "'");
  CHECK(contains(json.out, "\"shadowed_by\": \"" + dir + "/libtopomill_inclined_plane.so\""));

  const std::string used = "workpiece: inclined_plane from " + dir;
  const std::string scene = "configs/bench/flat_vertical.toml";
  const auto checked = run_topomill("check " + scene + " -v -P '" + dir + "'");
  INFO(checked.err);
  CHECK(checked.exit_code == 0);
  CHECK(contains(checked.err, used));
  const std::string out = testing::temp_dir("shadow_run");
  const auto ran = run_topomill("run " + scene + " -v -P '" + dir + "' --out '" + out +
                                "' --set region.spacing=0.05 --set output.formats=[]");
  INFO(ran.err);
  CHECK(ran.exit_code == 0);
  CHECK(contains(ran.err, used));
  // Without the directory the built-in is used.
  CHECK(contains(run_topomill("check " + scene + " -v").err,
                 "workpiece: inclined_plane from " + builtin));
}

TEST_CASE("a throwing constructor fails the run cleanly and a ParamError points at the scene",
          "[plugins]") {
  const auto scene = scene_with_workpiece("throwing", "fixture_throwing", fixture_dir("throwing"));
  const auto r = run_topomill("check '" + scene + "'");
  CHECK_FALSE(r.crashed);
  CHECK(r.exit_code == 1);
  CHECK(contains(r.err, "model 'fixture_throwing' from '" + fixture_dir("throwing") +
                            "/libtopomill_fixture_throwing.so' failed to construct: fixture: this "
                            "constructor always fails"));

  const auto picky =
      run_topomill("check configs/examples/quick.toml -P '" + fixture_dir("throwing") +
                   "' --set workpiece.plugin=fixture_picky");
  CHECK_FALSE(picky.crashed);
  CHECK(picky.exit_code == 2);
  CHECK(contains(picky.err,
                 "configs/examples/quick.toml:14:10: error: key 'workpiece.radius': "
                 "fixture: 50 mm is refused"));
}
