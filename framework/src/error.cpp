#include "topomill/error.hpp"

#include <cstdio>

namespace topomill {

std::string SourceRef::str() const {
  if (file.empty()) return "<unknown>";
  if (line <= 0) return file;
  return file + ":" + std::to_string(line) + ":" + std::to_string(column);
}

std::string format_number(double value) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", value);
  return buf;
}

namespace {
std::string compose(const SourceRef& where, const std::string& key, const std::string& message) {
  std::string out = where.str() + ": error: ";
  if (!key.empty()) out += "key '" + key + "': ";
  return out + message;
}
}  // namespace

InputError::InputError(SourceRef where, std::string key, std::string message)
    : std::runtime_error(compose(where, key, message)),
      where_(std::move(where)),
      key_(std::move(key)),
      message_(std::move(message)) {}

InputError::InputError(std::string message)
    : std::runtime_error("error: " + message), message_(std::move(message)) {}

ParamError::ParamError(std::string key, const std::string& message)
    : std::runtime_error(message), key_(std::move(key)) {}

}  // namespace topomill

namespace topomill {
// Key functions: anchor each exception's type information in the core library.
InputError::~InputError() = default;
ParamError::~ParamError() = default;
PluginError::~PluginError() = default;
}  // namespace topomill
