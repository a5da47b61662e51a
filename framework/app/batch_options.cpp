#include "batch_options.hpp"

#include <filesystem>

#include "distribution.hpp"

namespace topomill::cli {

void add_batch_options(po::options_description& opts, BatchOptions& b) {
  opts.add_options()("out,o", po::value(&b.out_dir), "output directory")(
      "jobs,j", po::value(&b.jobs)->default_value(1), "cases run at once (processes)")(
      "threads,t", po::value(&b.threads)->default_value(1), "evaluator threads per case");
  add_scene_options(opts, b.scene);
}

LoadedScene load_batch(const Args& args, const po::options_description& opts, BatchOptions& b,
                       const std::string& suffix) {
  LoadedScene loaded = load_scene(args, opts, b.scene, /*check_unused=*/false);
  if (!loaded.scene) return loaded;
  if (b.jobs < 1 || b.jobs > 256)
    throw InputError(SourceRef{"command line"}, "--jobs", "expected 1 to 256 cases at once");
  check_threads(b.threads);
  if (b.out_dir.empty())
    b.out_dir = (std::filesystem::path("out") /
                 (std::filesystem::path(b.scene.scene_file).stem().string() + "_" + suffix))
                    .string();
  return loaded;
}

RunnerOptions runner_options(const BatchOptions& b) {
  RunnerOptions r;
  r.scene_file = b.scene.scene_file;
  r.out_dir = b.out_dir;
  r.jobs = b.jobs;
  r.threads = b.threads;
  for (const auto& p : b.scene.common.plugin_paths) r.extra_args.push_back("--plugin-path=" + p);
  if (!b.scene.common.scene_plugin_paths_allowed())
    r.extra_args.push_back("--no-scene-plugin-paths");
  for (const auto& s : b.scene.overrides) r.extra_args.push_back("--set=" + s);
  return r;
}

std::unique_ptr<OutputLock> lock_batch_output(const BatchOptions& b,
                                              const std::vector<Case>& cases) {
  check_case_ids(cases);
  if (Distribution::instance().rank() != 0) return nullptr;
  auto lock = std::make_unique<OutputLock>(b.out_dir, SourceRef{"command line"}, "--out", false);
  lock->keep();
  return lock;
}

void check_variant(const BatchOptions& b, const std::vector<std::string>& extra,
                   const std::string& origin, bool check_unused) {
  SceneDocument doc = SceneDocument::parse_file(b.scene.scene_file);
  for (const auto& o : b.scene.overrides) doc.apply_override(o);
  try {
    for (const auto& o : extra) doc.apply_override(o);
    PluginCatalog catalog(
        search_path(b.scene.common, doc.plugin_paths(b.scene.common.scene_plugin_paths_allowed())));
    doc.resolve(catalog, check_unused);
  } catch (const InputError& e) {
    throw InputError(SourceRef{"command line"}, origin, e.what());
  }
}

}  // namespace topomill::cli
