// Finds, loads and checks plugin libraries, and makes models from them.
//
// Libraries are opened lazily: the model NAME is first looked for in a file named
// libtopomill_NAME.so in each search directory (the convention every built-in plugin follows), so a
// run opens only the libraries its scene names. Only when that fails, or when a full listing is
// asked for, is every library on the search path opened.
//
// One rule decides which library provides a model, whichever way it was found (so `run`, `check`
// and `plugins` agree): a library named after the model (libtopomill_NAME.so) before one that is
// not, then the earlier directory of the search path. The loser is "shadowed": listed by
// `topomill plugins`, never an error. Two libraries of one directory registering one name are an
// error (neither is more deliberate than the other).
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

  // The model `name`, if any library on the search path registers it (for any slot).
  const ModelEntry* find(const std::string& name);
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
