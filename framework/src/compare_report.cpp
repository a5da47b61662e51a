#include "compare_report.hpp"

#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "describe.hpp"
#include "io/atomic_file.hpp"
#include "io/png_chart.hpp"
#include "io/png_heatmap.hpp"
#include "metrology/autocorrelation.hpp"
#include "metrology/roughness.hpp"
#include "metrology/roughness_report.hpp"
#include "metrology/spectrum.hpp"
#include "metrology/write_surface.hpp"
#include "topomill/error.hpp"

namespace topomill {

namespace fs = std::filesystem;

namespace {
// measurement - simulation; for directions (deg, repeating every 180) the nearer way round.
double difference(const Roughness::Reported& sim, double meas) {
  const double d = meas - sim.value;
  return sim.unit == "deg" ? std::remainder(d, 180.0) : d;
}

toml::table lay_table(const Lay& l) {
  return toml::table{{"Std_deg", l.std_deg},
                     {"lay_deg", l.lay_deg},
                     {"period_across_lay_mm", l.across_mm},
                     {"period_along_lay_mm", l.along_mm},
                     {"period_x_mm", l.x_mm},
                     {"period_y_mm", l.y_mm}};
}

// The map with its invalid nodes left out of the picture (NaN is drawn as no data; the PNG holds
// colours, not numbers), values scaled so that the heat map's micrometres show `scale` x value.
HeightMap picture(const Surface& s, double scale = 1.0) {
  HeightMap m = s.map;
  for (std::size_t k = 0; k < m.z.size(); ++k) m.z[k] = s.is_valid(k) ? m.z[k] * scale : NAN;
  return m;
}

// The centre of a spectrum's picture, out to `f` (1/mm) each way.
HeightMap crop(const HeightMap& m, double f) {
  const Grid& g = m.grid;
  const auto keep_x = std::min<std::size_t>(g.nx / 2, static_cast<std::size_t>(f / g.dx));
  const auto keep_y = std::min<std::size_t>(g.ny / 2, static_cast<std::size_t>(f / g.dy));
  Grid c = g;
  c.nx = 2 * keep_x + 1, c.ny = 2 * keep_y + 1;
  c.x0 = -static_cast<double>(keep_x) * g.dx, c.y0 = -static_cast<double>(keep_y) * g.dy;
  HeightMap out(c);
  for (std::size_t j = 0; j < c.ny; ++j)
    for (std::size_t i = 0; i < c.nx; ++i)
      out.at(i, j) = m.at(g.nx / 2 - keep_x + i, g.ny / 2 - keep_y + j);
  return out;
}

std::string fixed(double v, int digits = 4) {
  std::ostringstream os;
  os.precision(digits);
  os << v;
  return os.str();
}

const Roughness::Reported* find(const ParameterValues& v, const std::string& name) {
  for (const auto& r : v.reported)
    if (r.name == name) return &r;
  return nullptr;
}
// The report's staging directory beside `dir` (made anew under a name of its own, so that nothing
// planted beside --out stands in for it), after `dir` is checked to be new or an earlier compare's.
fs::path make_stage(const std::string& dir) {
  std::error_code ec;
  if (fs::exists(dir, ec) &&
      !(fs::is_directory(dir, ec) &&
        (fs::is_empty(dir, ec) || fs::exists(fs::path(dir) / "compare.json", ec))))
    throw InputError(SourceRef{"command line"}, "--out",
                     "'" + dir +
                         "' exists and is not an earlier compare's output: expected a new "
                         "directory, or one holding compare.json");
  // Made anew under a name of its own, so that nothing planted beside --out stands in for it.
  std::string stage_name = fs::path(dir).string() + ".incomplete-XXXXXX";
  if (!mkdtemp(stage_name.data()))
    throw InputError(SourceRef{"command line"}, "--out",
                     "cannot write beside '" + dir + "': " + std::strerror(errno) +
                         ": expected a directory you can write into");
  const fs::path stage = stage_name;
  // mkdtemp makes it 0700; the report is shared as any directory the user makes.
  fs::permissions(stage, static_cast<fs::perms>(0777 & ~process_umask()), ec);
  return stage;
}

// The pictures and the difference map, into `stage`; their names.
std::vector<std::string> write_pictures(const fs::path& stage, const Comparison& c,
                                        const CompareInputs& in) {
  auto path = [&](const char* name) { return (stage / name).string(); };
  std::vector<std::string> files;
  write_surface(path("difference.x3p"), c.difference, "--out",
                "measurement - simulation, registered: " + in.meas_file + " - " + in.sim_file);
  files.push_back("difference.x3p");
  HeatmapLabels dl;
  dl.title = "measurement - simulation (registered)";
  dl.y = "y (mm)";
  dl.z = "difference (µm)";
  write_png_heatmap(path("difference.png"), picture(c.difference), dl);
  files.push_back("difference.png");
  write_heatmap_panels(
      path("surfaces.png"),
      {{"simulation", picture(c.sim_overlap)}, {"measurement, registered", picture(c.aligned)}},
      "x (mm)", "y (mm)");
  files.push_back("surfaces.png");
  for (const auto& [tag, surface, lay] : {std::tuple{"sim", &c.sim_overlap, &c.sim_lay},
                                          std::tuple{"meas", &c.aligned, &c.meas_lay}}) {
    const std::string who = std::string(tag) == "sim" ? "simulation" : "measurement";
    HeatmapLabels al;
    al.title = "areal autocorrelation, " + who;
    al.x = "tx (mm)", al.y = "ty (mm)", al.z = "ACF";
    Autocorrelation acf(*surface);
    if (acf.defined()) {
      write_png_heatmap(path((std::string("acf_") + tag + ".png").c_str()),
                        picture(Surface{acf.image(), {}, ""}, 1e-3), al);
      files.push_back(std::string("acf_") + tag + ".png");
    }
    // The spectrum out to eight times the frequency of the finer dominant period: the marks and
    // their harmonics, not the noise floor to Nyquist.
    const PowerSpectrum psd(*surface);
    const double shortest = std::min(lay->across_mm > 0 ? lay->across_mm : INFINITY,
                                     lay->along_mm > 0 ? lay->along_mm : INFINITY);
    HeatmapLabels pl;
    pl.title = "power spectral density, " + who;
    pl.x = "fx (1/mm)", pl.y = "fy (1/mm)", pl.z = "log10 PSD (mm^4)";
    const HeightMap image = psd.image();
    write_png_heatmap(
        path((std::string("psd_") + tag + ".png").c_str()),
        picture(Surface{std::isfinite(shortest) ? crop(image, 8 / shortest) : image, {}, ""}, 1e-3),
        pl);
    files.push_back(std::string("psd_") + tag + ".png");
  }

  return files;
}

// compare.json's content.
std::string compare_json(const Comparison& c, const CompareInputs& in, const Roughness& d,
                         double largest, const std::vector<std::string>& files) {
  const Registration& r = c.registration;
  toml::table params;
  for (const auto& s : c.sim_parameters.reported) {
    const Roughness::Reported* m = find(c.meas_parameters, s.name);
    if (!m) continue;
    const double dv = difference(s, m->value);
    toml::table e{
        {"unit", s.unit}, {"simulation", s.value}, {"measurement", m->value}, {"difference", dv}};
    if (s.value != 0 && s.unit != "deg") e.insert("relative_percent", 100 * dv / std::abs(s.value));
    if (!s.method.empty()) e.insert("method", s.method);
    params.insert(s.name, std::move(e));
  }
  toml::table undefined;
  for (const auto& [who, v] :
       {std::pair{"simulation", &c.sim_parameters}, std::pair{"measurement", &c.meas_parameters}})
    for (const auto& [name, why] : v->undefined) {
      if (!undefined.contains(name)) undefined.insert(name, toml::table{});
      undefined[name].as_table()->insert(who, why);
    }
  toml::array file_list;
  for (const auto& f : files) file_list.push_back(f);
  file_list.push_back("compare.json"), file_list.push_back("compare.md");
  const toml::table root{
      {"simulation", toml::table{{"file", in.sim_file}, {"grid", grid_table(c.sim.map.grid)}}},
      {"measurement", toml::table{{"file", in.meas_file}, {"grid", grid_table(c.meas.map.grid)}}},
      {"processing", in.processing},
      {"common_grid",
       toml::table{{"dx_mm", c.dx}, {"dy_mm", c.dy}, {"interpolation", c.interpolation}}},
      {"registration",
       toml::table{{"tx_mm", r.tx},
                   {"ty_mm", r.ty},
                   {"tx_nodes", r.tx / c.dx},
                   {"ty_nodes", r.ty / c.dy},
                   {"angle_deg", r.angle * 180 / M_PI},
                   {"height_offset_um", r.offset * 1e3},
                   {"correlation", r.correlation},
                   {"rms_um", r.rms * 1e3},
                   {"overlap_nodes", static_cast<std::int64_t>(r.overlap)},
                   {"overlap_share", c.overlap_share},
                   {"iterations", static_cast<std::int64_t>(r.iterations)},
                   {"converged", r.converged},
                   {"model",
                    "MEAS(R(angle) (p - o) + o + t) = SIM(p) + height_offset, o the "
                    "simulation map's centre"}}},
      {"difference", toml::table{{"Sa_um", d.Sa * 1e3},
                                 {"Sq_um", d.Sq * 1e3},
                                 {"max_abs_um", largest * 1e3},
                                 {"mean_um", d.mean * 1e3}}},
      {"parameters", std::move(params)},
      {"undefined", std::move(undefined)},
      {"lay",
       toml::table{{"simulation", lay_table(c.sim_lay)}, {"measurement", lay_table(c.meas_lay)}}},
      {"files", std::move(file_list)},
  };
  return to_json(root);
}

// compare.md and the console summary into rep.
void compare_texts(const Comparison& c, const CompareInputs& in, const Roughness& d, double largest,
                   const std::vector<std::string>& files, const std::string& dir,
                   CompareReport& rep) {
  const Registration& r = c.registration;
  std::ostringstream md, con;
  md << "# topomill compare\n\n"
     << "- simulation: `" << in.sim_file << "`\n- measurement: `" << in.meas_file << "`\n"
     << "- processing (both): " << in.processing << "\n"
     << "- common grid: " << fixed(c.dx * 1e3) << " x " << fixed(c.dy * 1e3) << " um, "
     << c.interpolation << "\n\n## Registration\n\n"
     << "| shift x | shift y | angle | height offset | correlation | residual rms | overlap |\n"
     << "|---|---|---|---|---|---|---|\n"
     << "| " << fixed(r.tx * 1e3) << " um (" << fixed(r.tx / c.dx) << " nodes) | "
     << fixed(r.ty * 1e3) << " um (" << fixed(r.ty / c.dy) << " nodes) | "
     << fixed(r.angle * 180 / M_PI) << " deg | " << fixed(r.offset * 1e3) << " um | "
     << fixed(r.correlation) << " | " << fixed(r.rms * 1e3) << " um | "
     << fixed(100 * c.overlap_share, 3) << " % |\n\n"
     << "## Parameters over the overlap\n\n| parameter | simulation | measurement | difference | "
        "relative |\n"
     << "|---|---|---|---|---|\n";
  con << "simulation   " << in.sim_file << "\nmeasurement  " << in.meas_file << "\nprocessing   "
      << in.processing << "; common grid " << fixed(c.dx * 1e3) << " x " << fixed(c.dy * 1e3)
      << " um (cubic)\nregistered   shift (" << fixed(r.tx * 1e3) << ", " << fixed(r.ty * 1e3)
      << ") um, angle " << fixed(r.angle * 180 / M_PI) << " deg, offset " << fixed(r.offset * 1e3)
      << " um, overlap " << fixed(100 * c.overlap_share, 3) << " %, residual rms "
      << fixed(r.rms * 1e3) << " um\n\n";
  char line[160];
  std::snprintf(line, sizeof line, "%-13s %12s %12s %12s %9s\n", "parameter", "simulation",
                "measurement", "difference", "relative");
  con << line;
  for (const auto& s : c.sim_parameters.reported) {
    const Roughness::Reported* m = find(c.meas_parameters, s.name);
    if (!m) continue;
    const std::string unit = s.unit == "1" ? "" : " " + s.unit;
    const double dv = difference(s, m->value);
    const std::string rel =
        s.value != 0 && s.unit != "deg" ? fixed(100 * dv / std::abs(s.value), 3) + " %" : "-";
    md << "| " << s.name << " | " << fixed(s.value) << unit << " | " << fixed(m->value) << unit
       << " | " << fixed(dv) << unit << " | " << rel << " |\n";
    std::snprintf(line, sizeof line, "%-13s %12.5g %12.5g %12.5g %9s  %s\n", (s.name).c_str(),
                  s.value, m->value, dv, rel.c_str(), s.unit == "1" ? "" : s.unit.c_str());
    con << line;
  }
  for (const auto& [name, why] : c.sim_parameters.undefined)
    md << "| " << name << " | undefined: " << why << " | | | |\n";
  auto lay_row = [&](const char* who, const Lay& l) {
    md << "| " << who << " | " << fixed(l.std_deg) << " deg | " << fixed(l.lay_deg) << " deg | "
       << fixed(l.across_mm * 1e3) << " um | " << fixed(l.along_mm * 1e3) << " um | "
       << fixed(l.x_mm * 1e3) << " um | " << fixed(l.y_mm * 1e3) << " um |\n";
    con << "lay          " << who << ": Std " << fixed(l.std_deg) << " deg, periods across "
        << fixed(l.across_mm * 1e3) << " um, along " << fixed(l.along_mm * 1e3) << " um (x "
        << fixed(l.x_mm * 1e3) << ", y " << fixed(l.y_mm * 1e3) << ")\n";
  };
  md << "\n## Lay and dominant periods\n\n| | Std | lay | period across | period along | along X | "
        "along Y |\n"
     << "|---|---|---|---|---|---|---|\n";
  con << "\n";
  lay_row("simulation", c.sim_lay);
  lay_row("measurement", c.meas_lay);
  md << "\n## Difference (measurement - simulation)\n\nSa " << fixed(d.Sa * 1e3) << " um, Sq "
     << fixed(d.Sq * 1e3) << " um, largest " << fixed(largest * 1e3) << " um.\n\n";
  for (const auto& f : files)
    if (f.size() > 4 && f.substr(f.size() - 4) == ".png") md << "![" << f << "](" << f << ")\n";
  con << "difference   Sa " << fixed(d.Sa * 1e3) << " um, Sq " << fixed(d.Sq * 1e3)
      << " um, largest " << fixed(largest * 1e3) << " um\noutputs      " << dir
      << "/compare.json, compare.md";
  for (const auto& f : files) con << ", " << f;
  con << "\n";
  rep.markdown = md.str();
  rep.summary = con.str();
}

}  // namespace

CompareReport write_compare_report(const std::string& dir_given, const Comparison& c,
                                   const CompareInputs& in) {
  // "out/" and "out" alike: the stage must sit beside the directory, not inside it.
  fs::path normal = fs::path(dir_given).lexically_normal();
  if (!normal.has_filename()) normal = normal.parent_path();
  const std::string dir = normal.string();
  const fs::path stage = make_stage(dir);
  auto path = [&](const char* name) { return (stage / name).string(); };
  std::error_code ec;
  std::vector<std::string> files;
  try {
    files = write_pictures(stage, c, in);
  } catch (...) {
    fs::remove_all(stage, ec);
    throw;
  }
  // The difference's own statistics (um): how far apart the two are, node by node.
  const Roughness d = roughness(c.difference.map, c.difference.valid);
  double largest = 0;
  for (std::size_t k = 0; k < c.difference.map.z.size(); ++k)
    if (c.difference.is_valid(k)) largest = std::max(largest, std::abs(c.difference.map.z[k]));
  CompareReport rep;
  rep.json = compare_json(c, in, d, largest, files);
  compare_texts(c, in, d, largest, files, dir, rep);
  try {
    write_atomically(path("compare.json"), [&](std::ostream& o) { o << rep.json; });
    write_atomically(path("compare.md"), [&](std::ostream& o) { o << rep.markdown; });
    // Into place: the earlier output (checked above to be a compare's) goes, the new one moves in.
    try {
      if (fs::exists(dir, ec)) fs::remove_all(dir);
      fs::rename(stage, dir);
    } catch (const fs::filesystem_error& e) {
      throw InputError(SourceRef{"command line"}, "--out",
                       "cannot put the report at '" + dir + "': " + e.code().message() +
                           ": expected a directory you may replace or create");
    }
  } catch (...) {
    fs::remove_all(stage, ec);
    throw;
  }
  return rep;
}

}  // namespace topomill
