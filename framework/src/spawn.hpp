// Starting a program without a shell (so that signals reach it, not a shell), with its stdout
// and stderr in one log file: the case runner's cases, and the tests' killed runs.
#pragma once

#include <string>
#include <vector>

namespace topomill {

// Starts `program` with `args`; returns its pid. With `own_group`, it gets a process group of
// its own, so that a terminal's Ctrl-C reaches only the caller. Throws std::runtime_error when
// it cannot start.
int spawn_logged(const std::string& program, const std::vector<std::string>& args,
                 const std::string& log, bool own_group);

}  // namespace topomill
