// The models on the plugin search path, as `topomill plugins --json` and `describe --json` give
// them (JSON text; the package turns it into dicts).
#include <pybind11/stl.h>

#include <memory>

#include "calls.hpp"
#include "cli.hpp"
#include "describe.hpp"
#include "scene.hpp"
#include "suggest.hpp"

namespace topomill::python {

namespace {
std::unique_ptr<PluginCatalog> loaded_catalog(const std::vector<std::string>& plugin_paths) {
  cli::Common common;
  common.plugin_paths = plugin_paths;
  auto catalog = std::make_unique<PluginCatalog>(cli::search_path(common));
  catalog->load_all();
  return catalog;
}
}  // namespace

void bind_catalog(py::module_& m) {
  m.def("plugins_json", [](const std::vector<std::string>& plugin_paths) {
    std::string json;
    interruptible(
        [&] {
          const auto catalog = loaded_catalog(plugin_paths);
          toml::table root;
          for (Slot slot : all_slots()) {
            toml::array models;
            for (const auto* e : catalog->models(slot)) models.push_back(model_to_toml(*e));
            root.insert(slot_id(slot), std::move(models));
          }
          json = to_json(root);
        },
        ErrorKind::Input);
    return json;
  });

  m.def("describe_json", [](const std::string& name, const std::vector<std::string>& plugin_paths) {
    std::string json;
    interruptible(
        [&] {
          if (name == "core") {
            toml::table core;
            for (const auto& [table, schema] : core_schemas())
              core.insert(table, schema_to_toml(schema));
            json = to_json(core);
            return;
          }
          const auto catalog = loaded_catalog(plugin_paths);
          const ModelEntry* e = catalog->find(name);
          if (!e) {
            std::vector<std::string> known{"core"};
            for (Slot slot : all_slots())
              for (const auto& n : catalog->names(slot)) known.push_back(n);
            throw InputError(
                SourceRef{"describe()"}, "name",
                with_candidates("unknown model '" + name + "'", name, known, "Known models"));
          }
          json = to_json(model_to_toml(*e));
        },
        ErrorKind::Input);
    return json;
  });
}

}  // namespace topomill::python
