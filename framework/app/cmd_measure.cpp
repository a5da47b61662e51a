#include <iostream>
#include <sstream>

#include "cli.hpp"
#include "commands.hpp"
#include "describe.hpp"
#include "metrology/form_removal.hpp"
#include "metrology/gaussian_filter.hpp"
#include "metrology/read_surface.hpp"
#include "roughness.hpp"

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
  if (lambda_s < 0 || lambda_c < 0 || (lambda_s > 0 && lambda_c > 0 && lambda_s >= lambda_c))
    throw InputError(SourceRef{"command line"}, "--filter-s",
                     "expected 0 < lambda_s < lambda_c (mm)");

  Surface s = read_surface(file, spacing);
  s = remove_form(s, form);
  if (lambda_s > 0) s = s_filter(s, lambda_s);
  if (lambda_c > 0) s = l_filter(s, lambda_c);
  const Roughness r = roughness(s.map, s.valid);

  const Grid& g = s.map.grid;
  if (json) {
    toml::table params;
    for (const auto& [name, v] : r.reported_um()) params.insert(name, v);
    toml::table root{{"file", file},
                     {"nx", static_cast<std::int64_t>(g.nx)},
                     {"ny", static_cast<std::int64_t>(g.ny)},
                     {"dx_mm", g.dx},
                     {"dy_mm", g.dy},
                     {"valid_points", static_cast<std::int64_t>(s.valid_count())},
                     {"form", form.name()},
                     {"filter_s_mm", lambda_s},
                     {"filter_l_mm", lambda_c},
                     {"roughness_um", std::move(params)}};
    std::cout << to_json(root);
    return 0;
  }
  std::ostringstream os;
  os.precision(6);
  os << file << ": " << g.nx << " x " << g.ny << " points (" << s.valid_count() << " valid), "
     << g.dx * 1e3 << " x " << g.dy * 1e3 << " um spacing, form " << form.name() << "\n";
  os << "Sa  " << r.Sa * 1e3 << " um\nSq  " << r.Sq * 1e3 << " um\nSp  " << r.Sp * 1e3
     << " um\nSv  " << r.Sv * 1e3 << " um\nSz  " << r.Sz * 1e3 << " um\nSsk " << r.Ssk << "\nSku "
     << r.Sku << "\nSdq " << r.Sdq << "\nSdr " << r.Sdr << " %\n";
  std::cout << os.str();
  return 0;
}

}  // namespace topomill::cli
