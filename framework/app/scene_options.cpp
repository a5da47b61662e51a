#include "scene_options.hpp"

namespace topomill::cli {

void add_scene_options(po::options_description& opts, SceneOptions& so) {
  opts.add_options()("set,s", po::value(&so.overrides)->composing(),
                     "override a scene key, e.g. --set cutting.feed_per_tooth=0.15 (repeatable; "
                     "checked like the file)");
  opts.add(common_options(so.common));
}

LoadedScene load_scene(const Args& args, const po::options_description& opts, SceneOptions& so,
                       bool check_unused) {
  LoadedScene out;
  out.vm = parse_with_positional(args, opts, "scene", so.scene_file, so.common);
  if (so.common.help) return out;
  if (so.scene_file.empty())
    throw InputError(SourceRef{"command line"}, "", "a scene file is required (see --help)");

  SceneDocument doc = SceneDocument::parse_file(so.scene_file);
  for (const auto& o : so.overrides) doc.apply_override(o);
  out.catalog = std::make_unique<PluginCatalog>(
      search_path(so.common, doc.plugin_paths(so.common.scene_plugin_paths_allowed())));
  out.scene = doc.resolve(*out.catalog, check_unused);
  return out;
}

}  // namespace topomill::cli
