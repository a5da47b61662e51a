// Scene files: parse (TOML++), apply --set overrides, check every table against its schema, and
// resolve plugin names, before anything is constructed.
#pragma once

#include <toml++/toml.h>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "plugin_catalog.hpp"
#include "topomill/params.hpp"

namespace topomill {

// A table that selects a model for a slot: [tool], [workpiece], [evaluator], [force], and the
// effect tables [vibration], [deflection], [springback].
struct SlotTable {
  std::string table;
  Slot slot = Slot::ToolGeometry;
  bool present = false;
  bool enabled = false;  // effects: present and `enabled` not false; other tables: present
  std::string plugin;
  const ModelEntry* model = nullptr;  // null when the table is not used by this run
  Params params;
  SourceRef where;  // the table itself
};

struct Scene {
  std::string file;
  std::vector<std::string> plugin_paths;
  std::map<std::string, Params> core;  // [scene], [cutting], [runout] if given, [region], ...
  std::map<std::string, SlotTable> slots;

  const Params& table(const std::string& name) const { return core.at(name); }
  // Whether an optional core table ([runout]) is in the scene.
  bool has_table(const std::string& name) const { return core.count(name) > 0; }
  const SlotTable& slot(const std::string& name) const { return slots.at(name); }
  bool enabled(const std::string& name) const { return slots.at(name).enabled; }
  // Names of the enabled effect tables, in pipeline order.
  std::vector<std::string> enabled_effects() const;
  // The resolved scene (defaults filled in, unused tables left out) as a TOML table.
  toml::table to_toml() const;
};

// The effect tables, in pipeline order; each needs forces.
const std::vector<std::string>& effect_tables();
// The core's own tables and their schemas (rendered by `describe core`).
const std::vector<std::pair<std::string, Schema>>& core_schemas();

// What a validated value looks like in TOML (used for the resolved scene and summaries).
void insert_value(toml::table& out, const std::string& key, const Value& value);
toml::table params_to_toml(const Params& params);

class SceneDocument {
 public:
  // Throws InputError with the file, line and column for unreadable or malformed TOML.
  static SceneDocument parse_file(const std::string& path);
  // A scene file's bytes, read bounded (InputError for a missing, oversized or special file).
  static std::string read_file(const std::string& path);
  static SceneDocument parse_string(const std::string& text, const std::string& name);

  // `key.path=value`; the value is read as TOML, or taken as a string when it is not TOML.
  void apply_override(const std::string& assignment);
  // The scene's plugin_paths, relative to the scene file's directory. A scene naming plugin
  // directories runs code from them (as a Makefile does); with `allowed` false (an untrusted
  // scene: --no-scene-plugin-paths or TOPOMILL_NO_SCENE_PLUGIN_PATHS) that is refused, exit 2.
  std::vector<std::string> plugin_paths(bool allowed = true) const;
  // Checks every key and resolves every model the run needs. With `check_unused`, also the
  // tables the run would skip (disabled effects, [force] without effects): that opens their
  // plugin libraries, which a run avoids.
  Scene resolve(PluginCatalog& catalog, bool check_unused = false) const;

  const std::string& file() const { return file_; }

 private:
  std::string file_;
  std::shared_ptr<toml::table> root_;
  std::map<std::string, SourceRef> overrides_;  // key path -> the --set that wrote it
};

}  // namespace topomill
