#include "describe.hpp"

#include <nlohmann/json.hpp>
#include <sstream>

#include "scene.hpp"

namespace topomill {

namespace {
// JSON through nlohmann::json, whose numbers are the shortest text that reads back to the same
// double (0.3 stays 0.3; 0.54274963... keeps all its digits): toml++'s formatter gives either 17
// digits for every number or 6.
nlohmann::json json_of(const toml::node& node) {
  if (const auto* t = node.as_table()) {
    nlohmann::json out = nlohmann::json::object();
    for (const auto& [k, v] : *t) out[std::string(k.str())] = json_of(v);
    return out;
  }
  if (const auto* a = node.as_array()) {
    nlohmann::json out = nlohmann::json::array();
    for (const auto& v : *a) out.push_back(json_of(v));
    return out;
  }
  if (const auto* d = node.as_floating_point()) return d->get();
  if (const auto* i = node.as_integer()) return i->get();
  if (const auto* b = node.as_boolean()) return b->get();
  if (const auto* s = node.as_string()) return s->get();
  std::ostringstream os;  // dates and times: their TOML text
  node.visit([&](auto&& n) { os << n; });
  return os.str();
}

std::string value_text(const Value& v) {
  if (const double* d = std::get_if<double>(&v)) {
    std::ostringstream os;
    os.precision(12);
    os << *d;
    return os.str();
  }
  toml::table t;
  insert_value(t, "v", v);
  std::ostringstream os;
  t.get("v")->visit([&](auto&& node) { os << node; });
  return os.str();
}

std::string constraint_text(const ParamSpec& s) {
  if (s.type == ParamType::Choice || (s.type == ParamType::StringArray && !s.choices.empty())) {
    std::string out;
    for (std::size_t i = 0; i < s.choices.size(); ++i) out += (i ? ", " : "") + s.choices[i];
    return "one of " + out;
  }
  std::string out = s.range_text();
  if (s.length) out += (out.empty() ? "" : ", ") + std::to_string(*s.length) + " elements";
  return out;
}

std::string default_text(const ParamSpec& s) {
  if (s.required) return "required";
  if (!s.default_value) return "optional";
  return value_text(*s.default_value);
}
}  // namespace

toml::array schema_to_toml(const Schema& schema) {
  toml::array params;
  for (const auto& s : schema.specs()) {
    toml::table p{
        {"name", s.name}, {"type", type_name(s.type)}, {"doc", s.doc}, {"required", s.required}};
    if (!s.unit.empty()) p.insert("unit", s.unit);
    if (s.default_value) insert_value(p, "default", *s.default_value);
    if (s.min) p.insert("min", *s.min), p.insert("min_exclusive", s.min_exclusive);
    if (s.max) p.insert("max", *s.max), p.insert("max_exclusive", s.max_exclusive);
    if (!s.choices.empty()) {
      toml::array c;
      for (const auto& x : s.choices) c.push_back(x);
      p.insert("choices", std::move(c));
    }
    if (s.length) p.insert("length", static_cast<std::int64_t>(*s.length));
    if (s.element) p.insert("element", schema_to_toml(*s.element));
    params.push_back(std::move(p));
  }
  return params;
}

toml::table model_to_toml(const ModelEntry& e) {
  return toml::table{{"name", e.info.name},
                     {"slot", slot_id(e.info.slot)},
                     {"doc", e.info.doc},
                     {"library", e.library->path},
                     {"library_name", e.library->name},
                     {"library_version", e.library->version},
                     {"parameters", schema_to_toml(e.schema)}};
}

std::string schema_text(const Schema& schema, const std::string& indent) {
  std::ostringstream os;
  for (const auto& s : schema.specs()) {
    os << indent << s.name << " (" << type_name(s.type);
    if (!s.unit.empty()) os << ", " << s.unit;
    os << ", " << default_text(s);
    std::string c = constraint_text(s);
    if (!c.empty()) os << ", " << c;
    os << ")\n" << indent << "    " << s.doc << "\n";
    if (s.element) os << schema_text(*s.element, indent + "    ");
  }
  return os.str();
}

std::string schema_markdown(const Schema& schema) {
  std::ostringstream os;
  os << "| key | type | unit | default | allowed | description |\n";
  os << "|---|---|---|---|---|---|\n";
  for (const auto& s : schema.specs()) {
    os << "| `" << s.name << "` | " << type_name(s.type) << " | " << s.unit << " | "
       << default_text(s) << " | " << constraint_text(s) << " | " << s.doc << " |\n";
  }
  for (const auto& s : schema.specs()) {
    if (!s.element) continue;
    os << "\nEach table of `" << s.name << "`:\n\n" << schema_markdown(*s.element);
  }
  return os.str();
}

std::string to_toml_text(const toml::table& table) {
  std::ostringstream os;
  os << toml::toml_formatter{table, toml::toml_formatter::default_flags |
                                        toml::format_flags::relaxed_float_precision}
     << "\n";
  return os.str();
}

std::string to_json(const toml::table& table) {
  return json_of(table).dump(4) + "\n";
}

std::string to_json(const toml::array& array) {
  return json_of(array).dump(4) + "\n";
}

toml::table grid_table(const Grid& g) {
  return toml::table{{"nx", static_cast<std::int64_t>(g.nx)},
                     {"ny", static_cast<std::int64_t>(g.ny)},
                     {"dx_mm", g.dx},
                     {"dy_mm", g.dy},
                     {"x0_mm", g.x0},
                     {"y0_mm", g.y0}};
}

}  // namespace topomill
