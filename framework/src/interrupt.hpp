// Ctrl-C: the first SIGINT asks the run to stop at the next check (between stages, between rows
// of the evaluator) so that it ends with a clear message and writes nothing; a second one kills.
#pragma once

#include <atomic>
#include <stdexcept>

namespace topomill {

// Thrown at a check after SIGINT (or any caller's request_stop()).
class Interrupted : public std::runtime_error {
 public:
  Interrupted();
};

// Installs the SIGINT handler. Safe to call more than once.
void install_interrupt_handler();

// The flag the handler sets; EvaluationRequest::stop points at it.
const std::atomic<bool>& stop_flag();
void request_stop();

// Throws Interrupted if a stop was requested.
void throw_if_interrupted();

}  // namespace topomill
