// Memory a run will need, estimated before any work, against what the machine has: a scene that
// would not fit is refused with the estimate and the key to turn, instead of swapping or being
// killed halfway.
#pragma once

#include <cstdint>
#include <string>

#include "run/pipeline.hpp"

namespace topomill {

// Bytes this process may still allocate: MemAvailable, capped by RLIMIT_AS / RLIMIT_DATA, or
// TOPOMILL_MEMORY_LIMIT (bytes, or with a K/M/G suffix) when set.
std::uint64_t available_memory();

// The cores this process may run on (its CPU affinity: a batch scheduler's share).
unsigned usable_cores();

// Samples on the force/dynamics time grid over all passes (0 when no effect is enabled).
std::uint64_t effect_samples(const Prepared& m);

// The force/dynamics time step, s: 1/64 of a tooth period, or the dynamics' own step if smaller.
double effect_time_step(const Prepared& m);

struct MemoryEstimate {
  std::uint64_t grid_bytes = 0;       // the core's height maps and outputs
  std::uint64_t evaluator_bytes = 0;  // the evaluator's own buffers (EvaluationCost)
  std::string evaluator_key;          // the scene key that drives them
  std::uint64_t effect_bytes = 0;     // cut states, forces and corrections on the time grid
  std::uint64_t analysis_bytes = 0;   // the parameters chosen (analysis.parameters)
  std::uint64_t total() const {
    return grid_bytes + evaluator_bytes + effect_bytes + analysis_bytes;
  }
};

MemoryEstimate estimate_memory(const Prepared& m, const EvaluationCost& cost);

// Throws InputError naming the key that dominates the estimate when it exceeds `available`.
// The evaluator's cost for this preparation (asked once; both checks below use it).
EvaluationCost evaluation_cost(const Prepared& m, unsigned threads);

void check_memory(const Scene& scene, const Prepared& m, const EvaluationCost& cost,
                  unsigned threads, std::uint64_t available);

// Seconds the stages after the evaluation take (form removal, parameters, writing), on one thread.
double finishing_seconds(const Scene& scene, const Prepared& m);

// Before a run estimated at over a minute (the evaluator's estimate on the cores there are, and
// the stages after it), a warning with the estimate and the key that drives it; one that would
// not end (over three years) is refused naming that key.
void check_duration(const Scene& scene, const Prepared& m, const EvaluationCost& cost,
                    unsigned threads);

std::string format_bytes(double bytes);

}  // namespace topomill
