// What the many-case commands (sweep, ablate, study) share: the scene and its --set overrides,
// --out, --jobs and --threads, and checking a variant's overrides before any case runs.
#pragma once

#include <memory>

#include "case_runner.hpp"
#include "io/output_lock.hpp"
#include "scene_options.hpp"

namespace topomill::cli {

struct BatchOptions {
  SceneOptions scene;
  std::string out_dir;
  unsigned jobs = 1, threads = 1;
};

void add_batch_options(po::options_description& opts, BatchOptions& b);

// Validates the options and the scene; fills `out_dir` (default out/<scene stem>_<suffix>).
// Empty scene when --help was asked for.
LoadedScene load_batch(const Args& args, const po::options_description& opts, BatchOptions& b,
                       const std::string& suffix);

// Runner options: every case gets the base --set overrides and the plugin search path.
RunnerOptions runner_options(const BatchOptions& b);

// The batch's output directory, locked for the whole command by its first rank (the others
// write only into their cases, each locked by its own run): null on the other ranks.
// The cases are checked first: a refused request leaves no directory behind.
std::unique_ptr<OutputLock> lock_batch_output(const BatchOptions& b,
                                              const std::vector<Case>& cases);

// Resolves the scene with its base overrides plus `extra`; an InputError names `origin` (the
// option that asked for the variant) and the value.
// With `check_unused`, tables the run would not use are checked too (a swapped model).
void check_variant(const BatchOptions& b, const std::vector<std::string>& extra,
                   const std::string& origin, bool check_unused = false);

}  // namespace topomill::cli
