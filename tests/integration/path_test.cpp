// The tool path slot: raster and raster_across lay out the passes the core laid out before the
// path was a slot (the same bits), and zigzag's reversed passes are what a mirror says they are.
#include <catch2/catch.hpp>
#include <cmath>
#include <sstream>

#include "support/run_command.hpp"
#include "support/scenes.hpp"

using testing::run_scene;

namespace {

// A flat plate under a vertical tool with a helix-free edge (its mirror image is itself), the
// paper's feed and step-over, ap 0.1 mm, patch centred on y = 0 (0.34 mm long: its marks are not
// symmetric about y = 0, so that the mirror image is another map).
std::string plate(const std::string& direction, const std::string& path) {
  std::ostringstream s;
  s << "[tool]\nplugin = 'ball_end_constant_lead'\nradius = 5.0\nteeth = 2\nhelix_angle = 0\n"
    << "[workpiece]\nplugin = 'inclined_plane'\n"
    << "[cutting]\nspindle_speed = 4000\nfeed_per_tooth = 0.1\ndepth_of_cut = 0.1\n"
    << "stepover = 0.3\nspindle_direction = '" << direction << "'\n"
    << "[path]\n"
    << path << "\n"
    << "[region]\nlambda = 0.0\nsize = [0.6, 0.34]\nspacing = 0.005\n";
  return s.str();
}

topomill::Prepared prepared(const std::string& scene) {
  auto doc = topomill::SceneDocument::parse_string(scene, "path.toml");
  topomill::PluginCatalog catalog({{topomill::PluginCatalog::builtin_dir(), "built-in"}});
  return topomill::prepare(doc.resolve(catalog), catalog);
}

// The CSV's height rows (its `#` header names the time of writing and is left out).
std::string csv_rows(const std::string& path) {
  std::istringstream in(testing::read_file(path));
  std::string line, rows;
  while (std::getline(in, line))
    if (!line.empty() && line[0] != '#') rows += line + "\n";
  return rows;
}

}  // namespace

TEST_CASE("zigzag's reversed passes are the mirror image of its forward ones", "[path]") {
  // Mirroring y about the patch's centre line (y = 0 on the plate) turns a pass feeding +Y into
  // one feeding -Y from the far end, and the spindle's sense: cw with the pass through x = 0
  // forward is, mirrored, ccw with that pass reversed. The start angle 0 mirrors to 0 and the
  // helix-free edge to itself.
  // With vibration and deflection too: the force's chip thickness follows the feed's direction
  // (a reversed pass's force is the mirror image), and the modes are along X and Y.
  const std::string evaluator = GENERATE(as<std::string>{}, "tooth_passage", "zmap");
  const bool effects = GENERATE(false, true);
  if (effects && evaluator == "zmap") return;  // the path's correction is the evaluator's input
  const std::vector<std::string> o{"evaluator.plugin=" + evaluator};
  const std::string extra = effects ? testing::dynamics_tables() : "";
  const auto a = run_scene(plate("cw", "plugin = 'zigzag'") + extra, o);
  const auto b = run_scene(plate("ccw", "plugin = 'zigzag'\neven_passes = 'reverse'") + extra, o);
  const auto& g = a.raw.grid;
  REQUIRE(g.ny == b.raw.grid.ny);
  double mirror = 0, same = 0;
  for (std::size_t j = 0; j < g.ny; ++j)
    for (std::size_t i = 0; i < g.nx; ++i) {
      mirror = std::max(mirror, std::abs(a.raw.at(i, j) - b.raw.at(i, g.ny - 1 - j)));
      same = std::max(same, std::abs(a.raw.at(i, j) - b.raw.at(i, j)));
    }
  INFO(evaluator << (effects ? " with effects" : "")
                 << ": largest difference from the mirror image " << mirror * 1e6
                 << " nm, from the unmirrored map " << same * 1e6 << " nm");
  // Ideal, both evaluators mirror to round-off (seen: 0 and 1e-15 mm). With effects a force
  // sample's edge elements are taken in or out of the material one by one, and a mirrored
  // angle's rounding can move one across the boundary: 1.8 nm seen. A pass whose chip thickness
  // kept the forward feed's sign is micrometres off.
  CHECK(mirror < (effects ? 1e-5 : 1e-9));
  CHECK(same > 1e-4);
}

TEST_CASE("zigzag reverses every second pass and leaves the others as raster lays them", "[path]") {
  // Columns 0.05 mm beside a pass are cut by that pass alone: beside the pass through x = 0
  // (forward in both) zigzag is raster to the bit; beside the one at x = 0.3 (reversed) it is
  // not (up- and down-milling swap sides: the marks turn half round).
  const auto raster = run_scene(plate("cw", "plugin = 'raster'"), {});
  const auto zigzag = run_scene(plate("cw", "plugin = 'zigzag'"), {});
  const auto& g = raster.raw.grid;
  auto column_difference = [&](double x) {
    const auto i = static_cast<std::size_t>(std::lround((x - g.x0) / g.dx));
    double worst = 0;
    for (std::size_t j = 0; j < g.ny; ++j)
      worst = std::max(worst, std::abs(raster.raw.at(i, j) - zigzag.raw.at(i, j)));
    return worst;
  };
  CHECK(column_difference(0.05) == 0);
  CHECK(column_difference(0.25) > 1e-4);

  // The layout itself: directions alternate, a reversed pass runs from the forward one's end to
  // its start in the same time, and the pass through the centre follows even_passes.
  for (const char* even : {"forward", "reverse"})
    for (const char* axis : {"y", "x"}) {
      const auto m = prepared(plate("cw", std::string("plugin = 'zigzag'\neven_passes = '") + even +
                                              "'\nfeed_axis = '" + axis + "'"));
      const topomill::ToolPath& path = *m.layout.path;
      REQUIRE(path.passes() >= 3);
      const bool along_y = std::string(axis) == "y";
      for (std::size_t p = 0; p < path.passes(); ++p) {
        const auto& pass = path.pass(p);
        const double d = along_y ? pass.dy : pass.dx;
        CHECK((along_y ? pass.dx : pass.dy) == 0);
        CHECK(std::abs(d) == 1);
        if (p > 0) CHECK(d == -(along_y ? path.pass(p - 1).dy : path.pass(p - 1).dx));
        // Where the step puts the centre: x = 0 (along Y) or the patch's centre line (along X).
        const double across = along_y ? pass.x : pass.y_start;
        if (std::abs(across) < 1e-12) CHECK(d == (std::string(even) == "forward" ? 1 : -1));
        if (p > 0) {
          const auto& prev = path.pass(p - 1);
          CHECK(pass.t_end == prev.t_end);
          const double start = along_y ? pass.y_start : pass.x;
          const double prev_start = along_y ? prev.y_start : prev.x;
          const double prev_end = prev_start + path.feed_speed() * d * -1 * prev.t_end;
          CHECK(start == Approx(prev_end).margin(1e-12));
        }
      }
    }
}

TEST_CASE("raster and raster_across give the bits kept in tests/refdata/raster_bits", "[path]") {
  // tests/refdata/raster_bits/: height_raw.csv of each case, 20 um grid, 2 threads, as this tree
  // writes it: first by the last commit with the path laid out by the core (6424af8). They guard
  // a restructuring against changing any bit. A change that moves them on purpose writes them
  // again, is checked against the files before, and says in its commit which heights moved and
  // how far (their history: git log tests/refdata/raster_bits).
  // The CSV's numbers are the shortest that read back to the same double: equal text, equal bits.
  struct Case {
    const char* file;
    const char* scene;
    const char* evaluator;
  };
  const Case c =
      GENERATE(Case{"lambda30_tooth_passage", "configs/paper/lambda30.toml", "tooth_passage"},
               Case{"lambda0_zmap", "configs/paper/lambda0.toml", "zmap"},
               Case{"lambda30_fz01_dynamics_tooth_passage",
                    "configs/paper/lambda30_fz01_dynamics.toml", "tooth_passage"},
               Case{"scallop_flat_across_tooth_passage",
                    "configs/validation/scallop_flat_across.toml", "tooth_passage"});
  INFO(c.file);
  const std::string out = testing::temp_dir(std::string("raster_bits_") + c.file);
  const auto r =
      testing::run_topomill(std::string("run ") + c.scene + " -q --threads 2 --out '" + out +
                            "' --set evaluator.plugin=" + c.evaluator +
                            " --set region.spacing=0.02 --set 'output.formats=[\"csv\"]'");
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  const std::string expected =
      csv_rows(testing::source_dir() + "/tests/refdata/raster_bits/" + c.file + ".csv");
  REQUIRE_FALSE(expected.empty());
  CHECK(csv_rows(out + "/height_raw.csv") == expected);
}
