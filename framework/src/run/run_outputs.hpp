// Everything `topomill run` writes: the height maps in the scene's formats, then summary.json
// last, each file atomically, so a directory with a summary.json holds a complete run.
#pragma once

#include <chrono>
#include <string>
#include <vector>

#include "run/pipeline.hpp"

namespace topomill {

struct RunSummary {
  std::string text;  // the human-readable result printed on stdout
  std::string json;  // summary.json's content
};

// summary.json's content: the run, the files written (none for a run kept in memory), the
// seconds writing them took and the whole run's since `started`.
std::string summary_json(const RunResult& result, const std::vector<std::string>& files,
                         double write_s, std::chrono::steady_clock::time_point started);

// The scene's settings come with the result (RunResult::settings), read once by the pipeline.
RunSummary write_run_outputs(const RunResult& result, const std::string& out_dir,
                             std::chrono::steady_clock::time_point started);

}  // namespace topomill
