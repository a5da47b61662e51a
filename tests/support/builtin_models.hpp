// Makes built-in models directly, for tests of one model's geometry.
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "plugin_catalog.hpp"

namespace testing {

// `values`: (key, number) pairs; integers are passed as numbers and converted for integer keys.
template <class T>
std::shared_ptr<T> make_model(const std::string& name,
                              const std::vector<std::pair<std::string, double>>& values) {
  topomill::PluginCatalog catalog({{topomill::PluginCatalog::builtin_dir(), "built-in"}});
  const topomill::ModelEntry* entry = catalog.find(name);
  if (!entry) throw std::runtime_error("no built-in model " + name);
  topomill::Params p;
  for (const auto& spec : entry->schema.specs())
    if (spec.default_value) p.set(spec.name, *spec.default_value);
  for (const auto& [key, v] : values) {
    const auto* spec = entry->schema.find(key);
    if (spec && spec->type == topomill::ParamType::Integer)
      p.set(key, static_cast<std::int64_t>(v));
    else
      p.set(key, v);
  }
  return catalog.create<T>(*entry, p);
}

}  // namespace testing
