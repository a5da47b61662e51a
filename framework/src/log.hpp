// The run log: one line per event on stderr. Quiet keeps warnings only.
#pragma once

#include <string>

namespace topomill {

enum class LogLevel { Quiet = 0, Normal = 1, Verbose = 2 };

void set_log_level(LogLevel level);
LogLevel log_level();
void log_info(const std::string& message);
void log_debug(const std::string& message);
void log_warning(const std::string& message);

}  // namespace topomill
