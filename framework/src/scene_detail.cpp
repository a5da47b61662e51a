#include "scene_detail.hpp"

#include <algorithm>
#include <cstdio>
#include <sstream>

#include "suggest.hpp"

namespace topomill::detail {

namespace {
Value convert(const toml::node& node, const ParamSpec& spec, const std::string& path,
              const Locator& loc);
}  // namespace

// A user's text in a message: control characters (a NUL would cut the message) as \xNN.
std::string printable(const std::string& text) {
  std::string out;
  for (const unsigned char c : text) {
    if (c >= 0x20 && c != 0x7f) {
      out += static_cast<char>(c);
    } else {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02x", c);
      out += buf;
    }
  }
  return out;
}

std::string node_kind(const toml::node& n) {
  switch (n.type()) {
    case toml::node_type::table:
      return "a table";
    case toml::node_type::array:
      return "an array";
    case toml::node_type::string:
      return "the string \"" + std::string(*n.as_string()) + "\"";
    case toml::node_type::integer:
      return "the integer " + std::to_string(n.as_integer()->get());
    case toml::node_type::floating_point:
      return "the number " + number_text(n.as_floating_point()->get());
    case toml::node_type::boolean:
      return n.as_boolean()->get() ? "true" : "false";
    default:
      return "a date or time";
  }
}

std::string number_text(double x) {
  std::ostringstream os;
  os.precision(12);
  os << x;
  return os.str();
}

std::string join(const std::vector<std::string>& names) {
  std::string out;
  for (std::size_t i = 0; i < names.size(); ++i) out += (i ? ", " : "") + names[i];
  return out.empty() ? "(none)" : out;
}

std::string unknown_key_message(const std::string& key, const std::vector<std::string>& valid) {
  return with_candidates("unknown key", key, valid, "Valid keys here");
}

Params check_table(const toml::table& table, const Schema& schema, const std::string& path,
                   const Locator& loc, const std::set<std::string>& reserved) {
  Params params;
  params.set_path(path);
  params.set_table_where(loc.at(path, table.source()));
  std::vector<std::string> valid = schema.names();
  for (const auto& r : reserved) valid.insert(valid.begin(), r);
  for (auto&& [k, node] : table) {
    std::string key(k.str());
    std::string full = path.empty() ? key : path + "." + key;
    if (reserved.count(key)) continue;
    const ParamSpec* spec = schema.find(key);
    if (!spec) throw InputError(loc.at(full, k.source()), full, unknown_key_message(key, valid));
    params.set(key, convert(node, *spec, full, loc), loc.at(full, node.source()));
  }
  for (const auto& spec : schema.specs()) {
    if (params.has(spec.name)) continue;
    std::string full = path.empty() ? spec.name : path + "." + spec.name;
    if (spec.required)
      throw InputError(
          params.table_where(), full,
          "missing required key: expected " + spec.expectation() + " (" + spec.doc + ")");
    if (spec.default_value) params.set(spec.name, *spec.default_value);
  }
  return params;
}

namespace {

double number_of(const toml::node& node, const ParamSpec& spec, const std::string& path,
                 const Locator& loc, const char* what) {
  if (!node.is_number())
    throw InputError(loc.at(path, node.source()), path,
                     std::string("expected ") + what + ", got " + node_kind(node));
  double x = node.is_integer() ? static_cast<double>(node.as_integer()->get())
                               : node.as_floating_point()->get();
  std::string bad = spec.range_violation(x);
  if (!bad.empty())
    throw InputError(
        loc.at(path, node.source()), path,
        "value " + number_text(x) + " is out of range: expected " + spec.expectation());
  return x;
}

Value convert(const toml::node& node, const ParamSpec& spec, const std::string& path,
              const Locator& loc) {
  auto wrong = [&]() {
    return InputError(loc.at(path, node.source()), path,
                      "expected " + spec.expectation() + ", got " + node_kind(node));
  };
  switch (spec.type) {
    case ParamType::Number:
      return number_of(node, spec, path, loc, "a number");
    case ParamType::Integer: {
      if (!node.is_integer()) throw wrong();
      std::int64_t i = node.as_integer()->get();
      if (!spec.range_violation(static_cast<double>(i)).empty())
        throw InputError(
            loc.at(path, node.source()), path,
            "value " + std::to_string(i) + " is out of range: expected " + spec.expectation());
      return i;
    }
    case ParamType::Bool:
      if (!node.is_boolean()) throw wrong();
      return node.as_boolean()->get();
    case ParamType::String:
      if (!node.is_string()) throw wrong();
      return std::string(*node.as_string());
    case ParamType::Choice: {
      if (!node.is_string()) throw wrong();
      std::string v(*node.as_string());
      if (std::find(spec.choices.begin(), spec.choices.end(), v) == spec.choices.end())
        throw wrong();
      return v;
    }
    case ParamType::NumberArray: {
      const toml::array* a = node.as_array();
      if (!a || (spec.length && a->size() != *spec.length)) throw wrong();
      std::vector<double> out;
      for (std::size_t i = 0; i < a->size(); ++i)
        out.push_back(
            number_of((*a)[i], spec, path + "[" + std::to_string(i) + "]", loc, "a number"));
      return out;
    }
    case ParamType::StringArray: {
      const toml::array* a = node.as_array();
      if (!a) throw wrong();
      std::vector<std::string> out;
      for (std::size_t i = 0; i < a->size(); ++i) {
        const toml::node& e = (*a)[i];
        bool ok = e.is_string() && (spec.choices.empty() ||
                                    std::find(spec.choices.begin(), spec.choices.end(),
                                              std::string(*e.as_string())) != spec.choices.end());
        if (!ok) {
          // A misspelt choice gets "did you mean" (e.g. "Vmcc" for Vmc) before the list.
          std::string hint;
          if (e.is_string())
            if (const std::string near = closest_name(std::string(*e.as_string()), spec.choices);
                !near.empty())
              hint = " (did you mean '" + near + "'?)";
          throw InputError(loc.at(path, e.source()), path + "[" + std::to_string(i) + "]",
                           "expected " + spec.expectation() + ", got " + node_kind(e) + hint);
        }
        const std::string v(*e.as_string());
        // A choice is a set member: twice would mean one output written twice (issue 18).
        if (!spec.choices.empty() && std::find(out.begin(), out.end(), v) != out.end())
          throw InputError(loc.at(path, e.source()), path + "[" + std::to_string(i) + "]",
                           "'" + v + "' is listed twice: expected each choice at most once");
        out.push_back(v);
      }
      return out;
    }
    case ParamType::TableArray: {
      const toml::array* a = node.as_array();
      if (!a) throw wrong();
      std::vector<Params> out;
      for (std::size_t i = 0; i < a->size(); ++i) {
        std::string sub = path + "[" + std::to_string(i) + "]";
        const toml::table* t = (*a)[i].as_table();
        if (!t)
          throw InputError(loc.at(sub, (*a)[i].source()), sub,
                           "expected a table, got " + node_kind((*a)[i]));
        out.push_back(check_table(*t, *spec.element, sub, loc, {}));
      }
      return out;
    }
  }
  throw wrong();
}

}  // namespace

const toml::source_region& key_source(const toml::table& t, const std::string& key) {
  for (auto&& [k, v] : t)
    if (k.str() == key) return k.source();
  return t.source();
}

}  // namespace topomill::detail
