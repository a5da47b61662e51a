// Fuzz target: the scene loader. Any bytes are parsed as a scene file, resolved against the
// built-in plugins and prepared (models constructed, grid and tool path laid out). A refusal
// (InputError, PluginError) is the expected answer to bad input; anything else escaping, a crash,
// a sanitizer report or a hang is a finding.
#include <cstddef>
#include <cstdint>
#include <string>

#include "pipeline.hpp"
#include "plugin_catalog.hpp"
#include "scene.hpp"
#include "topomill/error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static topomill::PluginCatalog catalog(
      {{topomill::PluginCatalog::builtin_dir(), "built-in"}});
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
