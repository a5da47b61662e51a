// The options `measure` and `compare` share: how a surface is processed before its parameters
// (form removal, ISO 25178-3's S- and L-filters), which parameters, and their settings.
#pragma once

#include <string>
#include <vector>

#include "cli.hpp"
#include "metrology/form_removal.hpp"
#include "metrology/parameters.hpp"

namespace topomill::cli {

struct AnalysisOptions {
  std::string form_text = "none";
  double lambda_s = 0, lambda_c = 0;  // mm; 0: no filter
  double spacing = 0;                 // mm, for CSV files
  std::string parameters = "default";
  ParameterSettings settings;  // as ratios and mm (the options take % and um)
  double volume_p = 10, volume_q = 80, sxp_p = 2.5, sxp_q = 50, smr_c = 0, smc_mr = 10, s = 0.2;

  po::options_description describe();
  // Checks every option (InputError naming it); fills `settings`, `form` and `names`.
  void check();
  // --spacing is for CSV files (the other formats carry their grid): refused when none of
  // `files` is one, rather than silently ignored.
  void check_spacing_used(const std::vector<std::string>& files) const;
  Form form;
  std::vector<std::string> names;

  // Form removed, then the S-filter, then the L-filter (ISO 25178-3's order: S, F, L; the form
  // is removed first so that the filters see no tilt or curvature at the map's edges).
  Surface process(Surface s) const;
  // "F-operator plane, S-filter nesting index 0.0025 mm, L-filter cut-off 0.8 mm": what
  // `process` did, in ISO 25178-3's words, for reports.
  std::string processing() const;
};

}  // namespace topomill::cli
