// Renders schemas and the plugin catalogue as text, JSON or Markdown (the scene reference in
// docs/ is generated from the Markdown form).
#pragma once

#include <toml++/toml.h>
#include <string>

#include "topomill/types.hpp"

#include "plugin_catalog.hpp"
#include "topomill/params.hpp"

namespace topomill {

toml::array schema_to_toml(const Schema& schema);
toml::table model_to_toml(const ModelEntry& entry);

std::string schema_text(const Schema& schema, const std::string& indent = "  ");
std::string schema_markdown(const Schema& schema);

std::string to_json(const toml::table& table);
// {"nx", "ny", "dx_mm", "dy_mm", "x0_mm", "y0_mm"}: a grid as summary.json and compare.json give
// it.
toml::table grid_table(const Grid& g);
std::string to_toml_text(const toml::table& table);
std::string to_json(const toml::array& array);

}  // namespace topomill
