// Runs many variants of one scene (a sweep, an ablation, a resolution study) as separate
// `topomill run` processes: a case that fails or crashes is reported and the others go on; each
// case writes into cases/<id>/ and counts as done once its summary.json is there, so a rerun
// skips it (resumable); up to `jobs` cases run at once. Under MPI, each rank runs its share.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace topomill::cli {

struct Case {
  std::string id;                                            // directory name, stable
  std::vector<std::pair<std::string, std::string>> columns;  // what identifies it in tables
  std::vector<std::string> overrides;                        // --set arguments
};

struct CaseResult {
  std::string id;
  bool ok = false;
  bool resumed = false;  // done by an earlier invocation, not rerun
  int exit_code = 0;
  std::string error;                        // the failing case's message
  std::map<std::string, double> roughness;  // Sa..Sku (um), Sdq, Sdr (%)
  double wall_s = 0;                        // the run's own total (summary timing)
  std::vector<std::pair<std::string, double>> stages;
  std::map<std::string, std::uint64_t> work;  // evaluator work counts, "nodes"
  std::vector<std::string> effects;
  std::string dir;  // the case's output directory
  int rank = 0;     // the MPI rank that ran it (0 without MPI)
};

struct RunnerOptions {
  std::string scene_file;
  std::string out_dir;                  // cases go into out_dir/cases/<id>
  unsigned jobs = 1, threads = 1;       // processes at once, evaluator threads each
  std::vector<std::string> extra_args;  // passed to every run (--plugin-path, base --set)
  bool progress = true;                 // one line per finished case on stderr
};

// Runs (or resumes) the cases with index i where i % ranks == rank, and returns the results of
// all cases: gathered on rank 0 (other ranks get only their own). Throws Interrupted after
// SIGINT, once the running cases have stopped.
// Refuses two cases that would share a directory (a value given twice).
void check_case_ids(const std::vector<Case>& cases);

std::vector<CaseResult> run_cases(const std::vector<Case>& cases, const RunnerOptions& options);

// A directory name from free text: letters, digits and ._=- kept, the rest '_'.
std::string case_id(const std::string& text);

}  // namespace topomill::cli
