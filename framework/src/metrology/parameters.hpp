// ISO 25178-2 field parameters: the catalogue (name, family, unit, definition as implemented),
// which of them a run or `measure` computes, their settings (ISO 25178-3's defaults), and the
// computation on a processed surface (form removed, filtered).
#pragma once

#include <string>
#include <vector>

#include "metrology/roughness.hpp"
#include "metrology/surface.hpp"

namespace topomill {

struct ParameterSettings {
  double acf_threshold = 0.2;  // s, the ACF's decay value for Sal and Str (ISO 25178-3)
  double volume_p = 0.10;      // Vmp = Vm(p), Vvc = Vv(p) - Vv(q); Vm and Vv at p
  double volume_q = 0.80;      // Vmc = Vm(q) - Vm(p), Vvv = Vv(q)
  double sxp_p = 0.025;        // Sxp = Smc(p) - Smc(q)
  double sxp_q = 0.50;
  double smr_c = 0.0;    // mm above the mean plane, for Smr(c)
  double smc_mr = 0.10;  // material ratio for Smc(mr)
};

// The settings of `[analysis]` (its percentages as ratios, smr_c from um to mm), checked
// together: p below q for the volumes and for Sxp (InputError at the key's file:line:column).
class Params;
ParameterSettings parameter_settings(const Params& analysis);
// The same check for settings from elsewhere (measure's options): the first problem, naming the
// option through `name` ("volume_q" -> "--volume-q"), or empty.
std::string settings_problem(const ParameterSettings& s, std::string* key);

struct ParameterInfo {
  std::string name, family, unit, definition;
};
// Every parameter, in the order reports list them.
const std::vector<ParameterInfo>& parameter_catalogue();
// The words `[analysis] parameters` and `measure --parameters` take: "default" (the short set:
// height and hybrid), "all", a family (height, spatial, hybrid, functional, volume), or a name.
std::vector<std::string> parameter_words();
// The names the words select, in catalogue order, each once. Every word must be one of
// parameter_words() (the schema checks that first).
std::vector<std::string> select_parameters(const std::vector<std::string>& words);

// Bytes a point that computing `names` holds at its peak besides the map itself: the
// autocorrelation's padded field and transforms (Sal, Str), the material ratio curve's sorted
// heights (its family); the texture direction's spectrum is held within a fixed size.
double parameter_bytes_per_point(const std::vector<std::string>& names);
// And the seconds a point that computing them takes, on one thread.
double parameter_seconds_per_point(const std::vector<std::string>& names);

struct ParameterValues {
  std::vector<Roughness::Reported> reported;  // the selected, defined ones, in catalogue order
  // Selected but not defined for this surface, with why (e.g. Sal of a map with no variance).
  std::vector<std::pair<std::string, std::string>> undefined;
};
// `height`: the surface's roughness() when the caller has it already (a run does), so that it is
// not computed twice.
ParameterValues compute_parameters(const Surface& surface, const std::vector<std::string>& names,
                                   const ParameterSettings& settings,
                                   const Roughness* height = nullptr);

}  // namespace topomill
