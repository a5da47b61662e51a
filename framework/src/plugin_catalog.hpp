// Finds, loads and checks plugin libraries, and makes models from them.
//
// A library provides exactly one model, named after its file: libtopomill_NAME.so registers NAME
// (gz-plugin's one hook per library). A scene's model NAME therefore opens libtopomill_NAME.so in
// the first search directory that has it, and no other library: a misspelt name runs no code.
// Only a full listing (`plugins`, `describe`) opens every libtopomill_*.so on the search path.
// Model names are identifiers (letters, digits, underscore), never joined into a path otherwise.
//
// A library registering anything else is refused (listed, never an error by itself). The same
// name in two directories: the earlier directory wins, whichever way it was found (so `run`,
// `check` and `plugins` agree); the loser is "shadowed", listed by `topomill plugins`.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "topomill/plugin.hpp"

namespace boost::dll {
class shared_library;
}

namespace topomill {

// Letters, digits and underscores, 1 to 128 of them: what a model name may be.
bool is_model_name(const std::string& name);

struct PluginLibrary {
  std::string path;
  std::string name, version;
  std::shared_ptr<boost::dll::shared_library> handle;
  std::size_t dir = 0;  // index of its directory in the search path
  ~PluginLibrary();
};

struct ModelEntry {
  // First member, so destroyed last: `info` holds code that lives in the library.
  std::shared_ptr<const PluginLibrary> library;
  ModelInfo info;
  Schema schema;
};

// A model registered by a library that lost to another by the rule above.
struct ShadowedModel {
  std::string name;
  std::string path;         // the library not used
  std::string shadowed_by;  // the library used
};

struct RefusedLibrary {
  std::string path;
  std::string reason;
};

class PluginCatalog {
 public:
  struct Dir {
    std::string path;
    std::string
        origin;  // "--plugin-path", "scene plugin_paths", "TOPOMILL_PLUGIN_PATH", "built-in"
  };

  explicit PluginCatalog(std::vector<Dir> search_path);
  ~PluginCatalog();

  // Where the built-in plugins live: <directory of the core library>/topomill/plugins.
  static std::string builtin_dir();
  // The directories of TOPOMILL_PLUGIN_PATH (colon-separated), in order.
  static std::vector<std::string> env_dirs();

  const std::vector<Dir>& search_path() const { return dirs_; }

  // The model `name` from libtopomill_NAME.so, opened from the first directory that has it;
  // nullptr when no directory has it (or the name is not an identifier). A library that is
  // there but refused is a PluginError naming it.
  const ModelEntry* find(const std::string& name);
  // Model names the search path offers, from file names alone (no library is opened).
  std::vector<std::string> available_names() const;
  // Opens every library on the search path.
  void load_all();
  // Models of one slot known so far, sorted by name.
  std::vector<const ModelEntry*> models(Slot slot) const;
  std::vector<std::string> names(Slot slot) const;
  // Libraries that were refused, with why; a refused library never stops the program by itself.
  const std::vector<RefusedLibrary>& refused() const { return refused_; }
  const std::vector<ShadowedModel>& shadowed() const { return shadowed_; }

  // Makes a model; the object keeps its library loaded for as long as it lives. A ParamError from
  // the constructor becomes an InputError at the parameter's scene position.
  template <class T>
  std::shared_ptr<T> create(const ModelEntry& entry, const Params& params) const {
    Model* raw = construct(entry, params, SlotOf<T>::value).release();
    auto keep = entry.library;
    return std::shared_ptr<T>(static_cast<T*>(raw), [keep](T* p) { delete p; });
  }

 private:
  std::unique_ptr<Model> construct(const ModelEntry& entry, const Params& params, Slot slot) const;
  void load(const std::string& path, std::size_t dir);
  void refuse(const std::string& path, const std::string& reason);

  std::vector<Dir> dirs_;
  std::map<std::string, bool> seen_;  // canonical path -> loaded (true) or refused (false)
  std::vector<std::unique_ptr<ModelEntry>> entries_;
  std::map<std::string, ModelEntry*> by_name_;
  std::vector<RefusedLibrary> refused_;
  std::vector<ShadowedModel> shadowed_;
  bool all_loaded_ = false;
};

}  // namespace topomill
