// The effects stage: forces on a time grid chosen for the dynamics, the vibration's response,
// the deformations, and their sum as the path's correction TC (Eq. 32-33). Each pass starts from
// rest. Runs only when the scene enables an effect (each needs forces).
#pragma once

#include "run/pipeline.hpp"

namespace topomill {

// Sets the correction of every pass of m's path; records the stages' times, the time step, the
// peaks and the effects that ran into `result`.
void apply_effects(const Scene& scene, const Prepared& m, unsigned threads, StageClock& clock,
                   RunResult& result);

}  // namespace topomill
