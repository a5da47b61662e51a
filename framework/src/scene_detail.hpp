// What scene.cpp checks a scene's tables with: positions for messages (Locator), the values
// against a schema (check_table), and the wording of what was found. Internal to the host.
#pragma once

#include <map>
#include <set>
#include <string>
#include <vector>

#include <toml++/toml.h>

#include "topomill/error.hpp"
#include "topomill/params.hpp"

namespace topomill::detail {

// Resolves positions: a --set override, or the node's place in the file.
class Locator {
 public:
  Locator(const std::string& file, const std::map<std::string, SourceRef>& overrides)
      : file_(file), overrides_(overrides) {}

  SourceRef at(const std::string& path, const toml::source_region& src) const {
    auto it = overrides_.find(path);
    if (it != overrides_.end()) return it->second;
    // A path under an override (a table written by --set) has the override's origin.
    for (const auto& [key, ref] : overrides_)
      if (path.rfind(key + ".", 0) == 0 || path.rfind(key + "[", 0) == 0) return ref;
    SourceRef r{file_, static_cast<int>(src.begin.line), static_cast<int>(src.begin.column)};
    if (r.line == 0) r.file = file_;
    return r;
  }

 private:
  const std::string& file_;
  const std::map<std::string, SourceRef>& overrides_;
};

// A user's text in a message: control characters (a NUL would cut the message) as \xNN.
std::string printable(const std::string& text);
// What a node is, for "expected ..., got ..." ("the string \"x\"", "an array").
std::string node_kind(const toml::node& n);
// A number as messages write it: 12 significant digits.
std::string number_text(double x);
// Names joined with commas; "(none)" for none.
std::string join(const std::vector<std::string>& names);
std::string unknown_key_message(const std::string& key, const std::vector<std::string>& valid);
// The table's values checked against the schema (every key known, every value of its type and
// in its range), under `path`; keys in `reserved` pass unchecked.
Params check_table(const toml::table& table, const Schema& schema, const std::string& path,
                   const Locator& loc, const std::set<std::string>& reserved);
// Where `key` is written in t (the table's own place when it is not).
const toml::source_region& key_source(const toml::table& t, const std::string& key);

}  // namespace topomill::detail
