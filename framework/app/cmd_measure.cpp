#include <cmath>
#include <iostream>
#include <sstream>

#include "cli.hpp"
#include "commands.hpp"
#include "describe.hpp"
#include "metrology/form_removal.hpp"
#include "metrology/gaussian_filter.hpp"
#include "metrology/read_surface.hpp"
#include "roughness_report.hpp"

namespace topomill::cli {

int cmd_measure(const Args& args) {
  Common common;
  std::string file, form_text = "none";
  double lambda_s = 0, lambda_c = 0, spacing = 0;
  bool json = false;
  po::options_description opts(
      "topomill measure FILE [--form none|plane|poly:N|arc] [--filter-s LS] [--filter-l LC] "
      "[--json]: ISO 25178-2 areal parameters of a height map (.x3p, .sdf, .gsf, .csv)");
  opts.add_options()("form", po::value(&form_text),
                     "form removal: none (default), plane, "
                     "poly:N, arc (cylinder with axis along X)")(
      "filter-s", po::value(&lambda_s), "S-filter nesting index lambda_s in mm (Gaussian)")(
      "filter-l", po::value(&lambda_c), "L-filter cut-off lambda_c in mm (Gaussian)")(
      "spacing", po::value(&spacing), "node spacing in mm, for CSV files (heights in um)")(
      "json", po::bool_switch(&json), "print JSON");
  opts.add(common_options(common));
  parse_with_positional(args, opts, "file", file, common);
  if (common.help) {
    std::cout << opts << "\n";
    return 0;
  }
  if (file.empty()) throw InputError(SourceRef{"command line"}, "", "measure needs a file");
  const Form form = Form::parse(form_text, "--form");
  // Each option named for itself; NaN and infinity are refused, not ignored.
  const SourceRef cli{"command line"};
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

  Surface s = read_surface(file, spacing);
  if (s.valid_count() < 4)
    throw InputError(SourceRef{file}, "",
                     "the map has " + std::to_string(s.valid_count()) +
                         " valid points: expected at least 4 to measure");
  s = remove_form(s, form);
  if (lambda_s > 0) s = s_filter(s, lambda_s);
  if (lambda_c > 0) s = l_filter(s, lambda_c);
  const Roughness r = roughness(s.map, s.valid);
  // Finite heights can still overflow a parameter (squares of 1e300): nothing non-finite is
  // printed, in text or JSON.
  if (const std::string name = first_non_finite(r); !name.empty())
    throw InputError(SourceRef{file}, "",
                     name +
                         " is not finite for these heights (their squares or slopes overflow "
                         "double precision): expected heights and spacings of a real "
                         "surface");

  const Grid& g = s.map.grid;
  if (json) {
    toml::table root{{"file", file},
                     {"nx", static_cast<std::int64_t>(g.nx)},
                     {"ny", static_cast<std::int64_t>(g.ny)},
                     {"dx_mm", g.dx},
                     {"dy_mm", g.dy},
                     {"x0_mm", g.x0},
                     {"y0_mm", g.y0},
                     {"valid_points", static_cast<std::int64_t>(s.valid_count())},
                     {"form", form.name()},
                     {"filter_s_mm", lambda_s},
                     {"filter_l_mm", lambda_c},
                     {"roughness", roughness_table(r)}};
    std::cout << to_json(root);
    return 0;
  }
  std::ostringstream os;
  os.precision(6);
  os << file << ": " << g.nx << " x " << g.ny << " points (" << s.valid_count() << " valid), "
     << g.dx * 1e3 << " x " << g.dy * 1e3 << " um spacing, form " << form.name() << "\n";
  os << roughness_text(r, "\n", 6) << "\n";
  std::cout << os.str();
  return 0;
}

}  // namespace topomill::cli
