#include <iostream>

#include "cli.hpp"
#include "commands.hpp"
#include "describe.hpp"
#include "log.hpp"
#include "run/pipeline.hpp"
#include "scene_options.hpp"

namespace topomill::cli {

int cmd_check(const Args& args) {
  SceneOptions so;
  unsigned threads = 1;
  po::options_description opts(
      "topomill check SCENE [--set key=value ...] [--threads N]: validate every table of a scene\n"
      "(including disabled effects) and print the resolved scene, defaults filled in; warn, as "
      "run\n"
      "would, of a run estimated at over a minute on N threads");
  opts.add_options()("threads,t", po::value(&threads)->default_value(1),
                     "the threads the memory and time estimates are for, as run's");
  add_scene_options(opts, so);
  LoadedScene loaded = load_scene(args, opts, so, /*check_unused=*/true);
  if (!loaded.scene) {
    std::cout << opts << "\n";
    return 0;
  }
  check_threads(threads);
  // Models and layout: the cross-table checks, and the estimates.
  prepare(*loaded.scene, *loaded.catalog, threads);
  std::cout << to_toml_text(loaded.scene->to_toml());
  log_info("scene '" + loaded.scene->file + "' is valid");
  return 0;
}

}  // namespace topomill::cli
