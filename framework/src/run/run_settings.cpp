#include "run/run_settings.hpp"

#include <sstream>

#include "describe.hpp"
#include "io/file_info.hpp"
#include "plugin_catalog.hpp"

namespace topomill {

namespace {

// A scene value as a reader writes it: 0.3 (the shortest exact text, not 0.29999999999999999),
// cw (no quotes), [0.86, 0.86].
std::string value_text(const toml::node& v) {
  if (const auto* d = v.as_floating_point()) return exact_text(d->get());
  if (const auto* text = v.as_string()) return text->get();
  if (const auto* a = v.as_array()) {
    std::string out = "[";
    for (const auto& e : *a) out += (out.size() > 1 ? ", " : "") + value_text(e);
    return out + "]";
  }
  std::ostringstream os;
  v.visit([&](auto&& n) { os << n; });
  return os.str();
}

// The scene in one line for the files' comments: its name, then each table's model and its
// keys as resolved ("tool ball_end_loxodrome (radius 5, teeth 2, ...); cutting (...); ...").
std::string describe_scene(const std::string& name, const toml::table& resolved) {
  std::ostringstream os;
  os << name;
  for (const char* table : {"tool", "workpiece", "cutting", "path", "region", "evaluator", "force",
                            "vibration", "deflection", "springback"}) {
    const toml::table* t = resolved[table].as_table();
    if (!t) continue;
    os << "; " << table;
    if (const auto* plugin = t->get_as<std::string>("plugin")) os << " " << plugin->get();
    std::string keys;
    for (const auto& [k, v] : *t) {
      if (k.str() == "plugin" || v.is_table() || v.is_array_of_tables()) continue;
      keys += (keys.empty() ? "" : ", ") + std::string(k.str()) + " " + value_text(v);
    }
    if (!keys.empty()) os << " (" << keys << ")";
  }
  return os.str();
}

}  // namespace

RunSettings RunSettings::read(const Scene& scene) {
  RunSettings s;
  s.file = scene.file;
  s.name = scene.table("scene").string("name");
  s.form = scene.table("analysis").string("form");
  s.formats = scene.table("output").strings("formats");
  s.depth_of_cut = scene.table("cutting").number("depth_of_cut");
  s.resolved = scene.to_toml();
  s.described = describe_scene(s.name, s.resolved);
  for (const auto& [table, st] : scene.slots)
    if (st.model)
      s.plugins.push_back({table, st.plugin, st.model->library->path, st.model->library->version});
  return s;
}

}  // namespace topomill
