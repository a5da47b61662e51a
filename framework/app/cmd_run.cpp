#include <iostream>

#include "cli.hpp"
#include "commands.hpp"
#include "scene_options.hpp"

namespace topomill::cli {

int cmd_run(const Args& args) {
  SceneOptions so;
  po::options_description opts("topomill run SCENE [--out DIR] [--set key=value ...] [--threads N]");
  add_scene_options(opts, so);
  LoadedScene loaded = load_scene(args, opts, so, /*check_unused=*/false);
  if (!loaded.scene) {
    std::cout << opts << "\n";
    return 0;
  }
  throw std::runtime_error("run: the pipeline is not built yet");
}

}  // namespace topomill::cli
