#include "io/file_info.hpp"

#include <charconv>

#include "topomill/version.hpp"

namespace topomill {

std::string file_creator() {
  return std::string("topomill ") + kVersion;
}

std::string iso8601_utc(std::time_t t) {
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[40];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%S+00:00", &tm);
  return buf;
}

std::string exact_text(double v) {
  char buf[32];
  return std::string(buf, std::to_chars(buf, buf + sizeof buf, v).ptr);
}

std::string one_line(std::string text) {
  for (char& c : text)
    if (c == '\n' || c == '\r' || c == '\0') c = ' ';
  return text;
}

std::time_t created_time(const FileInfo& info) {
  return info.created != 0 ? info.created : std::time(nullptr);
}

}  // namespace topomill
