#include "interrupt.hpp"

#include <csignal>

namespace topomill {

namespace {
std::atomic<bool> g_stop{false};
static_assert(std::atomic<bool>::is_always_lock_free, "the signal handler needs a lock-free flag");

extern "C" void on_sigint(int) {
  g_stop.store(true);
}
}  // namespace

Interrupted::Interrupted()
    : std::runtime_error("interrupted (SIGINT): the run stopped before writing its outputs") {}

void install_interrupt_handler() {
  struct sigaction sa {};
  sa.sa_handler = on_sigint;
  sa.sa_flags = SA_RESETHAND;  // a second Ctrl-C ends the process at once
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, nullptr);
}

const std::atomic<bool>& stop_flag() {
  return g_stop;
}

void throw_if_interrupted() {
  if (g_stop.load()) throw Interrupted();
}

}  // namespace topomill
