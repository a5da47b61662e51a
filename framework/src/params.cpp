#include "topomill/params.hpp"

#include <cmath>
#include <sstream>

namespace topomill {

const char* type_name(ParamType type) {
  switch (type) {
    case ParamType::Number:
      return "number";
    case ParamType::Integer:
      return "integer";
    case ParamType::Bool:
      return "boolean";
    case ParamType::String:
      return "string";
    case ParamType::Choice:
      return "choice";
    case ParamType::NumberArray:
      return "array of numbers";
    case ParamType::StringArray:
      return "array of strings";
    case ParamType::TableArray:
      return "array of tables";
  }
  return "?";
}

namespace {
std::string fmt(double v) {
  std::ostringstream os;
  os.precision(12);
  os << v;
  return os.str();
}
}  // namespace

ParamSpec& ParamSpec::with_unit(std::string u) {
  unit = std::move(u);
  return *this;
}
ParamSpec& ParamSpec::with_default(Value v) {
  default_value = std::move(v);
  return *this;
}
ParamSpec& ParamSpec::is_required() {
  required = true;
  return *this;
}
ParamSpec& ParamSpec::at_least(double v) {
  min = v;
  min_exclusive = false;
  return *this;
}
ParamSpec& ParamSpec::above(double v) {
  min = v;
  min_exclusive = true;
  return *this;
}
ParamSpec& ParamSpec::at_most(double v) {
  max = v;
  max_exclusive = false;
  return *this;
}
ParamSpec& ParamSpec::below(double v) {
  max = v;
  max_exclusive = true;
  return *this;
}
ParamSpec& ParamSpec::with_length(std::size_t n) {
  length = n;
  return *this;
}

std::string ParamSpec::range_text() const {
  std::string lo = min ? std::string(min_exclusive ? "> " : ">= ") + fmt(*min) : "";
  std::string hi = max ? std::string(max_exclusive ? "< " : "<= ") + fmt(*max) : "";
  if (!lo.empty() && !hi.empty()) return lo + " and " + hi;
  return lo + hi;
}

std::string ParamSpec::range_violation(double x) const {
  bool low = min && (min_exclusive ? !(x > *min) : !(x >= *min));
  bool high = max && (max_exclusive ? !(x < *max) : !(x <= *max));
  if (std::isnan(x) || low || high) return range_text().empty() ? "finite" : range_text();
  if (!std::isfinite(x)) return "finite";
  return "";
}

std::string ParamSpec::expectation() const {
  std::string out;
  switch (type) {
    case ParamType::Choice: {
      out = "one of ";
      for (std::size_t i = 0; i < choices.size(); ++i) out += (i ? ", " : "") + choices[i];
      return out;
    }
    case ParamType::NumberArray:
      out = length ? "an array of " + std::to_string(*length) + " numbers" : "an array of numbers";
      if (!range_text().empty()) out += ", each " + range_text();
      break;
    case ParamType::StringArray: {
      if (choices.empty()) return "an array of strings";
      out = "an array of strings, each one of ";
      for (std::size_t i = 0; i < choices.size(); ++i) out += (i ? ", " : "") + choices[i];
      return out;
    }
    case ParamType::TableArray:
      return "an array of tables";
    case ParamType::Integer:
      out = "an integer";
      break;
    case ParamType::Bool:
      return "a boolean (true or false)";
    case ParamType::String:
      return "a string";
    case ParamType::Number:
      out = "a number";
      break;
  }
  if (type != ParamType::NumberArray && !range_text().empty()) out += " " + range_text();
  if (!unit.empty()) out += " (" + unit + ")";
  return out;
}

ParamSpec& Schema::add(std::string name, ParamType type, std::string doc) {
  ParamSpec spec;
  spec.name = std::move(name);
  spec.type = type;
  spec.doc = std::move(doc);
  specs_.push_back(std::move(spec));
  return specs_.back();
}

ParamSpec& Schema::add_number(std::string name, std::string doc) {
  return add(std::move(name), ParamType::Number, std::move(doc));
}
ParamSpec& Schema::add_integer(std::string name, std::string doc) {
  return add(std::move(name), ParamType::Integer, std::move(doc));
}
ParamSpec& Schema::add_bool(std::string name, std::string doc) {
  return add(std::move(name), ParamType::Bool, std::move(doc));
}
ParamSpec& Schema::add_string(std::string name, std::string doc) {
  return add(std::move(name), ParamType::String, std::move(doc));
}
ParamSpec& Schema::add_choice(std::string name, std::vector<std::string> choices, std::string doc) {
  ParamSpec& s = add(std::move(name), ParamType::Choice, std::move(doc));
  s.choices = std::move(choices);
  return s;
}
ParamSpec& Schema::add_number_array(std::string name, std::string doc) {
  return add(std::move(name), ParamType::NumberArray, std::move(doc));
}
ParamSpec& Schema::add_string_array(std::string name, std::vector<std::string> choices,
                                    std::string doc) {
  ParamSpec& s = add(std::move(name), ParamType::StringArray, std::move(doc));
  s.choices = std::move(choices);
  return s;
}
ParamSpec& Schema::add_table_array(std::string name, Schema element, std::string doc) {
  ParamSpec& s = add(std::move(name), ParamType::TableArray, std::move(doc));
  s.element = std::make_shared<Schema>(std::move(element));
  return s;
}

const ParamSpec* Schema::find(const std::string& name) const {
  for (const auto& s : specs_)
    if (s.name == name) return &s;
  return nullptr;
}

std::vector<std::string> Schema::names() const {
  std::vector<std::string> out;
  for (const auto& s : specs_) out.push_back(s.name);
  return out;
}

void Params::set(const std::string& key, Value value, SourceRef where) {
  values_[key] = std::move(value);
  where_[key] = std::move(where);
}

const Value& Params::value(const std::string& key) const {
  auto it = values_.find(key);
  if (it == values_.end())
    throw std::logic_error("parameter '" + (path_.empty() ? key : path_ + "." + key) +
                           "' was read but is not in the model's schema");
  return it->second;
}

template <class T>
const T& Params::get(const std::string& key, const char* want) const {
  const Value& v = value(key);
  if (const T* p = std::get_if<T>(&v)) return *p;
  throw std::logic_error("parameter '" + key + "' is not " + want);
}

double Params::number(const std::string& key) const {
  const Value& v = value(key);
  if (const auto* i = std::get_if<std::int64_t>(&v)) return static_cast<double>(*i);
  return get<double>(key, "a number");
}
std::int64_t Params::integer(const std::string& key) const {
  return get<std::int64_t>(key, "an integer");
}
bool Params::boolean(const std::string& key) const {
  return get<bool>(key, "a boolean");
}
const std::string& Params::string(const std::string& key) const {
  return get<std::string>(key, "a string");
}
const std::vector<double>& Params::numbers(const std::string& key) const {
  return get<std::vector<double>>(key, "an array of numbers");
}
const std::vector<std::string>& Params::strings(const std::string& key) const {
  return get<std::vector<std::string>>(key, "an array of strings");
}
const std::vector<Params>& Params::tables(const std::string& key) const {
  return get<std::vector<Params>>(key, "an array of tables");
}

SourceRef Params::where(const std::string& key) const {
  auto it = where_.find(key);
  if (it == where_.end() || it->second.file.empty()) return table_where_;
  return it->second;
}

}  // namespace topomill
