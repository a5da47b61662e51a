#include <iostream>

#include "cli.hpp"
#include "commands.hpp"
#include "describe.hpp"
#include "log.hpp"
#include "pipeline.hpp"
#include "scene_options.hpp"

namespace topomill::cli {

int cmd_check(const Args& args) {
  SceneOptions so;
  po::options_description opts(
      "topomill check SCENE [--set key=value ...]: validate every table of a scene (including\n"
      "disabled effects) and print the resolved scene, defaults filled in");
  add_scene_options(opts, so);
  LoadedScene loaded = load_scene(args, opts, so, /*check_unused=*/true);
  if (!loaded.scene) {
    std::cout << opts << "\n";
    return 0;
  }
  prepare(*loaded.scene, *loaded.catalog);  // models and layout: the cross-table checks
  std::cout << to_toml_text(loaded.scene->to_toml());
  log_info("scene '" + loaded.scene->file + "' is valid");
  return 0;
}

}  // namespace topomill::cli
