// How the areal parameters are reported: one table for summary.json and measure --json (each
// parameter with its value, unit and, where more than one is in use, its discretisation), and
// one text line for the console.
#pragma once

#include <toml++/toml.h>
#include <string>

#include "roughness.hpp"

namespace topomill {

// {"Sa": {"value": 0.54, "unit": "um"}, ..., "Sdr": {"value": ..., "unit": "%", "method": ...}}
toml::table roughness_table(const Roughness& r);

// "Sa 0.5428 um<sep>Sq ...<sep>Sdr 0.01617 % (two triangles per cell; Gwyddion's: 0.0160 %)"
std::string roughness_text(const Roughness& r, const std::string& separator, int digits);

// The first parameter that is not finite (overflow of squares or slopes), or empty.
std::string first_non_finite(const Roughness& r);

}  // namespace topomill
