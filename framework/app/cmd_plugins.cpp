#include <iostream>

#include "cli.hpp"
#include "commands.hpp"
#include "describe.hpp"

namespace topomill::cli {

int cmd_plugins(const Args& args) {
  Common common;
  bool json = false;
  po::options_description opts("topomill plugins [--json]: the models on the plugin search path");
  opts.add_options()("json", po::bool_switch(&json), "print JSON");
  opts.add(common_options(common));
  parse(args, opts, {}, common);
  if (common.help) {
    std::cout << opts << "\n";
    return 0;
  }

  PluginCatalog catalog(search_path(common));
  try {
    catalog.load_all();
  } catch (const PluginError& e) {
    throw InputError(SourceRef{"plugin search path"}, "", e.what());
  }

  if (json) {
    toml::table root;
    toml::array dirs, refused, shadowed;
    for (const auto& d : catalog.search_path())
      dirs.push_back(toml::table{{"path", d.path}, {"origin", d.origin}});
    for (Slot slot : all_slots()) {
      toml::array models;
      for (const auto* e : catalog.models(slot)) models.push_back(model_to_toml(*e));
      root.insert(slot_id(slot), std::move(models));
    }
    for (const auto& r : catalog.refused())
      refused.push_back(toml::table{{"path", r.path}, {"reason", r.reason}});
    for (const auto& s : catalog.shadowed())
      shadowed.push_back(
          toml::table{{"name", s.name}, {"path", s.path}, {"shadowed_by", s.shadowed_by}});
    root.insert("search_path", std::move(dirs));
    root.insert("shadowed", std::move(shadowed));
    root.insert("refused", std::move(refused));
    std::cout << to_json(root);
    return 0;
  }
  for (Slot slot : all_slots()) {
    std::cout << slot_name(slot) << " (" << slot_id(slot) << "):\n";
    auto models = catalog.models(slot);
    if (models.empty()) std::cout << "  (none)\n";
    for (const auto* e : models)
      std::cout << "  " << e->info.name << "  - " << e->info.doc << "\n      from "
                << e->library->path << " (" << e->library->name << " " << e->library->version
                << ")\n";
  }
  if (!catalog.shadowed().empty()) {
    std::cout << "shadowed (not used; the library named after the model, then the earlier "
                 "directory, wins):\n";
    for (const auto& s : catalog.shadowed())
      std::cout << "  " << s.name << " from " << s.path << "\n      shadowed by " << s.shadowed_by
                << "\n";
  }
  if (!catalog.refused().empty()) {
    std::cout << "refused libraries:\n";
    for (const auto& r : catalog.refused()) std::cout << "  " << r.path << ": " << r.reason << "\n";
  }
  return 0;
}

}  // namespace topomill::cli
