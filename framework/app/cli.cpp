#include "cli.hpp"

#include <cstdlib>

#include "log.hpp"
#include "topomill/error.hpp"

namespace topomill::cli {

po::options_description common_options(Common& c) {
  po::options_description o("Common options");
  o.add_options()("plugin-path,P", po::value(&c.plugin_paths)->composing(),
                  "extra plugin directory, searched first (repeatable, or colon-separated)")(
      "verbose,v", po::bool_switch(&c.verbose), "log more (where each model came from, ...)")(
      "quiet,q", po::bool_switch(&c.quiet), "log warnings and errors only")(
      "help,h", po::bool_switch(&c.help), "show this help")(
      "no-scene-plugin-paths", po::bool_switch(&c.no_scene_plugin_paths),
      "refuse a scene that names plugin directories (for scenes you did not write; also "
      "TOPOMILL_NO_SCENE_PLUGIN_PATHS=1)");
  return o;
}

bool Common::scene_plugin_paths_allowed() const {
  const char* env = std::getenv("TOPOMILL_NO_SCENE_PLUGIN_PATHS");
  const bool env_refuses = env && *env && std::string(env) != "0";
  return !(no_scene_plugin_paths || env_refuses);
}

po::variables_map parse(const std::vector<std::string>& args, const po::options_description& opts,
                        const po::positional_options_description& positional, Common& common) {
  po::variables_map vm;
  try {
    po::store(po::command_line_parser(args).options(opts).positional(positional).run(), vm);
    po::notify(vm);
  } catch (const po::error& e) {
    throw InputError(SourceRef{"command line"}, "", std::string(e.what()) + " (see --help)");
  }
  set_log_level(common.quiet     ? LogLevel::Quiet
                : common.verbose ? LogLevel::Verbose
                                 : LogLevel::Normal);
  return vm;
}

po::variables_map parse_with_positional(const std::vector<std::string>& args,
                                        const po::options_description& visible, const char* name,
                                        std::string& value, Common& common) {
  po::options_description all;
  all.add(visible).add_options()(name, po::value(&value));
  po::positional_options_description pos;
  pos.add(name, 1);
  return parse(args, all, pos, common);
}

std::vector<PluginCatalog::Dir> search_path(const Common& common,
                                            const std::vector<std::string>& scene_paths) {
  std::vector<PluginCatalog::Dir> dirs;
  for (const auto& entry : common.plugin_paths) {
    std::size_t start = 0;
    while (start <= entry.size()) {
      std::size_t end = entry.find(':', start);
      if (end == std::string::npos) end = entry.size();
      if (end > start) dirs.push_back({entry.substr(start, end - start), "--plugin-path"});
      start = end + 1;
    }
  }
  for (const auto& p : scene_paths) dirs.push_back({p, "scene plugin_paths"});
  for (const auto& p : PluginCatalog::env_dirs()) dirs.push_back({p, "TOPOMILL_PLUGIN_PATH"});
  dirs.push_back({PluginCatalog::builtin_dir(), "built-in"});
  return dirs;
}

void check_threads(unsigned threads) {
  if (threads < 1 || threads > kMaxThreads)
    throw InputError(SourceRef{"command line"}, "--threads",
                     "expected 1 to " + std::to_string(kMaxThreads) + " threads");
}

}  // namespace topomill::cli
