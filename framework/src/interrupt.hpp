// Ctrl-C: the first SIGINT asks the run to stop at the next check (between stages, between rows
// of the evaluator) so that it ends with a clear message and writes nothing; a second one kills.
#pragma once

#include <atomic>
#include <stdexcept>
#include <string>

namespace topomill {

// Thrown at a check after SIGINT.
class Interrupted : public std::runtime_error {
 public:
  Interrupted();
  explicit Interrupted(const std::string& what) : std::runtime_error(what) {}
};

// Installs the SIGINT handler. Safe to call more than once.
void install_interrupt_handler();

// The flag the handler sets; EvaluationRequest::stop points at it.
const std::atomic<bool>& stop_flag();

// Throws Interrupted if a stop was requested.
void throw_if_interrupted();

}  // namespace topomill
