#include "plugin_catalog.hpp"

#include <algorithm>
#include <boost/dll/runtime_symbol_info.hpp>
#include <boost/dll/shared_library.hpp>
#include <cctype>
#include <cstdlib>
#include <filesystem>

#include "log.hpp"

namespace fs = std::filesystem;

namespace topomill {

namespace {
constexpr const char* kEntrySymbol = "topomill_plugin_entry_v1";
constexpr const char* kFilePrefix = "libtopomill_";

// The model a library file provides: NAME of libtopomill_NAME.so; empty for any other file.
std::string model_of_file(const fs::path& p) {
  const std::string f = p.filename().string();
  const std::string suffix = ".so";
  if (f.size() <= std::string(kFilePrefix).size() + suffix.size() || f.rfind(kFilePrefix, 0) != 0 ||
      f.compare(f.size() - suffix.size(), suffix.size(), suffix) != 0)
    return {};
  const std::string name = f.substr(std::string(kFilePrefix).size(),
                                    f.size() - std::string(kFilePrefix).size() - suffix.size());
  return is_model_name(name) ? name : std::string();
}
}  // namespace

bool is_model_name(const std::string& name) {
  if (name.empty() || name.size() > 128) return false;
  for (const unsigned char c : name)
    if (!(std::isalnum(c) || c == '_')) return false;
  return true;
}

PluginLibrary::~PluginLibrary() = default;

PluginCatalog::PluginCatalog(std::vector<Dir> search_path) : dirs_(std::move(search_path)) {}
PluginCatalog::~PluginCatalog() = default;

std::string PluginCatalog::builtin_dir() {
  fs::path core = boost::dll::this_line_location();
  return (core.parent_path() / "topomill" / "plugins").string();
}

std::vector<std::string> PluginCatalog::env_dirs() {
  std::vector<std::string> out;
  const char* env = std::getenv("TOPOMILL_PLUGIN_PATH");
  if (!env) return out;
  std::string s = env;
  std::size_t start = 0;
  while (start <= s.size()) {
    std::size_t end = s.find(':', start);
    if (end == std::string::npos) end = s.size();
    if (end > start) out.push_back(s.substr(start, end - start));
    start = end + 1;
  }
  return out;
}

void PluginCatalog::refuse(const std::string& path, const std::string& reason) {
  refused_.push_back({path, reason});
  log_warning("plugin library '" + path + "' refused: " + reason);
}

void PluginCatalog::load(const std::string& raw_path, std::size_t dir) {
  std::error_code ec;
  std::string path = fs::weakly_canonical(raw_path, ec).string();
  if (ec) path = raw_path;
  if (seen_.count(path)) return;
  seen_[path] = false;

  auto handle = std::make_shared<boost::dll::shared_library>();
  try {
    handle->load(path, boost::dll::load_mode::rtld_now | boost::dll::load_mode::rtld_local);
  } catch (const std::exception& e) {
    refuse(path, std::string("cannot be opened: ") + e.what());
    return;
  }
  if (!handle->has(kEntrySymbol)) {
    refuse(path, std::string("not a topomill plugin: it exports no entry point '") + kEntrySymbol +
                     "' (declare one with TOPOMILL_PLUGIN)");
    return;
  }
  const PluginManifest* m = handle->get_alias<PluginEntry>(kEntrySymbol)();
  // abi_version is the only field whose place every ABI agrees on: check it before the rest.
  if (!m || m->abi_version != kAbiVersion) {
    refuse(path, "built for topomill plugin ABI " + std::to_string(m ? m->abi_version : 0) +
                     ", this program provides ABI " + std::to_string(kAbiVersion) +
                     ": rebuild the plugin against this SDK");
    return;
  }
  auto size_check = [&](const char* what, std::uint32_t theirs, std::size_t ours) {
    if (theirs == ours) return true;
    refuse(path, std::string("record size mismatch for ") + what + ": the plugin has " +
                     std::to_string(theirs) + " bytes, this program " + std::to_string(ours) +
                     ": rebuild the plugin against this SDK with the same compiler");
    return false;
  };
  if (!size_check("PluginManifest", m->manifest_size, sizeof(PluginManifest)) ||
      !size_check("ModelInfo", m->model_info_size, sizeof(ModelInfo)) ||
      !size_check("Registrar", m->registrar_size, sizeof(Registrar)))
    return;

  Registrar registrar;
  std::vector<Schema> schemas;
  try {
    m->register_models(registrar);
    for (const auto& info : registrar.models()) schemas.push_back(info.schema());
  } catch (const std::exception& e) {
    refuse(path, std::string("registration failed: ") + e.what());
    return;
  }
  // One model per library, named after its file: a scene's name then opens that file and no
  // other, so a misspelt name runs no code that nothing named.
  const std::string expected = model_of_file(path);
  if (registrar.models().size() != 1 || registrar.models()[0].name != expected) {
    std::string names;
    for (const auto& info : registrar.models())
      names += (names.empty() ? "'" : ", '") + info.name + "'";
    refuse(path, "registers " + (names.empty() ? std::string("no model") : names) +
                     ": expected exactly one model, named after its file ('" + expected + "' for " +
                     fs::path(path).filename().string() + ")");
    return;
  }

  auto lib = std::make_shared<PluginLibrary>();
  lib->path = path;
  lib->name = m->library_name ? m->library_name : "";
  lib->version = m->library_version ? m->library_version : "";
  lib->handle = handle;
  lib->dir = dir;

  auto shadow = [&](const std::string& name, const std::string& loser, const std::string& winner) {
    shadowed_.push_back({name, loser, winner});
    log_debug("model '" + name + "' from '" + loser + "' is shadowed by '" + winner + "'");
  };
  std::vector<bool> keep(registrar.models().size(), true);
  for (std::size_t i = 0; i < registrar.models().size(); ++i) {
    const std::string& name = registrar.models()[i].name;
    auto it = by_name_.find(name);
    if (it == by_name_.end()) continue;
    const PluginLibrary& other = *it->second->library;
    if (dir < other.dir) {  // the earlier directory wins (the rule in the header)
      // The loser's entry stays in entries_ (a caller may hold it); it is no longer found.
      shadow(name, other.path, path);
      by_name_.erase(it);
    } else {
      shadow(name, path, other.path);
      keep[i] = false;
    }
  }
  for (std::size_t i = 0; i < registrar.models().size(); ++i) {
    if (!keep[i]) continue;
    auto entry = std::make_unique<ModelEntry>();
    entry->info = std::move(registrar.models()[i]);
    entry->schema = std::move(schemas[i]);
    entry->library = lib;
    by_name_[entry->info.name] = entry.get();
    log_debug(std::string(slot_name(entry->info.slot)) + " '" + entry->info.name + "' from " +
              path);
    entries_.push_back(std::move(entry));
  }
  seen_[path] = true;
}

const ModelEntry* PluginCatalog::find(const std::string& name) {
  if (!is_model_name(name)) return nullptr;  // never joined into a path
  auto known = by_name_.find(name);
  if (known != by_name_.end()) return known->second;
  for (std::size_t d = 0; d < dirs_.size(); ++d) {
    fs::path candidate = fs::path(dirs_[d].path) / (kFilePrefix + name + ".so");
    std::error_code ec;
    if (!fs::exists(candidate, ec)) continue;
    std::size_t refused_before = refused_.size();
    load(candidate.string(), d);
    known = by_name_.find(name);
    if (known != by_name_.end()) return known->second;
    if (refused_.size() > refused_before)
      throw PluginError("model '" + name + "' cannot be loaded: library '" + refused_.back().path +
                        "' " + refused_.back().reason);
  }
  return nullptr;
}

std::vector<std::string> PluginCatalog::available_names() const {
  std::vector<std::string> out;
  for (const Dir& dir : dirs_) {
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(dir.path, ec)) {
      const std::string name = model_of_file(e.path());
      if (!name.empty()) out.push_back(name);
    }
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

void PluginCatalog::load_all() {
  if (all_loaded_) return;
  all_loaded_ = true;
  for (std::size_t d = 0; d < dirs_.size(); ++d) {
    const Dir& dir = dirs_[d];
    std::error_code ec;
    if (!fs::is_directory(dir.path, ec)) {
      log_debug("plugin directory '" + dir.path + "' (" + dir.origin + ") does not exist");
      continue;
    }
    std::vector<fs::path> files;
    for (const auto& e : fs::directory_iterator(dir.path, ec))
      if (e.is_regular_file() && !model_of_file(e.path()).empty()) files.push_back(e.path());
    std::sort(files.begin(), files.end());  // a stable order makes listings reproducible
    for (const auto& f : files) load(f.string(), d);
  }
}

std::vector<const ModelEntry*> PluginCatalog::models(Slot slot) const {
  std::vector<const ModelEntry*> out;
  for (const auto& [name, entry] : by_name_)
    if (entry->info.slot == slot) out.push_back(entry);
  return out;
}

std::vector<std::string> PluginCatalog::names(Slot slot) const {
  std::vector<std::string> out;
  for (const auto* e : models(slot)) out.push_back(e->info.name);
  return out;
}

std::unique_ptr<Model> PluginCatalog::construct(const ModelEntry& entry, const Params& params,
                                                Slot slot) const {
  if (entry.info.slot != slot)
    throw std::logic_error("model '" + entry.info.name + "' is a " + slot_name(entry.info.slot) +
                           ", not a " + slot_name(slot));
  try {
    return entry.info.create(params);
  } catch (const ParamError& e) {
    std::string key = params.path().empty() ? e.key() : params.path() + "." + e.key();
    throw InputError(params.where(e.key()), key, e.what());
  } catch (const InputError&) {
    throw;  // a model that reads a file of its own names a place in it (cl_file: line, column)
  } catch (const std::exception& e) {
    throw PluginError("model '" + entry.info.name + "' from '" + entry.library->path +
                      "' failed to construct: " + e.what());
  }
}

}  // namespace topomill
