// Stopping on request: SIGINT (Ctrl-C), SIGTERM (kill, timeout, batch schedulers) and SIGHUP (a
// closed terminal) all ask the run to stop at the next check (between stages, between rows of
// the evaluator, between output files) so that it ends with a clear message, writes nothing and
// exits with 128 + the signal's number; the same signal a second time kills at once.
#pragma once

#include <atomic>
#include <string>

#include "topomill/interrupt.hpp"

namespace topomill {

// Installs the handlers for SIGINT, SIGTERM and SIGHUP. Safe to call more than once.
void install_interrupt_handler();

// The flag the handlers set; EvaluationRequest::stop points at it.
const std::atomic<bool>& stop_flag();

// The signal that asked to stop (SIGINT when none did: a stop raised by other means).
int stop_signal();
// A stop asked for by the host itself (the Python module on KeyboardInterrupt), reported as
// SIGINT; and the flag cleared again once the run has stopped, so that the process can run more.
void request_stop();
void clear_stop();
// "SIGINT", "SIGTERM", "SIGHUP".
std::string signal_name(int signal);

}  // namespace topomill
