// Cutter-location data's feeds: the file's own speed moves the tool and sets the force model's
// chip (a raster written at twice the scene's feed is the raster at 2 fz), and FEDRAT in inches
// per minute is 25.4 mm/min an inch.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <fstream>

#include "support/cl_scenes.hpp"
#include "support/scenes.hpp"

using testing::run_scene;
using namespace testing::cl;

TEST_CASE("CL data's own feed sets the chip: twice the scene's feed is the raster at 2 fz",
          "[cl]") {
  // The file's f column moves the tool at its own speed, and the force model's feed per tooth
  // follows it (speed x 2 pi / omega / teeth): a raster written at fz = 0.2 mm and read into a
  // scene of fz = 0.1 mm is the fz = 0.2 mm raster, forces and all, away from the passes' ends
  // (see above).
  const std::string tables = testing::dynamics_tables();
  const std::vector<std::string> twice{"cutting.feed_per_tooth=0.2"};
  const std::string raster_scene =
      scene(kPlate, "plugin = 'raster'", 0.01, 0.3, "lambda = 0.0", true) + tables;
  const auto m = prepared(raster_scene, twice);
  const std::string file = write_cl(*m.layout.path, 2, false, false, "twice", true);
  const auto raster = run_scene(raster_scene, twice);
  const auto cl = run_scene(scene(kPlate, cl_path(file), 0.01, 0.3, "lambda = 0.0", true) + tables);
  const topomill::ToolPath &a = *raster.layout.path, &b = *cl.layout.path;
  REQUIRE(a.passes() == b.passes());
  const double reach = std::sqrt(2 * 5.0 * 0.1 - 0.1 * 0.1);
  double inside = 0;
  for (std::size_t p = 1; p < a.passes(); ++p) {
    const auto &ca = a.correction_samples(p).values, &cb = b.correction_samples(p).values;
    REQUIRE(ca.size() == cb.size());
    for (std::size_t k = 0; k < ca.size(); ++k)
      if ((a.pass(p).t_end - a.correction_step(p) * k) * a.feed_speed() > reach)
        inside = std::max(inside, (ca[k] - cb[k]).norm());
  }
  INFO("corrections apart by " << inside * 1e3 << " um");
  CHECK(inside < 1e-9);
  CHECK(largest_difference(raster.raw, cl.raw) < 1e-9);
}

TEST_CASE("a feed in inches per minute is 25.4 mm/min an inch, end to end", "[cl]") {
  // The raster at 2 fz written as APT with its speed in FEDRAT, once in mm/min and once in in/min
  // (1 in = 25.4 mm exactly), each read into a scene of fz: both are the raster at 2 fz. Left
  // unconverted, IPM moves the tool 25.4 times slower: its marks 25.4 times closer.
  const std::vector<std::string> twice{"cutting.feed_per_tooth=0.06"};
  const std::string raster_scene = scene(kPlate, "plugin = 'raster'", 0.004, 0.1);
  const auto m = prepared(raster_scene, twice);
  const topomill::ToolPath& path = *m.layout.path;
  const double mm_per_min = path.feed_speed() * 60;
  auto write = [&](const std::string& name, const std::string& fedrat) {
    const std::string file = cl_dir() + "/" + name + ".cl";
    std::ofstream out(file);
    out << "PARTNO/" << name << "\nUNITS/MM\n" << fedrat << "\n";
    char buf[256];
    for (std::size_t p = 0; p < path.passes(); ++p) {
      out << "RAPID\n";
      for (const double t : {0.0, path.pass(p).t_end}) {
        const topomill::Vec3 c = spindle_centre(path, p, t);
        std::snprintf(buf, sizeof buf, "GOTO/%.17g,%.17g,%.17g\n", c.x(), c.y(), c.z());
        out << buf;
      }
    }
    out << "FINI\n";
    return file;
  };
  char rate[128];
  std::snprintf(rate, sizeof rate, "FEDRAT/MMPM,%.17g", mm_per_min);
  const std::string mmpm = write("feed_mmpm", rate);
  std::snprintf(rate, sizeof rate, "FEDRAT/IPM,%.17g", mm_per_min / 25.4);
  const std::string ipm = write("feed_ipm", rate);
  const auto raster = run_scene(raster_scene, twice);
  const auto in_mm = run_scene(scene(kPlate, cl_path(mmpm), 0.004, 0.1));
  const auto in_inches = run_scene(scene(kPlate, cl_path(ipm), 0.004, 0.1));
  CHECK(largest_difference(raster.raw, in_mm.raw) < 1e-9);
  CHECK(largest_difference(in_mm.raw, in_inches.raw) < 1e-9);
}
