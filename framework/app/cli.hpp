// Shared pieces of the command-line program: common options and the plugin search path.
#pragma once

#include <boost/program_options.hpp>
#include <string>
#include <vector>

#include "plugin_catalog.hpp"

namespace topomill::cli {

namespace po = boost::program_options;

struct Common {
  std::vector<std::string> plugin_paths;
  bool verbose = false, quiet = false, help = false;
  bool no_scene_plugin_paths = false;  // or TOPOMILL_NO_SCENE_PLUGIN_PATHS set (not "0")

  // Whether a scene's plugin_paths may be used (see SceneDocument::plugin_paths).
  bool scene_plugin_paths_allowed() const;
};

// --plugin-path, --verbose, --quiet, --help.
po::options_description common_options(Common& common);

// Parses `args` against `visible` (+ the positional names), applies the log level. Unknown
// options and missing values become InputError (exit code 2).
po::variables_map parse(const std::vector<std::string>& args, const po::options_description& opts,
                        const po::positional_options_description& positional, Common& common);

// parse() with one positional argument `name` stored in `value` (not shown in --help).
po::variables_map parse_with_positional(const std::vector<std::string>& args,
                                        const po::options_description& visible, const char* name,
                                        std::string& value, Common& common);

// --threads as run, check and the batch commands take it: 1 to kMaxThreads (InputError).
constexpr unsigned kMaxThreads = 256;
void check_threads(unsigned threads);

// Search order: --plugin-path, the scene's plugin_paths, TOPOMILL_PLUGIN_PATH, built-in.
std::vector<PluginCatalog::Dir> search_path(const Common& common,
                                            const std::vector<std::string>& scene_paths = {});

}  // namespace topomill::cli
