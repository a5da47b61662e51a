// Fuzz target: the scene loader. Any bytes are parsed as a scene file, resolved against the
// built-in plugins and prepared (models constructed, grid and tool path laid out). A refusal
// (InputError, PluginError) is the expected answer to bad input; anything else escaping, a crash,
// a sanitizer report or a hang is a finding.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "plugin_catalog.hpp"
#include "run/pipeline.hpp"
#include "scene.hpp"
#include "topomill/error.hpp"

namespace {
// The memory the scene may plan for, as a user's TOPOMILL_MEMORY_LIMIT: far below the fuzzer's
// 2 GB, so that a scene whose layout or maps would not fit is refused by the estimates before
// anything large is laid out (a refusal is an answer; an allocation of gigabytes, or tens of
// seconds laying out passes, is a finding).
constexpr const char* kMemoryLimit = "64M";
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const bool limited = setenv("TOPOMILL_MEMORY_LIMIT", kMemoryLimit, 1) == 0;
  (void)limited;
  static topomill::PluginCatalog catalog({{topomill::PluginCatalog::builtin_dir(), "built-in"}});
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const auto doc = topomill::SceneDocument::parse_string(text, "fuzz.toml");
    const topomill::Scene scene = doc.resolve(catalog);
    topomill::prepare(scene, catalog);
  } catch (const topomill::InputError&) {
  } catch (const topomill::PluginError&) {
  }
  return 0;
}
