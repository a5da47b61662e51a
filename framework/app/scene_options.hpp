// What `run` and `check` share: the SCENE argument, --set overrides, and loading the scene with
// its plugin search path.
#pragma once

#include <memory>
#include <optional>

#include "cli.hpp"
#include "commands.hpp"
#include "scene.hpp"

namespace topomill::cli {

struct SceneOptions {
  Common common;
  std::string scene_file;
  std::vector<std::string> overrides;
};

// Adds SCENE (positional), --set and the common options to `opts`.
void add_scene_options(po::options_description& opts, SceneOptions& so);

struct LoadedScene {
  std::unique_ptr<PluginCatalog> catalog;  // outlives `scene`, which points into it
  std::optional<Scene> scene;              // empty when --help was asked for
  po::variables_map vm;
};

LoadedScene load_scene(const Args& args, const po::options_description& opts, SceneOptions& so,
                       bool check_unused);

}  // namespace topomill::cli
