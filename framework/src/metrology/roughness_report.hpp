// How the areal parameters are reported: one table for summary.json and measure --json (each
// parameter with its value, unit and, where it has a setting or more than one discretisation is in
// use, its method), and one text line for the console.
#pragma once

#include <toml++/toml.h>
#include <string>

#include "metrology/parameters.hpp"

namespace topomill {

// {"Sa": {"value": 0.54, "unit": "um"}, ..., "Sal": {"value": ..., "unit": "mm", "method":
// "s = 0.2"}}; a parameter selected but undefined for the surface: {"Str": {"undefined": why}}.
toml::table roughness_table(const ParameterValues& v);

// "Sa 0.5428 um<sep>Sq ...<sep>Sdr 0.01617 % (two triangles per cell; Gwyddion's: 0.0160 %)"
std::string roughness_text(const ParameterValues& v, const std::string& separator, int digits);

// The first parameter that is not finite (overflow of squares or slopes), or empty.
std::string first_non_finite(const ParameterValues& v);

}  // namespace topomill
