// Model parameters: the schema a model declares (MOOSE validParams style) and the validated
// values it is constructed from. The schema is data: the scene loader checks every table against
// it before any model is built, and `topomill describe` renders it as text, JSON or Markdown.
#pragma once

#include <cstdint>
#include <deque>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "topomill/error.hpp"

namespace topomill {

class Params;

enum class ParamType {
  Number,
  Integer,
  Bool,
  String,
  Choice,
  NumberArray,
  StringArray,
  TableArray
};

// Name used in messages and in the JSON schema ("number", "array of tables", ...).
TOPOMILL_API const char* type_name(ParamType type);

// A validated value. Integers stay integers; numbers are doubles in the scene's units.
using Value = std::variant<double, std::int64_t, bool, std::string, std::vector<double>,
                           std::vector<std::string>, std::vector<Params>>;

class Schema;

// One parameter: its type, unit, default, allowed range or choices, and a one-line doc.
struct TOPOMILL_API ParamSpec {
  std::string name;
  ParamType type = ParamType::Number;
  std::string doc;
  std::string unit;
  std::optional<Value> default_value;  // absent and !required: the key is optional with no value
  bool required = false;
  std::optional<double> min, max;  // numbers, integers and each element of a number array
  bool min_exclusive = false, max_exclusive = false;
  std::vector<std::string> choices;   // Choice, and each element of a StringArray when set
  std::optional<std::size_t> length;  // NumberArray: exact element count
  std::shared_ptr<Schema> element;    // TableArray: schema of each table

  // Chainable setters, used right after Schema::add*.
  ParamSpec& with_unit(std::string u);
  ParamSpec& with_default(Value v);
  ParamSpec& is_required();
  ParamSpec& at_least(double v);
  ParamSpec& above(double v);
  ParamSpec& at_most(double v);
  ParamSpec& below(double v);
  ParamSpec& with_length(std::size_t n);

  // "a number > 0 (mm)", "one of cw, ccw": what the scene must hold, for error messages.
  std::string expectation() const;
  // Empty when `x` is within range, otherwise the violated bound, e.g. "> 0".
  std::string range_violation(double x) const;
  std::string range_text() const;
};

// An ordered list of parameter specs. References returned by add* stay valid (deque).
class TOPOMILL_API Schema {
 public:
  ParamSpec& add_number(std::string name, std::string doc);
  ParamSpec& add_integer(std::string name, std::string doc);
  ParamSpec& add_bool(std::string name, std::string doc);
  ParamSpec& add_string(std::string name, std::string doc);
  ParamSpec& add_choice(std::string name, std::vector<std::string> choices, std::string doc);
  ParamSpec& add_number_array(std::string name, std::string doc);
  ParamSpec& add_string_array(std::string name, std::vector<std::string> choices, std::string doc);
  ParamSpec& add_table_array(std::string name, Schema element, std::string doc);

  const ParamSpec* find(const std::string& name) const;
  const std::deque<ParamSpec>& specs() const { return specs_; }
  std::vector<std::string> names() const;

 private:
  ParamSpec& add(std::string name, ParamType type, std::string doc);
  std::deque<ParamSpec> specs_;
};

// Validated values of one table, with where each came from so that a model's own checks
// (ParamError) can be reported against the scene's file and line.
class TOPOMILL_API Params {
 public:
  void set(const std::string& key, Value value, SourceRef where = {});

  bool has(const std::string& key) const { return values_.count(key) != 0; }
  double number(const std::string& key) const;
  std::int64_t integer(const std::string& key) const;
  bool boolean(const std::string& key) const;
  const std::string& string(const std::string& key) const;
  const std::vector<double>& numbers(const std::string& key) const;
  const std::vector<std::string>& strings(const std::string& key) const;
  const std::vector<Params>& tables(const std::string& key) const;
  const Value& value(const std::string& key) const;

  // Where `key` was set; the table's own position when the key took its default.
  SourceRef where(const std::string& key) const;
  const SourceRef& table_where() const { return table_where_; }
  void set_table_where(SourceRef where) { table_where_ = std::move(where); }
  // Dotted path of this table in the scene ("vibration.modes[1]"), for messages.
  const std::string& path() const { return path_; }
  void set_path(std::string path) { path_ = std::move(path); }

  const std::map<std::string, Value>& values() const { return values_; }

 private:
  template <class T>
  const T& get(const std::string& key, const char* want) const;

  std::map<std::string, Value> values_;
  std::map<std::string, SourceRef> where_;
  SourceRef table_where_;
  std::string path_;
};

}  // namespace topomill
