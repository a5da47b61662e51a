// topomill compare SIM MEAS: a simulation beside a measurement (framework/src/compare.hpp does
// the work; this file reads the inputs and writes the report).
#include <cmath>
#include <filesystem>
#include <iostream>
#include <sstream>

#include "analysis_options.hpp"
#include "commands.hpp"
#include "compare.hpp"
#include "compare_report.hpp"
#include "metrology/read_surface.hpp"

namespace topomill::cli {

namespace fs = std::filesystem;

namespace {
// A run's output directory stands for its residual map, in the first format it wrote; only a
// finished run's (sealed by its summary.json): a stopped or running one may hold a map of
// another run, or pieces.
std::string surface_file(const std::string& given) {
  std::error_code ec;
  if (!fs::is_directory(given, ec)) return given;
  if (!fs::is_regular_file(fs::path(given) / "summary.json", ec))
    throw InputError(SourceRef{given}, "",
                     "the directory holds no summary.json, so no finished run (a run that was "
                     "stopped, failed or is still writing leaves none): expected a finished run's "
                     "output directory or a height-map file");
  for (const char* ext : {"x3p", "gsf", "sdf", "csv"}) {
    const fs::path p = fs::path(given) / (std::string("height_residual.") + ext);
    if (fs::is_regular_file(p, ec)) return p.string();
  }
  throw InputError(SourceRef{given}, "",
                   "the directory holds no height_residual.x3p, .gsf, .sdf or .csv: expected a "
                   "run's output directory or a height-map file");
}
}  // namespace

int cmd_compare(const Args& args) {
  Common common;
  AnalysisOptions analysis;
  std::vector<std::string> files;
  std::string out = "compare";
  bool rotation = false, json = false;
  double max_shift = 0;
  po::options_description opts(
      "topomill compare SIM MEAS [options]: a simulated surface (a height-map file or a run's "
      "output directory) beside a measured one (.x3p, .sdf, .gsf, .csv): both processed alike, "
      "on the coarser grid, registered, differenced; parameters, lays and periods side by side");
  opts.add_options()("out", po::value(&out),
                     "directory for compare.json, compare.md, the difference map and the plots "
                     "(default: compare)")(
      "rotation", po::bool_switch(&rotation),
      "register the in-plane angle too, starting from the difference of the two lays")(
      "max-shift", po::value(&max_shift),
      "largest shift of the whole-node search in mm (0: any with half the smaller map "
      "overlapping); below half the marks' period it keeps a periodic surface from matching a "
      "period away (the refinement below a node may go beyond it)")(
      "json", po::bool_switch(&json), "print compare.json instead of the summary");
  opts.add(analysis.describe());
  opts.add(common_options(common));
  po::options_description all;
  all.add(opts).add_options()("inputs", po::value(&files)->multitoken());
  po::positional_options_description pos;
  pos.add("inputs", 2);
  parse(args, all, pos, common);
  if (common.help) {
    std::cout << opts << "\n";
    return 0;
  }
  const SourceRef cli{"command line"};
  if (files.size() != 2)
    throw InputError(cli, "",
                     "compare needs two inputs: SIM (a file or a run's directory) and MEAS");
  analysis.check();
  if (!(std::isfinite(max_shift) && max_shift >= 0 && max_shift <= 1e6))
    throw InputError(
        cli, "--max-shift",
        "expected a length from 0 to 1e6 mm (0: any shift), got " + format_number(max_shift));
  if (out.empty()) throw InputError(cli, "--out", "expected a directory name");

  const std::string sim_file = surface_file(files[0]), meas_file = surface_file(files[1]);
  analysis.check_spacing_used({sim_file, meas_file});
  auto load = [&](const std::string& f) {
    Surface s = read_surface(f, analysis.spacing);
    s.source = f;
    if (s.valid_count() < 16)
      throw InputError(SourceRef{f}, "",
                       "the map has " + std::to_string(s.valid_count()) +
                           " valid points: expected at least 16 to compare");
    s = analysis.process(std::move(s));
    s.source = f;
    return s;
  };
  const Surface sim = load(sim_file), meas = load(meas_file);
  CompareSettings settings;
  settings.names = analysis.names;
  settings.parameters = analysis.settings;
  settings.registration.rotation = rotation;
  settings.registration.max_shift = max_shift;
  const Comparison c = compare_surfaces(sim, meas, settings);

  CompareInputs inputs{sim_file, meas_file, analysis.processing()};
  const CompareReport report = write_compare_report(out, c, inputs);
  std::cout << (json ? report.json : report.summary);
  return 0;
}

}  // namespace topomill::cli
