// The plugin contract: one exported entry point per library, returning a manifest that the host
// checks (ABI version, record sizes) before it reads anything else. Include this in a plugin's
// single translation unit that uses TOPOMILL_PLUGIN.
//
//   TOPOMILL_PLUGIN("my_models", "1.0.0") {
//     registrar.add<topomill::SurfaceShape, MySurface>("my_surface", "what it models");
//   }
//
// MySurface needs `static topomill::Schema schema();` and a constructor from `const Params&`.
#pragma once

#include <boost/dll/alias.hpp>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

#include "topomill/model.hpp"
#include "topomill/params.hpp"
#include "topomill/version.hpp"

namespace topomill {

// One model a library offers.
struct ModelInfo {
  Slot slot;
  std::string name;
  std::string doc;
  std::function<Schema()> schema;
  std::function<std::unique_ptr<Model>(const Params&)> create;
};

class Registrar {
 public:
  template <class Interface, class Impl>
  void add(std::string name, std::string doc) {
    static_assert(std::is_base_of_v<Interface, Impl>, "Impl must implement the slot interface");
    // Upcast here, where the types are known, so the host can static_cast back by slot.
    models_.push_back(ModelInfo{SlotOf<Interface>::value, std::move(name), std::move(doc),
                                [] { return Impl::schema(); },
                                [](const Params& p) -> std::unique_ptr<Model> {
                                  return std::unique_ptr<Interface>(new Impl(p));
                                }});
  }
  std::vector<ModelInfo>& models() { return models_; }

 private:
  std::vector<ModelInfo> models_;
};

// The record the entry point returns. `abi_version` must stay the first member in every ABI so
// that the host can read it from any library before trusting the rest of the layout.
struct PluginManifest {
  std::uint32_t abi_version;
  std::uint32_t manifest_size;    // sizeof(PluginManifest) as the plugin saw it
  std::uint32_t model_info_size;  // sizeof(ModelInfo)
  std::uint32_t registrar_size;   // sizeof(Registrar)
  const char* library_name;
  const char* library_version;
  void (*register_models)(Registrar&);
};

using PluginEntry = const PluginManifest*();

}  // namespace topomill

// The exported symbol's name; the loader looks only for this.
#define TOPOMILL_PLUGIN_ENTRY_SYMBOL topomill_plugin_entry_v1

// Overridable only so that tests can build deliberately mismatched fixture plugins.
#ifndef TOPOMILL_PLUGIN_ABI
#define TOPOMILL_PLUGIN_ABI TOPOMILL_ABI_VERSION
#endif
#ifndef TOPOMILL_PLUGIN_MODEL_INFO_SIZE
#define TOPOMILL_PLUGIN_MODEL_INFO_SIZE sizeof(::topomill::ModelInfo)
#endif

#define TOPOMILL_PLUGIN(LIBRARY_NAME, LIBRARY_VERSION)                    \
  static void topomill_register_models(::topomill::Registrar& registrar); \
  static const ::topomill::PluginManifest* topomill_plugin_entry() {      \
    static const ::topomill::PluginManifest manifest{                     \
        TOPOMILL_PLUGIN_ABI,                                              \
        static_cast<std::uint32_t>(sizeof(::topomill::PluginManifest)),   \
        static_cast<std::uint32_t>(TOPOMILL_PLUGIN_MODEL_INFO_SIZE),      \
        static_cast<std::uint32_t>(sizeof(::topomill::Registrar)),        \
        LIBRARY_NAME,                                                     \
        LIBRARY_VERSION,                                                  \
        &topomill_register_models};                                       \
    return &manifest;                                                     \
  }                                                                       \
  BOOST_DLL_ALIAS(topomill_plugin_entry, topomill_plugin_entry_v1)        \
  static void topomill_register_models(::topomill::Registrar& registrar)
