// What a run's stages and its output writer read of the scene, read once into a typed record
// (RunSettings::read), so that no stage after the models are made looks a key up by its name.
#pragma once

#include <string>
#include <vector>

#include "scene.hpp"

namespace topomill {

struct RunSettings {
  std::string file;                  // the scene file
  std::string name;                  // [scene] name
  std::string form;                  // [analysis] form: "nominal", "plane" or "none"
  std::vector<std::string> formats;  // [output] formats
  double depth_of_cut = 0;           // [cutting], mm: the nominal cut surface's depth
  std::string described;             // the scene in one line, for the files' comments
  toml::table resolved;              // the scene as resolved (defaults filled in)
  // Each slot's model and the library it came from (those with a model: the enabled ones).
  struct Plugin {
    std::string table, model, library, version;
  };
  std::vector<Plugin> plugins;

  static RunSettings read(const Scene& scene);
  // Whether the residual lies along the surface (form removal "nominal": unrolled), else in plan.
  bool unrolled() const { return form == "nominal"; }
};

}  // namespace topomill
