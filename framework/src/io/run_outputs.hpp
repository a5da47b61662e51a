// Everything `topomill run` writes: the height maps in the scene's formats, then summary.json
// last, each file atomically, so a directory with a summary.json holds a complete run.
#pragma once

#include <chrono>
#include <string>

#include "pipeline.hpp"
#include "scene.hpp"

namespace topomill {

struct RunSummary {
  std::string text;  // the human-readable result printed on stdout
  std::string json;  // summary.json's content
};

RunSummary write_run_outputs(const Scene& scene, const RunResult& result,
                             const std::string& out_dir,
                             std::chrono::steady_clock::time_point started);

}  // namespace topomill
