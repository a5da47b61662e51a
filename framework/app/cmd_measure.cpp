#include <iostream>
#include <sstream>

#include "analysis_options.hpp"
#include "commands.hpp"
#include "describe.hpp"
#include "metrology/read_surface.hpp"
#include "metrology/roughness_report.hpp"
#include "metrology/write_surface.hpp"

namespace topomill::cli {

int cmd_measure(const Args& args) {
  Common common;
  AnalysisOptions analysis;
  std::string file, out;
  bool json = false;
  po::options_description opts(
      "topomill measure FILE [--form none|plane|poly:N|arc] [--filter-s LS] [--filter-l LC] "
      "[--parameters LIST] [--out FILE] [--json]: ISO 25178-2 areal parameters of a height map "
      "(.x3p, .sdf, .gsf, .csv)");
  opts.add_options()("out", po::value(&out),
                     "write the processed surface (form removed, filtered) to FILE: .x3p (keeps "
                     "missing points), .gsf, .sdf or .csv (heights in um)")(
      "json", po::bool_switch(&json), "print JSON");
  opts.add(analysis.describe());
  opts.add(common_options(common));
  parse_with_positional(args, opts, "file", file, common);
  if (common.help) {
    std::cout << opts << "\n";
    return 0;
  }
  if (file.empty()) throw InputError(SourceRef{"command line"}, "", "measure needs a file");
  analysis.check();
  analysis.check_spacing_used({file});
  if (!out.empty()) check_surface_format(out, "--out");

  Surface s = read_surface(file, analysis.spacing);
  if (s.valid_count() < 4)
    throw InputError(SourceRef{file}, "",
                     "the map has " + std::to_string(s.valid_count()) +
                         " valid points: expected at least 4 to measure");
  s = analysis.process(std::move(s));
  const ParameterValues values = compute_parameters(s, analysis.names, analysis.settings);
  // Finite heights can still overflow a parameter (squares of 1e300): nothing non-finite is
  // printed, in text or JSON, nor written.
  if (const std::string name = first_non_finite(values); !name.empty())
    throw InputError(SourceRef{file}, "",
                     name +
                         " is not finite for these heights (their squares or slopes overflow "
                         "double precision): expected heights and spacings of a real "
                         "surface");
  if (!out.empty())
    write_surface(out, s, "--out", "topomill measure: " + analysis.processing() + " of " + file);

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
                     {"form", analysis.form.name()},
                     {"filter_s_mm", analysis.lambda_s},
                     {"filter_l_mm", analysis.lambda_c},
                     {"roughness", roughness_table(values)}};
    if (!out.empty()) root.insert("out", out);
    std::cout << to_json(root);
    return 0;
  }
  std::ostringstream os;
  os.precision(6);
  os << file << ": " << g.nx << " x " << g.ny << " points (" << s.valid_count() << " valid), "
     << g.dx * 1e3 << " x " << g.dy * 1e3 << " um spacing, " << analysis.processing() << "\n";
  os << roughness_text(values, "\n", 6) << "\n";
  if (!out.empty()) os << "processed surface written to " << out << "\n";
  std::cout << os.str();
  return 0;
}

}  // namespace topomill::cli
