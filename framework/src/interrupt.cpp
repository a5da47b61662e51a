#include "interrupt.hpp"

#include <csignal>

namespace topomill {

namespace {
std::atomic<bool> g_stop{false};
std::atomic<int> g_signal{0};
static_assert(std::atomic<bool>::is_always_lock_free, "the signal handler needs a lock-free flag");
static_assert(std::atomic<int>::is_always_lock_free, "the signal handler needs a lock-free flag");

extern "C" void on_stop_signal(int signal) {
  int none = 0;
  g_signal.compare_exchange_strong(none, signal);  // the first signal is the one reported
  g_stop.store(true);
}
}  // namespace

Interrupted::Interrupted()
    : std::runtime_error("interrupted (" + signal_name(stop_signal()) +
                         "): the run stopped before writing its outputs") {}

Interrupted::~Interrupted() = default;

bool stop_requested() {
  return g_stop.load();
}

void install_interrupt_handler() {
  struct sigaction sa {};
  sa.sa_handler = on_stop_signal;
  sa.sa_flags = SA_RESETHAND;  // the same signal again ends the process at once
  sigemptyset(&sa.sa_mask);
  for (const int s : {SIGINT, SIGTERM, SIGHUP}) sigaction(s, &sa, nullptr);
}

const std::atomic<bool>& stop_flag() {
  return g_stop;
}

int stop_signal() {
  const int s = g_signal.load();
  return s ? s : SIGINT;
}

void request_stop() {
  on_stop_signal(SIGINT);
}

void clear_stop() {
  g_signal.store(0);
  g_stop.store(false);
}

std::string signal_name(int signal) {
  switch (signal) {
    case SIGTERM:
      return "SIGTERM";
    case SIGHUP:
      return "SIGHUP";
    default:
      return "SIGINT";
  }
}

void throw_if_interrupted() {
  if (g_stop.load()) throw Interrupted();
}

}  // namespace topomill
