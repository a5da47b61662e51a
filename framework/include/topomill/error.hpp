// Error types shared by the core and every plugin. The host copies messages out of these, so a
// plugin never has to know how errors are reported.
#pragma once

#include <stdexcept>
#include <string>

#include "topomill/export.hpp"

namespace topomill {

// Where a value came from: a scene file position, or a command-line override.
struct TOPOMILL_API SourceRef {
  std::string file;  // path, or "--set key=value" for overrides; empty when unknown
  int line = 0;      // 1-based; 0 when the origin has no line (command line, defaults)
  int column = 0;

  // "file:line:col", "file" or "--set ..." as appropriate.
  std::string str() const;
};

// A number for a message: six significant digits ("1e+300", not std::to_string's 300 digits).
TOPOMILL_API std::string format_number(double value);

// Bad input: a scene, an option or a file. The program exits with code 2.
class TOPOMILL_API InputError : public std::runtime_error {
 public:
  InputError(SourceRef where, std::string key, std::string message);
  explicit InputError(std::string message);

  const SourceRef& where() const { return where_; }
  const std::string& key() const { return key_; }
  const std::string& message() const { return message_; }
  ~InputError() override;

 private:
  SourceRef where_;
  std::string key_;
  std::string message_;
};

// Thrown by a model's constructor when a parameter (or a combination of parameters) is
// unacceptable. The host turns it into an InputError that names the scene file and line of `key`.
class TOPOMILL_API ParamError : public std::runtime_error {
 public:
  ParamError(std::string key, const std::string& message);
  const std::string& key() const { return key_; }
  ~ParamError() override;

 private:
  std::string key_;
};

// A plugin library that cannot be used (missing entry point, ABI mismatch, duplicate name).
class TOPOMILL_API PluginError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
  ~PluginError() override;
};

}  // namespace topomill
