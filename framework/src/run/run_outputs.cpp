#include "run/run_outputs.hpp"

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <sstream>

#include "code_fingerprint.hpp"
#include "describe.hpp"
#include "interrupt.hpp"
#include "io/atomic_file.hpp"
#include "io/cl_csv.hpp"
#include "io/csv.hpp"
#include "io/file_info.hpp"
#include "io/gsf.hpp"
#include "io/png_heatmap.hpp"
#include "io/png_surface3d.hpp"
#include "io/sdf.hpp"
#include "io/vts.hpp"
#include "io/x3p.hpp"
#include "log.hpp"
#include "metrology/roughness_report.hpp"
#include "topomill/version.hpp"

namespace fs = std::filesystem;

namespace topomill {

namespace {

// The staging directories' names: ".incomplete." and six random characters.
constexpr const char* kStagingPrefix = ".incomplete.";

// A dead run's staging directories and files (this run holds the lock: no live run has one). A
// link named so is removed, not followed.
void remove_stale_staging(const std::string& out_dir) {
  std::error_code ec;
  for (fs::directory_iterator it(out_dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.rfind(kStagingPrefix, 0) == 0 ||
        (name.front() == '.' && name.find(kStagingSuffix) != std::string::npos)) {
      std::error_code gone;
      fs::remove_all(it->path(), gone);
    }
  }
}

fs::path make_staging_dir(const std::string& out_dir) {
  std::string name = (fs::path(out_dir) / kStagingPrefix).string() + "XXXXXX";
  if (!mkdtemp(name.data()))
    throw InputError(SourceRef{"command line"}, "--out",
                     "cannot write into the output directory '" + out_dir + "': " +
                         std::strerror(errno) + ": expected a directory you can write into");
  return name;
}

// The height maps (and the tool path) in the scene's formats, into `staging`; their names.
std::vector<std::string> write_map_files(const RunSettings& settings, const RunResult& result,
                                         const fs::path& staging) {
  std::vector<std::string> files;
  auto path = [&](const std::string& name) {
    files.push_back(name);
    return (staging / name).string();
  };
  // Every file names its map, the program, the time and the scene.
  const std::time_t now = std::time(nullptr);
  const std::string& described = settings.described;
  const FileInfo raw_info{"topomill raw height (in plan, the evaluation grid)", described, now};
  const FileInfo residual_info{std::string("topomill residual height (") +
                                   (settings.unrolled() ? "along the surface" : "in plan") +
                                   ", form " + settings.form + " removed)",
                               described, now};
  for (const auto& format : settings.formats) {
    throw_if_interrupted();  // between files: a stop request is honoured while writing too
    if (format == "csv") {
      write_csv(path("height_raw.csv"), result.raw, raw_info);
      write_csv(path("height_residual.csv"), result.residual, residual_info);
    } else if (format == "gsf") {
      write_gsf(path("height_raw.gsf"), result.raw, raw_info);
      write_gsf(path("height_residual.gsf"), result.residual, residual_info);
    } else if (format == "x3p") {
      write_x3p(path("height_raw.x3p"), result.raw, raw_info);
      write_x3p(path("height_residual.x3p"), result.residual, residual_info);
    } else if (format == "sdf") {
      write_sdf(path("height_raw.sdf"), result.raw, raw_info);
      write_sdf(path("height_residual.sdf"), result.residual, residual_info);
    } else if (format == "cl") {
      write_cl_csv(path("tool_path.csv"), *result.layout.path,
                   {"topomill tool path (cutter-location data)", described, now});
    } else if (format == "vts") {
      write_vts(path("height_raw.vts"), result.raw);
      write_vts(path("height_residual.vts"), result.residual);
    } else if (format == "png") {
      HeatmapLabels labels;
      if (!settings.unrolled()) labels.y = "y (mm)";
      char sa[64];
      std::snprintf(sa, sizeof sa, "   Sa %.4g µm", result.roughness.Sa * 1e3);
      labels.title = settings.name + sa;
      labels.z = "h (µm), form " + settings.form + " removed";
      write_png_heatmap(path("height_residual.png"), result.residual, labels);
      write_png_surface3d(path("height_residual_3d.png"), result.residual, labels.title, labels.x,
                          labels.y);
    }
  }
  return files;
}

// The staged files moved into `out_dir`, after the old summary is removed (it would vouch for
// files about to be replaced); what would make a move fail is refused before anything visible
// changes.
void move_into_place(const std::string& out_dir, const fs::path& staging,
                     const std::vector<std::string>& files) {
  std::error_code ec;
  std::vector<std::string> targets = files;
  targets.push_back("summary.json");
  for (const auto& f : targets)
    if (fs::is_directory(fs::path(out_dir) / f, ec))
      throw InputError(SourceRef{"command line"}, "--out",
                       "'" + (fs::path(out_dir) / f).string() +
                           "' is a directory: expected a file there, or nothing (remove it or "
                           "choose another output directory)");
  // The last moment a stop request can be honoured: after it, the old result is replaced.
  throw_if_interrupted();
  fs::remove(fs::path(out_dir) / "summary.json", ec);
  for (const auto& f : files) fs::rename(staging / f, fs::path(out_dir) / f);
  fs::remove(staging, ec);
}

// The human-readable result printed on stdout.
std::string summary_text(const RunResult& result, const std::string& out_dir,
                         const std::vector<std::string>& files) {
  std::ostringstream os;
  os.precision(4);
  os << "scene    " << result.settings.file << "\n";
  const Grid &raw = result.raw.grid, &res = result.residual.grid;
  os << "grids    height_raw " << raw.nx << " x " << raw.ny << " nodes in plan, dx " << raw.dx * 1e3
     << " um, dy " << raw.dy * 1e3 << " um; height_residual " << res.nx << " x " << res.ny
     << " nodes " << (result.settings.unrolled() ? "along the surface" : "in plan") << ", "
     << res.dx * 1e3 << " x " << res.dy * 1e3 << " um\n";
  os << roughness_text(result.parameters, "   ", 4) << "\n";
  os << "time     ";
  for (const auto& s : result.stages) os << s.name << " " << s.seconds << " s  ";
  os << "\noutputs  " << out_dir << "/summary.json";
  for (const auto& f : files) os << " " << f;
  os << "\n";
  return os.str();
}

}  // namespace

std::string summary_json(const RunResult& result, const std::vector<std::string>& files,
                         double write_s, std::chrono::steady_clock::time_point started) {
  const RunSettings& settings = result.settings;
  toml::table timing;
  toml::array stage_names;
  for (const auto& s : result.stages) {
    timing.insert(s.name, s.seconds);
    stage_names.push_back(s.name);
  }
  timing.insert("output", write_s);
  stage_names.push_back("output");
  timing.insert("total",
                std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count());
  toml::table plugins;
  std::vector<std::string> libraries;
  for (const auto& p : settings.plugins) {
    plugins.insert(
        p.table,
        toml::table{{"model", p.model}, {"library", p.library}, {"library_version", p.version}});
    libraries.push_back(p.library);
  }
  toml::table work;
  for (const auto& [k, v] : result.work) work.insert(k, static_cast<std::int64_t>(v));
  toml::array effects, file_list;
  for (const auto& e : result.effects) effects.push_back(e);
  for (const auto& f : files) file_list.push_back(f);
  // The files the models read, each with its bytes' checksum when read: a resumed sweep or
  // study runs the case again when one differs (case_runner.cpp).
  toml::array inputs;
  for (const auto& [file, crc] : result.input_files)
    inputs.push_back(toml::table{{"file", file}, {"crc32", crc}});
  toml::table root{
      {"topomill", toml::table{{"version", kVersion},
                               {"abi", static_cast<std::int64_t>(kAbiVersion)},
                               {"code_fingerprint", code_fingerprint(libraries)}}},
      {"scene", toml::table{{"file", settings.file}, {"name", settings.name}}},
      {"resolved_scene", settings.resolved},
      {"plugins", std::move(plugins)},
      {"effects", std::move(effects)},
      {"stages", std::move(stage_names)},
      {"grid", toml::table{{"spacing_mm", result.layout.spacing},
                           {"zmap", grid_table(result.raw.grid)},
                           {"residual", grid_table(result.residual.grid)},
                           {"form", settings.form},
                           {"passes", static_cast<std::int64_t>(result.layout.path->passes())}}},
      {"roughness", roughness_table(result.parameters)},
      {"inputs", std::move(inputs)},
      {"effects_detail", toml::table{{"time_step_s", result.dynamics_step},
                                     {"peak_force_N", result.peak_force},
                                     {"peak_correction_mm", result.peak_correction}}},
      {"timing_s", std::move(timing)},
      {"work", std::move(work)},
      {"files", std::move(file_list)},
  };
  return to_json(root);
}

RunSummary write_run_outputs(const RunResult& result, const std::string& out_dir,
                             std::chrono::steady_clock::time_point started) {
  // The caller holds the directory's OutputLock: this run is its only writer. Files are written
  // into a hidden staging directory and moved in only when all are whole, so a killed run leaves
  // its pieces there (removed by the next run), never beside summary.json. The directory is made
  // anew under a name of its own (mkdtemp), so nothing planted in the output directory can stand
  // in for it.
  remove_stale_staging(out_dir);
  const fs::path staging = make_staging_dir(out_dir);
  const auto t0 = std::chrono::steady_clock::now();
  const std::vector<std::string> files = write_map_files(result.settings, result, staging);
  move_into_place(out_dir, staging, files);
  const double write_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  RunSummary summary;
  summary.json = summary_json(result, files, write_s, started);
  write_atomically((fs::path(out_dir) / "summary.json").string(),
                   [&](std::ostream& out) { out << summary.json; });
  summary.text = summary_text(result, out_dir, files);
  log_debug("wrote " + std::to_string(files.size() + 1) + " files to " + out_dir);
  return summary;
}

}  // namespace topomill
