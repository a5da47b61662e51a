// Scenes and cutter-location files for the CL tests (support/cl_scenes.hpp).
#include "support/cl_scenes.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "support/run_command.hpp"

namespace testing::cl {

// A vertical ball end (R 1 mm, two teeth, helix 20 deg) on a plate or the convex arc (r 20 mm);
// `paper`: the paper's tool and cut (R 5 mm, fz 0.1, ae 0.3, ap 0.1), for which the effects'
// tables (testing::dynamics_tables) are made.
std::string scene(const std::string& workpiece, const std::string& path, double spacing,
                  double size, const std::string& place, bool paper) {
  std::ostringstream s;
  s.precision(17);
  s << "[tool]\nplugin = 'ball_end_constant_lead'\nradius = " << (paper ? 5.0 : 1.0)
    << "\nteeth = 2\nhelix_angle = 20\n"
    << "[workpiece]\n"
    << workpiece << "\n[cutting]\n"
    << (paper ? "spindle_speed = 4000\nfeed_per_tooth = 0.1\ndepth_of_cut = 0.1\nstepover = 0.3\n"
              : "spindle_speed = 6000\nfeed_per_tooth = 0.03\ndepth_of_cut = 0.02\n"
                "stepover = 0.06\n")
    << "spindle_direction = 'cw'\n"
    << "[path]\n"
    << path << "\n[region]\n"
    << place << "\nsize = [" << size << ", " << size << "]\nspacing = " << spacing << "\n";
  return s.str();
}

topomill::Prepared prepared(const std::string& toml, const std::vector<std::string>& set) {
  auto doc = topomill::SceneDocument::parse_string(toml, "cl.toml");
  for (const auto& s : set) doc.apply_override(s);
  topomill::PluginCatalog catalog({{topomill::PluginCatalog::builtin_dir(), "built-in"}});
  return topomill::prepare(doc.resolve(catalog), catalog);
}

// This run's folder for CL files.
std::string cl_dir() {
  static const std::string dir = [] {
    const std::string d = testing::temp_dir("cl_file");
    std::filesystem::create_directories(d);
    return d;
  }();
  return dir;
}

std::string cl_path(const std::string& file, const std::string& point) {
  return "plugin = 'cl_file'\nfile = '" + file + "'\npoint = '" + point + "'";
}

// A pass's ball centre without the runout (the CL data locate the spindle's axis).
topomill::Vec3 spindle_centre(const topomill::ToolPath& path, std::size_t p, double t) {
  return path.nominal_centre(p, t) - path.runout_offset(p, t);
}

// Writes `path`'s passes as CL data, `points` per pass evenly in time, with the axis when
// `axes`: CSV (a blank line between passes) or APT (RAPID before each pass's first point). With
// `feeds` (CSV) each point carries the feed of the move to it, its chord over its time: the CL
// pass keeps the path's times.
std::string write_cl(const topomill::ToolPath& path, int points, bool axes, bool apt,
                     const std::string& name, bool feeds) {
  const std::string file = cl_dir() + "/" + name + (apt ? ".cl" : ".csv");
  std::ofstream out(file);
  char buf[256];
  if (!apt) out << (axes ? "x,y,z,i,j,k" : "x,y,z") << (feeds ? ",f\n" : "\n");
  if (apt) out << "PARTNO/written by cl_file_test\nUNITS/MM\nMULTAX\n";
  for (std::size_t p = 0; p < path.passes(); ++p) {
    if (apt) out << "RAPID\n";
    for (int k = 0; k < points; ++k) {
      const double t = path.pass(p).t_end * k / (points - 1);
      const topomill::Vec3 c = spindle_centre(path, p, t), a = path.axis(p, t);
      if (axes)
        std::snprintf(buf, sizeof buf, "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g", c.x(), c.y(), c.z(),
                      a.x(), a.y(), a.z());
      else
        std::snprintf(buf, sizeof buf, "%.17g,%.17g,%.17g", c.x(), c.y(), c.z());
      out << (apt ? "GOTO/" : "") << buf;
      if (feeds) {
        const double dt = path.pass(p).t_end / (points - 1), tk = k > 0 ? t : dt;
        const double chord =
            (spindle_centre(path, p, tk) - spindle_centre(path, p, tk - dt)).norm();
        std::snprintf(buf, sizeof buf, ",%.17g", chord / dt * 60);
        out << buf;
      }
      out << "\n";
    }
    if (!apt) out << "\n";
  }
  if (apt) out << "FINI\n";
  return file;
}

double largest_difference(const topomill::HeightMap& a, const topomill::HeightMap& b) {
  REQUIRE(a.grid.nx == b.grid.nx);
  REQUIRE(a.grid.ny == b.grid.ny);
  double worst = 0;
  for (std::size_t i = 0; i < a.z.size(); ++i) worst = std::max(worst, std::abs(a.z[i] - b.z[i]));
  return worst;
}

}  // namespace testing::cl
