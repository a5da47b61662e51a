#include "log.hpp"

#include <iostream>
#include <mutex>

namespace topomill {
namespace {
LogLevel g_level = LogLevel::Normal;
std::mutex g_mutex;

void emit(const char* tag, const std::string& message) {
  std::lock_guard<std::mutex> lock(g_mutex);
  std::cerr << "topomill: " << tag << message << '\n';
}
}  // namespace

void set_log_level(LogLevel level) {
  g_level = level;
}
LogLevel log_level() {
  return g_level;
}
void log_info(const std::string& message) {
  if (g_level >= LogLevel::Normal) emit("", message);
}
void log_debug(const std::string& message) {
  if (g_level >= LogLevel::Verbose) emit("", message);
}
void log_warning(const std::string& message) {
  emit("warning: ", message);
}

}  // namespace topomill
