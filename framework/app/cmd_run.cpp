#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "cli.hpp"
#include "commands.hpp"
#include "interrupt.hpp"
#include "io/output_lock.hpp"
#include "log.hpp"
#include "run/pipeline.hpp"
#include "run/run_outputs.hpp"
#include "scene_options.hpp"

namespace topomill::cli {

int cmd_run(const Args& args) {
  SceneOptions so;
  std::string out_dir;
  unsigned threads = 1;
  bool wait = false;
  po::options_description opts(
      "topomill run SCENE [--out DIR] [--set key=value ...] [--threads N]: simulate a scene and "
      "write summary.json, height maps and a heat map");
  opts.add_options()("out,o", po::value(&out_dir),
                     "output directory (default: [output] dir, "
                     "else out/<scene name>)")("threads,t", po::value(&threads)->default_value(1),
                                               "worker threads for the evaluator")(
      "wait", po::bool_switch(&wait),
      "if another run is writing into the output directory, wait for it (default: refuse)");
  add_scene_options(opts, so);
  const auto started = std::chrono::steady_clock::now();
  LoadedScene loaded = load_scene(args, opts, so, /*check_unused=*/false);
  if (!loaded.scene) {
    std::cout << opts << "\n";
    return 0;
  }
  check_threads(threads);
  const Scene& scene = *loaded.scene;
  // Where the directory came from, for messages: --out, the scene's [output] dir, or neither.
  SourceRef out_where{"command line"};
  std::string out_key = "--out";
  if (out_dir.empty()) {
    const Params& output = scene.table("output");
    out_dir = output.string("dir");
    out_where = output.where("dir"), out_key = "output.dir";
  }
  if (out_dir.empty()) {
    out_dir = (std::filesystem::path("out") / std::filesystem::path(scene.file).stem()).string();
    out_where = SourceRef{"command line"}, out_key = "--out";
  }
  // One writer per directory for the whole run, taken before the work (issue 18).
  OutputLock lock(out_dir, out_where, out_key, wait);

  RunOptions options;
  options.threads = threads;
  const bool tty = isatty(STDERR_FILENO) && log_level() != LogLevel::Quiet;
  if (tty)
    options.progress = [](const std::string& stage, double f) {
      std::fprintf(stderr, "\r%s %3.0f%%", stage.c_str(), 100 * f);
      std::fflush(stderr);
    };
  RunResult result = run_pipeline(scene, *loaded.catalog, options);
  if (tty) std::fprintf(stderr, "\r%*s\r", 20, "");
  throw_if_interrupted();

  lock.keep();
  RunSummary summary = write_run_outputs(result, out_dir, started);
  std::cout << summary.text;
  return 0;
}

}  // namespace topomill::cli
