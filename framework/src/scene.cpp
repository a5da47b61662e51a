#include "scene.hpp"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "io/read_file.hpp"
#include "scene_detail.hpp"
#include "suggest.hpp"

namespace fs = std::filesystem;

namespace topomill {

using detail::check_table;
using detail::join;
using detail::key_source;
using detail::Locator;
using detail::node_kind;
using detail::printable;
using detail::unknown_key_message;

namespace {

struct SlotTableSpec {
  const char* table;
  Slot slot;
  bool required;
  const char* default_plugin;  // used when the table is absent; nullptr: none
  bool effect;
};

const std::vector<SlotTableSpec>& slot_table_specs() {
  static const std::vector<SlotTableSpec> specs = {
      {"tool", Slot::ToolGeometry, true, nullptr, false},
      {"workpiece", Slot::SurfaceShape, true, nullptr, false},
      {"path", Slot::Path, false, "raster", false},
      {"force", Slot::ForceModel, false, nullptr, false},
      {"vibration", Slot::DynamicsModel, false, nullptr, true},
      {"deflection", Slot::Deformation, false, nullptr, true},
      {"springback", Slot::Deformation, false, nullptr, true},
      {"evaluator", Slot::Evaluator, false, "tooth_passage", false},
  };
  return specs;
}

const std::set<std::string> kRequiredCore = {"cutting", "region"};
// Core tables that are left out of the scene when absent (an effect that costs nothing then).
const std::set<std::string> kOptionalCore = {"runout"};

toml::table parse_or_throw(const std::string& text, const std::string& name) {
  try {
    return toml::parse(text, name);
  } catch (const toml::parse_error& e) {
    throw InputError(SourceRef{name, static_cast<int>(e.source().begin.line),
                               static_cast<int>(e.source().begin.column)},
                     "", "malformed TOML: " + std::string(e.description()));
  }
}

// Only known tables at the top level, and plugin_paths.
void check_top_level(const toml::table& root, const Locator& loc) {
  std::vector<std::string> top = {"plugin_paths"};
  for (const auto& [name, schema] : core_schemas()) top.push_back(name);
  for (const auto& s : slot_table_specs()) top.push_back(s.table);
  for (auto&& [k, node] : root) {
    std::string key(k.str());
    if (std::find(top.begin(), top.end(), key) == top.end())
      throw InputError(loc.at(key, k.source()), key, unknown_key_message(key, top));
    if (key != "plugin_paths" && !node.is_table())
      throw InputError(loc.at(key, node.source()), key,
                       "expected a table [" + key + "], got " + node_kind(node));
  }
}

// A slot table's presence and whether it is enabled (an effect can be switched off), refusing
// what cannot stand in it.
SlotTable select_slot(const SlotTableSpec& spec, const toml::table* t, const Locator& loc,
                      const SourceRef& file_only) {
  SlotTable st;
  st.table = spec.table;
  st.slot = spec.slot;
  st.present = t != nullptr;
  st.where = t ? loc.at(spec.table, t->source()) : file_only;
  st.enabled = st.present;
  if (t && spec.effect) {
    if (const toml::node* e = t->get("enabled")) {
      std::string full = std::string(spec.table) + ".enabled";
      if (!e->is_boolean())
        throw InputError(loc.at(full, e->source()), full,
                         "expected a boolean (true or false), got " + node_kind(*e));
      st.enabled = e->as_boolean()->get();
    }
  }
  if (!t && spec.required)
    throw InputError(file_only, spec.table,
                     std::string("missing required table [") + spec.table + "] selecting a " +
                         slot_name(spec.slot) + " with plugin = \"...\"");
  if (t && !spec.effect && t->contains("enabled"))
    throw InputError(loc.at(std::string(spec.table) + ".enabled", key_source(*t, "enabled")),
                     std::string(spec.table) + ".enabled",
                     std::string("unknown key: only the effect tables (vibration, deflection, "
                                 "springback) can be switched off"));
  // The path was a core table choosing among built-in strategies; it is a slot now. Refused,
  // not kept as an alias: one way to say it, and an old scene is told exactly what to write.
  if (t && std::string(spec.table) == "path" && t->contains("strategy")) {
    const toml::node* n = t->get("strategy");
    const std::string was = n->is_string() ? std::string(*n->as_string()) : "raster";
    const bool known = was == "raster" || was == "raster_across";
    throw InputError(loc.at("path.strategy", key_source(*t, "strategy")), "path.strategy",
                     "path.strategy is gone: the tool path is a plugin slot now; write plugin = "
                     "\"" +
                         (known ? was : std::string("raster")) +
                         "\" in [path] instead (`topomill plugins` lists the tool paths: "
                         "raster, raster_across, zigzag)");
  }
  return st;
}

// The model a used slot table names (or its default), found in the catalog for its slot, and the
// table's values checked against the model's schema.
void resolve_model(const SlotTableSpec& spec, SlotTable& st, const toml::table* t,
                   PluginCatalog& catalog, const Locator& loc) {
  std::string plugin_key = std::string(spec.table) + ".plugin";
  const toml::node* pn = t ? t->get("plugin") : nullptr;
  SourceRef plugin_where = pn ? loc.at(plugin_key, pn->source()) : st.where;
  if (pn && !pn->is_string())
    throw InputError(plugin_where, plugin_key,
                     "expected the name of a " + std::string(slot_name(spec.slot)) +
                         " model, got " + node_kind(*pn));
  if (pn) {
    st.plugin = std::string(*pn->as_string());
    if (!is_model_name(st.plugin))  // before any library is looked for
      throw InputError(plugin_where, plugin_key,
                       "'" + printable(st.plugin) +
                           "' is not a model name: expected letters, digits and underscores "
                           "(up to 128), as in libtopomill_NAME.so");
  } else if (spec.default_plugin) {
    st.plugin = spec.default_plugin;
  } else {
    throw InputError(
        st.where, plugin_key,
        std::string("missing required key: the name of a ") + slot_name(spec.slot) + " model");
  }

  const ModelEntry* entry = nullptr;
  try {
    entry = catalog.find(st.plugin);
  } catch (const PluginError& e) {
    throw InputError(plugin_where, plugin_key, e.what());
  }
  if (entry && entry->info.slot != spec.slot)
    throw InputError(plugin_where, plugin_key,
                     std::string("unknown ") + slot_name(spec.slot) + " '" + st.plugin + "' ('" +
                         st.plugin + "' is a " + slot_name(entry->info.slot) +
                         "; `topomill plugins` lists the models per slot)");
  if (!entry) {
    // Listed from file names: a misspelt name opens no library (what each one is, per slot,
    // is `topomill plugins`, which opens them all).
    const std::vector<std::string> known = catalog.available_names();
    throw InputError(
        plugin_where, plugin_key,
        with_candidates(std::string("unknown ") + slot_name(spec.slot) + " '" + st.plugin + "'",
                        st.plugin, known,
                        "Models on the plugin search path (`topomill plugins` "
                        "lists them per slot)"));
  }
  st.model = entry;
  static const toml::table empty;
  std::set<std::string> reserved = {"plugin"};
  if (spec.effect) reserved.insert("enabled");
  st.params = check_table(t ? *t : empty, entry->schema, spec.table, loc, reserved);
  st.params.set_table_where(st.where);
}

}  // namespace

std::string SceneDocument::read_file(const std::string& path) {
  // A scene is a few kilobytes: 16 MiB is far beyond any, and a device or a directory given as
  // the scene is named as such (a directory read as "missing required table [cutting]").
  constexpr std::uint64_t kSceneMaxBytes = 16u << 20;
  return read_file_bounded(path, kSceneMaxBytes, "a scene file (TOML)");
}

SceneDocument SceneDocument::parse_file(const std::string& path) {
  return parse_string(read_file(path), path);
}

SceneDocument SceneDocument::parse_string(const std::string& text, const std::string& name) {
  SceneDocument doc;
  doc.file_ = name;
  doc.root_ = std::make_shared<toml::table>(parse_or_throw(text, name));
  return doc;
}

void SceneDocument::apply_override(const std::string& assignment) {
  SourceRef origin{"--set " + assignment};
  auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0)
    throw InputError(origin, "", "expected --set key=value, for example --set tool.radius=4");
  std::string path = assignment.substr(0, eq);
  std::string text = assignment.substr(eq + 1);

  // One value on one line: a newline would let the rest of the text add tables of its own
  // ("scene.name=\"x\"\n[evil]\na=1" kept "x" and dropped the rest without a word).
  if (text.find_first_of("\n\r") != std::string::npos)
    throw InputError(SourceRef{"--set " + printable(assignment)}, path,
                     "the value holds a line break: expected one TOML value on one line");
  // The value as TOML if it reads as one ("4", "true", "[1, 2]", "\"cw\""), else a bare string.
  toml::table parsed;
  try {
    parsed = toml::parse("v = " + text);
  } catch (const toml::parse_error&) {
    parsed = toml::table{{"v", text}};
  }
  if (parsed.size() != 1)
    throw InputError(origin, path, "expected one TOML value, got '" + text + "'");

  // Walk "a.b[2].c", creating tables on the way; a table made here is the override's, so that a
  // message about it (an unknown table 'a') names the --set, not the scene file.
  toml::table* table = root_.get();
  std::size_t start = 0;
  while (true) {
    std::size_t dot = path.find('.', start);
    std::string part =
        path.substr(start, dot == std::string::npos ? std::string::npos : dot - start);
    std::size_t bracket = part.find('[');
    std::string key = part.substr(0, bracket);
    if (key.empty()) throw InputError(origin, path, "empty key name");
    if (dot == std::string::npos) {
      if (bracket != std::string::npos)
        throw InputError(origin, path, "cannot replace an array element; set the whole array");
      parsed.get("v")->visit([&](auto&& node) { table->insert_or_assign(key, node); });
      break;
    }
    if (bracket != std::string::npos) {
      // "key[N]" exactly: digits and a closing bracket, nothing else (std::stoul would throw
      // on "x" and read "1x]" as 1).
      const std::string digits = part.substr(bracket + 1, part.size() - bracket - 2);
      if (part.back() != ']' || digits.empty() || digits.size() > 9 ||
          digits.find_first_not_of("0123456789") != std::string::npos)
        throw InputError(
            origin, path,
            "'" + part + "': expected an element number in brackets, such as " + key + "[0]");
      const std::size_t index = std::stoul(digits);
      toml::array* arr = (*table)[key].as_array();
      if (!arr || index >= arr->size() || !(*arr)[index].as_table())
        throw InputError(origin, path, "'" + part + "' is not an element of an array of tables");
      table = (*arr)[index].as_table();
    } else {
      if (!table->contains(key)) {
        table->insert(key, toml::table{});
        overrides_.emplace(path.substr(0, dot), origin);
      }
      table = (*table)[key].as_table();
      if (!table) throw InputError(origin, path, "'" + key + "' is not a table");
    }
    start = dot + 1;
  }
  overrides_[path] = origin;
}

std::vector<std::string> SceneDocument::plugin_paths(bool allowed) const {
  std::vector<std::string> out;
  const toml::node* node = root_->get("plugin_paths");
  if (!node) return out;
  Locator loc(file_, overrides_);
  if (!allowed)
    throw InputError(loc.at("plugin_paths", node->source()), "plugin_paths",
                     "this scene names plugin directories, and scene plugin paths are refused "
                     "(--no-scene-plugin-paths or TOPOMILL_NO_SCENE_PLUGIN_PATHS): a plugin "
                     "runs code; pass trusted directories with --plugin-path instead");
  const toml::array* a = node->as_array();
  if (!a)
    throw InputError(loc.at("plugin_paths", node->source()), "plugin_paths",
                     "expected an array of directory names, got " + node_kind(*node));
  fs::path base = fs::path(file_).parent_path();
  for (std::size_t i = 0; i < a->size(); ++i) {
    if (!(*a)[i].is_string())
      throw InputError(loc.at("plugin_paths", (*a)[i].source()), "plugin_paths",
                       "expected a directory name, got " + node_kind((*a)[i]));
    fs::path p(std::string(*(*a)[i].as_string()));
    out.push_back((p.is_relative() ? base / p : p).lexically_normal().string());
  }
  return out;
}

Scene SceneDocument::resolve(PluginCatalog& catalog, bool check_unused) const {
  Locator loc(file_, overrides_);
  Scene scene;
  scene.file = file_;
  scene.plugin_paths = plugin_paths();

  check_top_level(*root_, loc);

  SourceRef file_only{file_};
  for (const auto& [name, schema] : core_schemas()) {
    const toml::table* t = root_->get_as<toml::table>(name);
    if (!t && kRequiredCore.count(name))
      throw InputError(file_only, name, "missing required table [" + name + "]");
    static const toml::table empty;
    if (!t && kOptionalCore.count(name)) continue;
    scene.core[name] = check_table(t ? *t : empty, schema, name, loc, {});
  }

  // Which slot tables this run uses: effects when enabled, [force] when any effect is.
  bool any_effect = false;
  for (const auto& spec : slot_table_specs()) {
    const toml::table* t = root_->get_as<toml::table>(spec.table);
    SlotTable st = select_slot(spec, t, loc, file_only);
    if (spec.effect) any_effect = any_effect || st.enabled;
    scene.slots[spec.table] = std::move(st);
  }
  // [force] serves the effects: without an enabled effect its library is never opened.
  scene.slots["force"].enabled = any_effect && scene.slots["force"].present;
  if (any_effect && !scene.slots["force"].present) {
    std::string effects = join(scene.enabled_effects());
    throw InputError(file_only, "force",
                     "missing table [force]: the enabled effects (" + effects +
                         ") need a force model, e.g. [force] plugin = \"armarego\"");
  }

  for (const auto& spec : slot_table_specs()) {
    SlotTable& st = scene.slots[spec.table];
    const toml::table* t = root_->get_as<toml::table>(spec.table);
    bool used = st.enabled || (!t && spec.default_plugin);
    if (!used && !(check_unused && t)) continue;

    resolve_model(spec, st, t, catalog, loc);
    if (!used) st.model = nullptr;  // checked only
  }
  return scene;
}

std::vector<std::string> Scene::enabled_effects() const {
  std::vector<std::string> out;
  for (const auto& name : effect_tables())
    if (slots.at(name).enabled) out.push_back(name);
  return out;
}

void insert_value(toml::table& out, const std::string& key, const Value& value) {
  std::visit(
      [&](const auto& v) {
        using T = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<T, std::vector<double>> ||
                      std::is_same_v<T, std::vector<std::string>>) {
          toml::array a;
          for (const auto& x : v) a.push_back(x);
          out.insert_or_assign(key, std::move(a));
        } else if constexpr (std::is_same_v<T, std::vector<Params>>) {
          toml::array a;
          for (const auto& p : v) a.push_back(params_to_toml(p));
          out.insert_or_assign(key, std::move(a));
        } else {
          out.insert_or_assign(key, v);
        }
      },
      value);
}

toml::table params_to_toml(const Params& params) {
  toml::table t;
  for (const auto& [key, value] : params.values()) insert_value(t, key, value);
  return t;
}

toml::table Scene::to_toml() const {
  toml::table root;
  if (!plugin_paths.empty()) {
    toml::array a;
    for (const auto& p : plugin_paths) a.push_back(p);
    root.insert("plugin_paths", std::move(a));
  }
  for (const auto& [name, params] : core) root.insert(name, params_to_toml(params));
  for (const auto& [name, st] : slots) {
    if (!st.model) continue;
    toml::table t = params_to_toml(st.params);
    t.insert("plugin", st.plugin);
    root.insert(name, std::move(t));
  }
  return root;
}

}  // namespace topomill
