// Cutter-location data as the tool path (cl_file): the raster written as CL data, in either form,
// is the raster again to the bit; passes in any direction are cut where an independent brute
// force cuts them; a 5-axis raster written as CL points (the axis turning) is that raster to the
// points' chord error; the force model's material test over CL passes (every earlier pass, not
// only the one before) matches the raster's on parallel passes.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>

#include "support/brute_force.hpp"
#include "support/cl_scenes.hpp"
#include "support/run_command.hpp"
#include "support/scenes.hpp"

using testing::run_scene;
using namespace testing::cl;

namespace {

// The largest difference of a map from the brute force at every node but those `skip` says,
// where it is, and how many nodes were compared.
struct Against {
  double worst = 0;
  std::string where;
  std::size_t nodes = 0;
};
template <class Skip>
Against against_brute_force(const topomill::Prepared& m, const topomill::RunResult& r, Skip skip) {
  const auto& g = r.raw.grid;
  Against worst;
  for (std::size_t j = 0; j < g.ny; ++j)
    for (std::size_t i = 0; i < g.nx; ++i) {
      if (skip(g.x(i), g.y(j))) continue;
      ++worst.nodes;
      const double b = testing::brute_force_height(*m.tool, *m.layout.path, g.x(i), g.y(j));
      if (std::abs(r.raw.at(i, j) - b) <= worst.worst) continue;
      std::ostringstream at;
      at.precision(12);
      at << "(" << g.x(i) << ", " << g.y(j) << "): " << r.raw.at(i, j) << " against " << b;
      worst.worst = std::abs(r.raw.at(i, j) - b), worst.where = at.str();
    }
  return worst;
}

}  // namespace

TEST_CASE("the raster written as CL data is the raster again, to the bit", "[cl]") {
  // On a plate each raster pass's centre is a straight line along Y at the feed speed: two CL
  // points per pass locate it, and the segment's direction (0, +-1, 0), its speed (the scene's
  // feed: the file gives none) and its time (length / speed) are the raster's own numbers.
  const std::string evaluator = GENERATE(as<std::string>{}, "tooth_passage", "zmap");
  const bool apt = GENERATE(false, true);
  const bool runout = GENERATE(false, true);
  const std::string extra = runout ? "\n[runout]\noffset = 0.004\nangle = 30\n" : "";
  const std::vector<std::string> set{"evaluator.plugin=" + evaluator};
  const std::string raster_scene = scene(kPlate, "plugin = 'zigzag'", 0.004, 0.1) + extra;
  const auto m = prepared(raster_scene, set);
  const std::string file = write_cl(*m.layout.path, 2, false, apt, "raster");
  const auto raster = run_scene(raster_scene, set);
  const auto cl = run_scene(scene(kPlate, cl_path(file), 0.004, 0.1) + extra, set);
  INFO(evaluator << (apt ? ", APT" : ", CSV") << (runout ? ", runout 4 um" : ""));
  CHECK(largest_difference(raster.raw, cl.raw) == 0);
  // The same points as tool tips (R below the centres along the vertical axis).
  if (!apt && !runout) {
    const std::string tips = cl_dir() + "/tips.csv";
    std::ifstream in(file);
    std::ofstream out(tips);
    std::string line;
    std::getline(in, line), out << line << "\n";
    while (std::getline(in, line)) {
      double x, y, z;
      if (std::sscanf(line.c_str(), "%lf,%lf,%lf", &x, &y, &z) != 3) {
        out << line << "\n";
        continue;
      }
      char buf[128];
      std::snprintf(buf, sizeof buf, "%.17g,%.17g,%.17g\n", x, y, z - 1.0);
      out << buf;
    }
    out.close();
    const auto tip = run_scene(scene(kPlate, cl_path(tips, "tip"), 0.004, 0.1), set);
    CHECK(largest_difference(raster.raw, tip.raw) < 1e-12);
  }
}

TEST_CASE("the raster written as CL data gives the raster's forces and corrections", "[cl]") {
  // With vibration and deflection the force model asks which edge points are in material. Over
  // CL data that is every earlier pass's swept ball and the pass's own earlier loops; over the
  // raster's parallel passes it is the pass before's alone. On parallel passes the two agree
  // (the pass before covers the ones before it), and the chip's feed per tooth from the CL
  // speed is fz: the maps agree to round-off.
  const std::string raster_scene =
      scene(kPlate, "plugin = 'raster'", 0.01, 0.3, "lambda = 0.0", true) +
      testing::dynamics_tables();
  const auto m = prepared(raster_scene);
  const std::string file = write_cl(*m.layout.path, 2, false, false, "raster_effects");
  const auto raster = run_scene(raster_scene);
  const auto cl = run_scene(scene(kPlate, cl_path(file), 0.01, 0.3, "lambda = 0.0", true) +
                            testing::dynamics_tables());
  REQUIRE(raster.peak_correction > 1e-4);
  // Two differences, both right for CL data: the raster's material test assumes a pass a
  // step-over before its first (the paper's steady state) and takes the pass before as an
  // endless line, while nothing was cut before the CL data's first pass (a full slot: 60 against
  // 50 um of correction) and the pass before ends where it ended (as the ball nears the end, the
  // material ahead of it was not cut by it). Elsewhere the two agree to the bit: from the second
  // pass on, while the centre is farther from the pass's end than the cut's radius
  // sqrt(2 R ap - ap^2) (they part at 0.65 mm).
  const topomill::ToolPath &a = *raster.layout.path, &b = *cl.layout.path;
  REQUIRE(a.passes() == b.passes());
  const double reach = std::sqrt(2 * 5.0 * 0.1 - 0.1 * 0.1);
  double first = 0, inside = 0, end = 0;
  for (std::size_t p = 0; p < a.passes(); ++p) {
    const auto &ca = a.correction_samples(p).values, &cb = b.correction_samples(p).values;
    REQUIRE(ca.size() == cb.size());
    for (std::size_t k = 0; k < ca.size(); ++k) {
      const double to_end = (a.pass(p).t_end - a.correction_step(p) * k) * a.feed_speed();
      double& d = p == 0 ? first : to_end > reach ? inside : end;
      d = std::max(d, (ca[k] - cb[k]).norm());
    }
  }
  INFO("corrections apart by " << first * 1e3 << " um on the first pass; on the others "
                               << inside * 1e3 << " um away from the end, " << end * 1e3
                               << " um near it");
  CHECK(first > 1e-3);
  CHECK(end > 1e-3);
  CHECK(inside < 1e-12);
  // The first pass runs a step-over before the patch and leaves its nodes alone.
  CHECK(largest_difference(raster.raw, cl.raw) < 1e-12);
}

// The raster turned by 30 deg in plan on a plate: parallel passes 0.7 mm long, a step-over
// (0.06 mm) apart, zigzag, the middle one bending 0.2 mm sideways at its far end (their ends'
// imprints, steep walls where the Z-map's nearest node errs by the wall's slope times half a
// cell, stay off the patch). No pass along X or Y.
// `axis`: the tool axis at a point (x, y), written as the i, j, k columns; none: vertical.
using AxisAt = std::function<topomill::Vec3(double x, double y)>;

std::string turned_raster_file(const std::string& name, const AxisAt& axis = nullptr) {
  const std::string file = cl_dir() + "/" + name + ".csv";
  const double a = 30 * M_PI / 180, c = std::cos(a), s = std::sin(a);
  std::ofstream out(file);
  out << "# the raster turned by 30 deg about (0.01, 0)\n" << (axis ? "x,y,z,i,j,k\n" : "x,y,z\n");
  out.precision(17);
  auto point = [&](double x, double y) {
    out << x << "," << y << "," << 0.98;
    if (axis) out << "," << axis(x, y).x() << "," << axis(x, y).y() << "," << axis(x, y).z();
    out << "\n";
  };
  for (int k = -3; k <= 3; ++k) {
    const double d = k * 0.06, e = k % 2 == 0 ? 0.35 : -0.35;  // across, along
    // Each line written as five points (as CAM output writes long lines), where a 5-axis
    // axis turns from point to point along a straight pass.
    for (int q = -2; q <= 2; ++q) point(0.01 - d * s + q * e / 2 * c, d * c + q * e / 2 * s);
    if (k == 0) point(0.01 + e * c - 0.2 * s, e * s + 0.2 * c);
    out << "\n";
  }
  return file;
}

// A spiral about (0.3, 0) growing a step-over (0.06 mm) a turn, three turns: through a patch
// about the origin at radii 0.24, 0.30 and 0.36 mm, its chords turning by `step` deg.
template <class Point>
void spiral(Point point, int step) {
  for (int k = 0; k <= 3 * 360 / step; ++k) {
    const double th = k * step * M_PI / 180, r = 0.18 + 0.06 * th / (2 * M_PI);
    point(0.3 + r * std::cos(th + M_PI), r * std::sin(th + M_PI));
  }
}

TEST_CASE("the Z-map cuts CL passes in any direction where the brute force does", "[cl]") {
  // The brute force follows the same centre (ToolPath) with its own edge and crossings.
  const std::string file = turned_raster_file("turned");
  const double a = 30 * M_PI / 180, c = std::cos(a), s = std::sin(a);
  const std::string toml = scene(kPlate, cl_path(file), 0.004, 0.12, "centre = [0.01, 0.0]");
  const auto m = prepared(toml, {"evaluator.plugin=zmap"});
  REQUIRE(m.layout.path->feed_axis() == topomill::ToolPath::FeedAxis::None);
  const auto r = run_scene(toml, {"evaluator.plugin=zmap"});
  // Within about v / omega of a pass's axis line the edges' crossings are sparse (the tip's
  // marks): the surface there is jagged on a scale below the cell, and the Z-map, which gives a
  // node the lowest edge point within half a cell of it, reads it lower than it is (220 nm at a
  // node 0.18 um off a line at 40 deg, 152 nm at 3.9 um off one along X, both where the brute
  // force finds the crossings; near_axis_test.cpp holds tooth_passage to the brute force there).
  // Those nodes are left out: twice v / omega, 19 um, either side of each line.
  const double band = 2 * 6.0 / (2 * M_PI * 100);
  const auto near_a_line = [&](double x, double y) {
    const double across = -(x - 0.01) * s + y * c;
    return std::abs(across - 0.06 * std::round(across / 0.06)) < band;
  };
  const Against got = against_brute_force(m, r, near_a_line);
  INFO("largest difference from the brute force " << got.worst * 1e6 << " nm at " << got.where
                                                  << ", over " << got.nodes << " nodes");
  CHECK(got.nodes > 250);
  // The Z-map's own grid error at 4 um.
  CHECK(got.worst < 100e-6);
  // And the passes did cut: below the uncut plate (z = 0) by nearly the depth.
  CHECK(*std::max_element(r.raw.z.begin(), r.raw.z.end()) < -0.015);
}

TEST_CASE("a 5-axis raster written as CL points is that raster to the points' chord", "[cl]") {
  // The normal posture on the convex arc: the axis turns with the surface. Written as CL points
  // with their axes every 4 um of travel, the centre between points is the chord of the raster's
  // arc (sagging (4 um)^2 / 8 / 21 mm, 1e-10 mm) and the axis the normalised blend: the maps
  // agree to far below the Z-map's grid error (the two evaluate the same time steps only where
  // the passes' times agree). tooth_passage takes the two by different routes: the raster's
  // passes whole, their frame turning about X with the inclination; the CL passes a window per
  // pair of points, each frame the blend of the two axes (BlendFrame).
  const std::string evaluator = GENERATE(as<std::string>{}, "zmap", "tooth_passage");
  INFO(evaluator);
  const std::vector<std::string> set{"evaluator.plugin=" + evaluator};
  const std::string raster_scene =
      scene(kArc, "plugin = 'raster'\nposture = 'normal'\nlead = 10\ntilt = 5", 0.004, 0.06,
            "lambda = 30.0");
  const auto m = prepared(raster_scene, set);
  const topomill::ToolPath& path = *m.layout.path;
  const int points = static_cast<int>(std::ceil(path.pass(0).t_end * path.feed_speed() / 0.004));
  const std::string file = write_cl(path, points, true, false, "normal", true);
  const auto cl_m = prepared(scene(kArc, cl_path(file), 0.004, 0.06, "lambda = 30.0"), set);
  const double apart_limit = 1e-6;  // mm (0.16 nm seen: the chord and the blend)
  // The CL pass's axis between its points is the normalised blend of theirs; in the middle of a
  // segment it is within the turn's chord of the raster's.
  const topomill::ToolPath& cl = *cl_m.layout.path;
  REQUIRE(cl.passes() == path.passes());
  REQUIRE(cl.pass(1).posture.turns);
  for (double share : {0.25, 0.5, 0.75}) {
    const double t = share * cl.pass(1).t_end;
    CHECK((cl.axis(1, t) - testing::posture_axis(cl, 1, t)).norm() < 1e-14);
  }
  // posture_axis writes the blend again; at the points themselves the axis is the file's own
  // (written from the raster's axis at those times), whatever the blend.
  for (std::size_t k = 0; k < cl.pass(1).waypoints.size(); k += 7) {
    const double t = path.pass(1).t_end * static_cast<double>(k) / (points - 1);
    CHECK((cl.axis(1, cl.waypoint_time(1, k)) - path.axis(1, t)).norm() < 1e-12);
  }
  // The feed column keeps the raster's times (its feed is uniform in Y, not along the path).
  CHECK(cl.pass(1).t_end == Approx(path.pass(1).t_end).epsilon(1e-12));
  const auto a = run_scene(raster_scene, set);
  const auto b = run_scene(scene(kArc, cl_path(file), 0.004, 0.06, "lambda = 30.0"), set);
  const double apart = largest_difference(a.raw, b.raw);
  INFO("largest difference of the CL map from the raster's " << apart * 1e6 << " nm");
  CHECK(apart < apart_limit);
}

TEST_CASE("tooth_passage cuts bent CL passes as the brute force does, at every node",
          "[cl][bent]") {
  // Passes in any direction that turn at their points: the turned raster's bent middle pass
  // (a corner of 22 deg inside the patch's reach), a vertex of 90 deg right over the patch, and
  // a spiral of 5 deg chords (a radial-then-spiral path's kind). tooth_passage takes each
  // straight stretch as its own window; the brute force knows no windows: it follows the pass
  // (ToolPath) through its corners. Every node, those next to the lines included, to 1 nm.
  // Vertical, with a 4 um runout, tilted (a fixed axis 12 deg off vertical from the data's i, j,
  // k; on the turned raster only, the others having the next) and turning (an axis 4 to 17 deg
  // off vertical, leaning a different way at every point: 5-axis data), by both walks. (The
  // brute force takes 3 to 23 s a case: 80 s in all.)
  const std::string kind = GENERATE(as<std::string>{}, "turned", "vertex", "spiral");
  const std::string variant =
      GENERATE(as<std::string>{}, "vertical", "runout", "tilted", "turning");
  if (variant == "tilted" && kind != "turned") return;
  AxisAt axis;
  if (variant == "tilted")
    axis = [](double, double) { return topomill::Vec3(std::sin(0.21), 0, std::cos(0.21)); };
  if (variant == "turning")
    axis = [](double x, double y) {
      const double b = 0.15 + 0.15 * x, phi = 3 * y;
      return topomill::Vec3(std::sin(b) * std::cos(phi), std::sin(b) * std::sin(phi), std::cos(b));
    };
  std::string file;
  if (kind == "turned") {
    file = turned_raster_file("turned_" + variant, axis);
  } else {
    file = cl_dir() + "/" + kind + "_" + variant + ".csv";
    std::ofstream out(file);
    out.precision(17);
    out << (axis ? "x,y,z,i,j,k\n" : "x,y,z\n");
    auto point = [&](double x, double y) {
      out << x << "," << y << "," << 0.98;
      if (axis) out << "," << axis(x, y).x() << "," << axis(x, y).y() << "," << axis(x, y).z();
      out << "\n";
    };
    if (kind == "vertex") {
      // Two passes a step-over apart, each in along one diagonal and out along the other.
      for (double d : {0.0, 0.06}) {
        point(-0.4, -0.4 + d), point(0.0, d), point(0.4, -0.4 + d);
        out << "\n";
      }
    } else {
      spiral(point, 5);
    }
  }
  INFO(kind << ", " << variant);
  const std::string extra = variant == "runout" ? "\n[runout]\noffset = 0.004\nangle = 30\n" : "";
  const std::string toml = scene(kPlate, cl_path(file), 0.004, 0.06, "centre = [0.0, 0.0]") + extra;
  const auto m = prepared(toml);
  REQUIRE(m.layout.path->feed_axis() == topomill::ToolPath::FeedAxis::None);
  const topomill::Grid g = run_scene(toml).raw.grid;
  std::vector<double> brute(g.size());
  for (std::size_t j = 0; j < g.ny; ++j)
    for (std::size_t i = 0; i < g.nx; ++i)
      brute[g.index(i, j)] = testing::brute_force_height(*m.tool, *m.layout.path, g.x(i), g.y(j));
  // The passes did cut the patch: below the uncut plate (z = 0) by most of the depth.
  CHECK(*std::max_element(brute.begin(), brute.end()) < -0.01);
  for (const std::string walk : {"row", "node"}) {
    const auto r = run_scene(toml, {"evaluator.walk=" + walk});
    double worst = 0;
    std::size_t at = 0;
    for (std::size_t k = 0; k < brute.size(); ++k)
      if (std::abs(r.raw.z[k] - brute[k]) > worst) worst = std::abs(r.raw.z[k] - brute[k]), at = k;
    INFO("walk " << walk << ": largest difference from the brute force " << worst * 1e6
                 << " nm at node " << at << " of " << g.nx << " x " << g.ny);
    CHECK(worst < 1e-6);
  }
}

TEST_CASE("tooth_passage cuts bent CL passes with vibration and deflection as the brute force does",
          "[cl][bent]") {
  // The paper's tool and cut with its vibration and deflection (each pass's correction from the
  // force along the bent path), on two passes a step-over apart that turn by 90 deg over the
  // patch, vertical and with a 5-axis axis turning at every point; by both walks, to 1 nm at
  // every node. The corrected walk bounds passages by the floor of each window.
  const std::string variant = GENERATE(as<std::string>{}, "vertical", "turning");
  INFO(variant);
  const std::string file = cl_dir() + "/vertex_effects_" + variant + ".csv";
  {
    std::ofstream out(file);
    out.precision(17);
    const bool turning = variant == "turning";
    out << (turning ? "x,y,z,i,j,k\n" : "x,y,z\n");
    auto point = [&](double x, double y) {
      out << x << "," << y << "," << 4.9;
      const double b = 0.1 + 0.1 * x, phi = 2 * y;
      if (turning)
        out << "," << std::sin(b) * std::cos(phi) << "," << std::sin(b) * std::sin(phi) << ","
            << std::cos(b);
      out << "\n";
    };
    for (double d : {0.0, 0.3}) {
      point(-1.5, -1.5 + d), point(0.0, d), point(1.5, -1.5 + d);
      out << "\n";
    }
  }
  const std::string toml = scene(kPlate, cl_path(file), 0.01, 0.06, "centre = [0.0, 0.0]", true) +
                           testing::dynamics_tables();
  const auto m = prepared(toml);  // its tool; the run's path carries the corrections
  const auto first = run_scene(toml);
  REQUIRE(first.layout.path->corrected());
  REQUIRE(first.peak_correction > 1e-4);
  const topomill::Grid g = first.raw.grid;
  std::vector<double> brute(g.size());
  for (std::size_t j = 0; j < g.ny; ++j)
    for (std::size_t i = 0; i < g.nx; ++i)
      brute[g.index(i, j)] =
          testing::brute_force_height(*m.tool, *first.layout.path, g.x(i), g.y(j));
  for (const std::string walk : {"row", "node"}) {
    const auto r = run_scene(toml, {"evaluator.walk=" + walk});
    double worst = 0;
    for (std::size_t k = 0; k < brute.size(); ++k)
      worst = std::max(worst, std::abs(r.raw.z[k] - brute[k]));
    INFO("walk " << walk << ": largest difference from the brute force " << worst * 1e6 << " nm");
    CHECK(worst < 1e-6);
  }
}

TEST_CASE("on windows shorter than a revolution the corrected row walk is the node walk",
          "[cl][bent]") {
  // The paper's tool, cut and effects along a spiral of 1 deg chords (4 to 6 um: a fortieth of
  // a revolution): each window is crossed by a tooth once or not at all, and the corrected
  // walk's first passage often lies beyond the window's other end. The row walk must still give
  // the node walk's heights, to round-off.
  const std::string file = cl_dir() + "/fine_spiral.csv";
  {
    std::ofstream out(file);
    out.precision(17);
    out << "x,y,z\n";
    spiral([&](double x, double y) { out << x << "," << y << "," << 4.9 << "\n"; }, 1);
  }
  const std::string toml = scene(kPlate, cl_path(file), 0.005, 0.05, "centre = [0.0, 0.0]", true) +
                           testing::dynamics_tables();
  const auto row = run_scene(toml, {"evaluator.walk=row"});
  REQUIRE(row.peak_correction > 1e-4);
  const auto node = run_scene(toml, {"evaluator.walk=node"});
  const double apart = largest_difference(row.raw, node.raw);
  INFO("largest difference " << apart * 1e6 << " nm");
  CHECK(apart < 1e-9);
}

TEST_CASE("the shipped CL raster is configs/examples/plate.toml again, to the bit", "[cl]") {
  // configs/examples/cl/plate_raster.csv was written by `topomill run configs/examples/plate.toml
  // --set 'output.formats=["cl"]'`: read back it gives that scene's map. (A change to either
  // scene, or to how passes are laid out, shows here: rewrite the file as its header says.)
  std::string raw[2];
  int k = 0;
  for (const std::string scene : {"plate", "cl_plate_raster"}) {
    const std::string out = testing::temp_dir("cl_example_" + scene);
    const auto r = testing::run_topomill("run configs/examples/" + scene + ".toml -q --out '" +
                                         out + "' --set 'output.formats=[\"csv\"]'");
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    std::istringstream in(testing::read_file(out + "/height_raw.csv"));
    for (std::string line; std::getline(in, line);)
      if (!line.empty() && line[0] != '#') raw[k] += line + "\n";
    ++k;
  }
  REQUIRE(raw[0].size() > 1000);
  CHECK(raw[0] == raw[1]);
}

TEST_CASE("a patch placed by its centre is the patch there (translation)", "[cl][path]") {
  // On a plate the raster's passes lie every step-over along X: the patch centred a step-over
  // along is the same surface at the same nodes relative to the passes. On the arc, centred
  // over y = r sin(30 deg) it is the patch at lambda = 30 deg.
  const std::string raster = "plugin = 'raster'";
  const auto a = run_scene(scene(kPlate, raster, 0.004, 0.1));
  const auto b = run_scene(scene(kPlate, raster, 0.004, 0.1, "centre = [0.06, 0.0]"));
  CHECK(b.raw.grid.x0 == Approx(a.raw.grid.x0 + 0.06).margin(1e-15));
  CHECK(largest_difference(a.raw, b.raw) < 1e-12);
  const auto c = run_scene(scene(kArc, raster, 0.004, 0.06, "lambda = 30.0"));
  const auto d = run_scene(scene(kArc, raster, 0.004, 0.06, "centre = [0.0, 10.0]"));
  CHECK(d.raw.grid.y0 == Approx(c.raw.grid.y0).margin(1e-12));
  CHECK(largest_difference(c.raw, d.raw) < 1e-12);
  // Elsewhere it differs (the test can fail): a third of a step-over along X.
  const auto e = run_scene(scene(kPlate, raster, 0.004, 0.1, "centre = [0.02, 0.0]"));
  CHECK(largest_difference(a.raw, e.raw) > 1e-4);
}

TEST_CASE("tooth_passage follows the raster over an inclined plane written as CL data", "[cl]") {
  // On a plane at 10 deg each pass's centre climbs along a straight line: still one line along
  // Y in plan, which tooth_passage follows. The CL pass's speed is along that line (the file
  // gives it: f, the chord over the raster's time), so the times and centres are the raster's
  // to round-off, and so is the map.
  const std::string plane = "plugin = 'inclined_plane'\nangle = 10.0";
  const std::string raster_scene = scene(plane, "plugin = 'zigzag'", 0.004, 0.1, "lambda = 10.0");
  const auto m = prepared(raster_scene);
  const std::string file = write_cl(*m.layout.path, 2, false, false, "plane", true);
  const std::string cl_scene = scene(plane, cl_path(file), 0.004, 0.1, "lambda = 10.0");
  REQUIRE(prepared(cl_scene).layout.path->feed_axis() == topomill::ToolPath::FeedAxis::Y);
  const auto a = run_scene(raster_scene);
  const auto b = run_scene(cl_scene);
  const double apart = largest_difference(a.raw, b.raw);
  INFO("largest difference " << apart * 1e6 << " nm");
  CHECK(apart < 1e-9);
}
