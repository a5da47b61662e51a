#include "analysis_options.hpp"

#include <cctype>
#include <cmath>
#include <filesystem>
#include <sstream>

#include "interrupt.hpp"

#include "metrology/gaussian_filter.hpp"
#include "suggest.hpp"

namespace topomill::cli {

po::options_description AnalysisOptions::describe() {
  po::options_description o("Processing and parameters");
  o.add_options()("form", po::value(&form_text),
                  "F-operator, form removal: none (default), plane, poly:N, arc (cylinder with "
                  "axis along X)")("filter-s", po::value(&lambda_s),
                                   "S-filter nesting index lambda_s in mm (Gaussian)")(
      "filter-l", po::value(&lambda_c), "L-filter cut-off lambda_c in mm (Gaussian)")(
      "spacing", po::value(&spacing), "node spacing in mm, for CSV files (heights in um)")(
      "parameters", po::value(&parameters),
      "comma-separated: default, all, height, spatial, hybrid, functional, volume, or names "
      "(Sa, Sal, Vmp, ...)")("acf-threshold", po::value(&s),
                             "s for Sal and Str (default 0.2, ISO 25178-3)")(
      "volume-p", po::value(&volume_p), "p in % for Vmp, Vvc, Vm, Vv (default 10)")(
      "volume-q", po::value(&volume_q), "q in % for Vmc, Vvc, Vvv (default 80)")(
      "sxp-p", po::value(&sxp_p), "p in % for Sxp (default 2.5)")("sxp-q", po::value(&sxp_q),
                                                                  "q in % for Sxp (default 50)")(
      "smr-c", po::value(&smr_c), "c in um above the mean plane for Smr(c) (default 0)")(
      "smc-mr", po::value(&smc_mr), "mr in % for Smc(mr) (default 10)");
  return o;
}

void AnalysisOptions::check() {
  const SourceRef cli{"command line"};
  form = Form::parse(form_text, "--form");
  // Each option named for itself; NaN and infinity are refused, not ignored.
  auto within = [&](double v, const char* option, double lo, double hi, bool open,
                    const std::string& what) {
    const bool ok = std::isfinite(v) && (open ? v > lo && v < hi : v >= lo && v <= hi);
    if (!ok)
      throw InputError(cli, option,
                       "expected " + what + (open ? " strictly between " : " from ") +
                           format_number(lo) + (open ? " and " : " to ") + format_number(hi) +
                           ", got " + format_number(v));
  };
  auto length = [&](double v, const char* option, const char* what) {
    if (!(std::isfinite(v) && v >= 0 && v <= 1e6))
      throw InputError(
          cli, option,
          std::string("expected ") + what + " from 0 to 1e6 mm, got " + format_number(v));
  };
  length(lambda_s, "--filter-s", "a nesting index (0: no S-filter)");
  length(lambda_c, "--filter-l", "a cut-off (0: no L-filter)");
  length(spacing, "--spacing", "a node spacing (0: none; CSV files need one)");
  if (lambda_s > 0 && lambda_c > 0 && lambda_s >= lambda_c)
    throw InputError(cli, "--filter-s",
                     "the S-filter's nesting index " + format_number(lambda_s) +
                         " mm is not below the L-filter's cut-off " + format_number(lambda_c) +
                         " mm: expected lambda_s < lambda_c");
  within(s, "--acf-threshold", 0, 1, true, "a correlation value");
  within(volume_p, "--volume-p", 0, 100, true, "a material ratio in %");
  within(volume_q, "--volume-q", 0, 100, true, "a material ratio in %");
  within(sxp_p, "--sxp-p", 0, 100, true, "a material ratio in %");
  within(sxp_q, "--sxp-q", 0, 100, true, "a material ratio in %");
  within(smc_mr, "--smc-mr", 0, 100, false, "a material ratio in %");
  within(smr_c, "--smr-c", -1e6, 1e6, false, "a height in um");
  settings.acf_threshold = s;
  settings.volume_p = volume_p / 100, settings.volume_q = volume_q / 100;
  settings.sxp_p = sxp_p / 100, settings.sxp_q = sxp_q / 100;
  settings.smr_c = smr_c * 1e-3, settings.smc_mr = smc_mr / 100;
  std::string key;
  if (const std::string problem = settings_problem(settings, &key); !problem.empty()) {
    std::string option = "--" + key;
    for (char& c : option)
      if (c == '_') c = '-';
    throw InputError(cli, option, problem);
  }
  std::vector<std::string> words;
  std::istringstream in(parameters);
  for (std::string w; std::getline(in, w, ',');) {
    if (w.empty()) continue;
    const auto all = parameter_words();
    if (std::find(all.begin(), all.end(), w) == all.end())
      throw InputError(
          cli, "--parameters",
          with_candidates("'" + w + "' is not a parameter or family", w, all, "expected one of"));
    words.push_back(w);
  }
  if (words.empty())
    throw InputError(cli, "--parameters", "expected at least one parameter, family or 'default'");
  names = select_parameters(words);
}

void AnalysisOptions::check_spacing_used(const std::vector<std::string>& files) const {
  if (spacing == 0) return;
  for (const auto& f : files) {
    std::string ext = std::filesystem::path(f).extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (ext == ".csv") return;
  }
  throw InputError(SourceRef{"command line"}, "--spacing",
                   "no input is a CSV file, and the others (x3p, sdf, gsf) carry their own "
                   "spacing: expected --spacing only with a CSV file that has no grid in its "
                   "header");
}

Surface AnalysisOptions::process(Surface surface) const {
  throw_if_interrupted();
  surface = remove_form(surface, form);
  throw_if_interrupted();
  if (lambda_s > 0) surface = s_filter(surface, lambda_s);
  if (lambda_c > 0) surface = l_filter(surface, lambda_c);
  throw_if_interrupted();
  return surface;
}

std::string AnalysisOptions::processing() const {
  // ISO 25178-3's names for the three operations.
  std::ostringstream os;
  os << "F-operator " << form.name();
  if (lambda_s > 0) os << ", S-filter nesting index " << format_number(lambda_s) << " mm";
  if (lambda_c > 0) os << ", L-filter cut-off " << format_number(lambda_c) << " mm";
  return os.str();
}

}  // namespace topomill::cli
