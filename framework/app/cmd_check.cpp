#include <iostream>

#include "cli.hpp"
#include "commands.hpp"
#include "log.hpp"
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
  std::cout << loaded.scene->to_toml() << "\n";
  log_info("scene '" + loaded.scene->file + "' is valid");
  return 0;
}

}  // namespace topomill::cli
