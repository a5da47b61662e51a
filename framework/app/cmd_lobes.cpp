// topomill lobes: the stability lobes of a scene's cutter, force law, immersion and modes by
// semi-discretisation (framework/src/stability/, docs/stability.md).
#include <cmath>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli.hpp"
#include "commands.hpp"
#include "io/png_lobes.hpp"
#include "log.hpp"
#include "run/pipeline.hpp"
#include "scene_options.hpp"
#include "stability/lobes.hpp"

namespace topomill::cli {

namespace {

constexpr int kDefaultSpeeds = 200;
constexpr int kMaxSpeeds = 100000;
constexpr int kMaxSteps = 2000;
constexpr double kMaxDepth = 1000;  // mm: a bound on the edge elements a trial builds

struct SpeedRange {
  double from, to;
  int count;
};

SpeedRange parse_speeds(const std::string& text) {
  auto refuse = [&] {
    return InputError(SourceRef{"command line"}, "--spindle",
                      "'" + text + "': expected FROM:TO[:N] in rpm, 0 < FROM < TO, 2 <= N <= " +
                          std::to_string(kMaxSpeeds) + " (e.g. 5000:25000:200)");
  };
  std::vector<std::string> parts;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ':');) parts.push_back(item);
  if (parts.size() < 2 || parts.size() > 3) throw refuse();
  auto number = [&](const std::string& s) {
    std::size_t used = 0;
    double v = NAN;
    try {
      v = std::stod(s, &used);
    } catch (const std::exception&) {
      throw refuse();
    }
    if (used != s.size() || !std::isfinite(v)) throw refuse();
    return v;
  };
  SpeedRange r{number(parts[0]), number(parts[1]), kDefaultSpeeds};
  if (parts.size() == 3) {
    const double n = number(parts[2]);
    if (n != std::floor(n) || n < 2 || n > kMaxSpeeds) throw refuse();
    r.count = static_cast<int>(n);
  }
  if (!(r.from > 0) || !(r.to > r.from)) throw refuse();
  return r;
}

// The scene's steady engagement: its first pass's feed, the next pass's side, the stepover.
stability::Engagement engagement(const Scene& scene, const ToolPath& path) {
  const ToolPath::Pass& p0 = path.pass(0);
  stability::Engagement e{std::atan2(p0.dy, p0.dx), 1, scene.table("cutting").number("stepover"),
                          0.0};
  if (path.passes() > 1) {
    const ToolPath::Pass& p1 = path.pass(1);
    const double ox = p1.x - p0.x, oy = p1.y_start - p0.y_start;
    e.side = -p0.dy * ox + p0.dx * oy >= 0 ? 1 : -1;
  }
  return e;
}

// What the analysis reads of the scene's models, refused (naming the table) where they give none.
stability::LobeSetup lobe_setup(const Scene& scene, const Prepared& m, int steps,
                                double depth_max) {
  if (!m.dynamics || m.dynamics->modes().empty())
    throw InputError(scene.slot("vibration").where, "vibration",
                     "lobes needs the structure's modes: expected an enabled [vibration] table "
                     "with a modal model (modal_exact, modal_rk4)");
  const ChipCoefficients k = m.force->chip_coefficients();
  if (!std::isfinite(k.tangential) || !std::isfinite(k.radial) || !std::isfinite(k.axial))
    throw InputError(scene.slot("force").where, "force.plugin",
                     "lobes needs a force law proportional to the chip (armarego)");
  stability::LobeSetup s;
  s.tool = m.tool.get();
  s.engagement = engagement(scene, *m.layout.path);
  s.sense = m.layout.path->spindle_rate() >= 0 ? 1 : -1;
  s.k = k;
  s.modes = m.dynamics->modes();
  s.steps = steps;
  s.depth_max = depth_max;
  return s;
}

// --depth-max, --steps and --png, before any work.
void check_options(double depth_max, int steps, const std::string& png) {
  if (!(depth_max > 0) || !(depth_max <= kMaxDepth))
    throw InputError(SourceRef{"command line"}, "--depth-max",
                     "expected a positive depth in mm, at most 1000 (e.g. 50)");
  if (steps != 0 && (steps < 4 || steps > kMaxSteps))
    throw InputError(
        SourceRef{"command line"}, "--steps",
        "expected 0 (automatic) or 4 to " + std::to_string(kMaxSteps) + " steps per tooth period");
  if (!png.empty()) {
    const std::filesystem::path dir = std::filesystem::path(png).parent_path();
    if (!std::filesystem::is_directory(dir.empty() ? "." : dir))
      throw InputError(SourceRef{"command line"}, "--png",
                       "'" + png + "': expected a file in an existing directory");
  }
}

nlohmann::json finite_or_null(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nullptr;
}

}  // namespace

int cmd_lobes(const Args& args) {
  SceneOptions so;
  std::string speeds = "";
  double depth_max = 50;
  int steps = 0;
  bool json = false;
  std::string png;
  po::options_description opts(
      "topomill lobes SCENE --spindle FROM:TO[:N] [--depth-max MM] [--steps M] [--json]: the\n"
      "stability lobes of the scene's cutter, force law, stepover and modes (its [vibration]\n"
      "table), by semi-discretisation: the critical axial depth at N spindle speeds, and whether\n"
      "the cut turns unstable by a flip (period doubling) or a Hopf bifurcation");
  opts.add_options()("spindle", po::value(&speeds), "FROM:TO[:N] rpm (N: 200)")(
      "depth-max", po::value(&depth_max)->default_value(50.0),
      "the deepest axial depth looked at (mm)")(
      "steps", po::value(&steps)->default_value(0),
      "semi-discretisation steps per tooth period (0: at least 40, and 30 per cycle of the "
      "fastest mode)")("json", po::bool_switch(&json), "print JSON instead of a table")(
      "png", po::value(&png), "also draw the lobes, the scene's operating point marked, here");
  add_scene_options(opts, so);
  LoadedScene loaded = load_scene(args, opts, so, /*check_unused=*/false);
  if (!loaded.scene) {
    std::cout << opts << "\n";
    return 0;
  }
  if (speeds.empty())
    throw InputError(SourceRef{"command line"}, "--spindle",
                     "missing: expected FROM:TO[:N] in rpm (e.g. 5000:25000:200)");
  const SpeedRange range = parse_speeds(speeds);
  check_options(depth_max, steps, png);
  const Scene& scene = *loaded.scene;
  const Prepared m = prepare(scene, *loaded.catalog);
  const stability::LobeSetup s = lobe_setup(scene, m, steps, depth_max);
  const double slowest = stability::slowest_speed(s);
  if (range.from < slowest)
    throw InputError(SourceRef{"command line"}, "--spindle",
                     "'" + speeds + "': expected FROM of at least " + std::to_string(slowest) +
                         " rpm: slower, a tooth period holds more cycles of the fastest mode "
                         "than 2000 steps resolve");
  const double rpm0 = scene.table("cutting").number("spindle_speed");
  const double ap0 = scene.table("cutting").number("depth_of_cut");
  // The scene's own speed, where the steps resolve it (else its stability is not known: null).
  const bool resolved = rpm0 >= slowest;
  const stability::Multiplier at =
      resolved ? stability::multiplier_at(s, rpm0, ap0) : stability::Multiplier{NAN};
  nlohmann::json out;
  out["spindle_rpm"] = nlohmann::json::array();
  out["depth_mm"] = nlohmann::json::array();
  out["onset"] = nlohmann::json::array();
  out["steps_per_period"] = nlohmann::json::array();
  LobeCurve curve;
  curve.depth_max = depth_max;
  if (!json) std::cout << "spindle_rpm\tdepth_mm\tonset\n";
  for (int i = 0; i < range.count; ++i) {
    const double rpm = range.from + (range.to - range.from) * i / (range.count - 1);
    const stability::LobePoint p = stability::critical_depth(s, rpm);
    out["spindle_rpm"].push_back(rpm);
    out["depth_mm"].push_back(finite_or_null(p.depth));
    out["onset"].push_back(stability::onset_name(p.onset));
    out["steps_per_period"].push_back(stability::steps_at(s, rpm));
    curve.rpm.push_back(rpm), curve.depth.push_back(p.depth);
    curve.flip.push_back(p.onset == stability::Onset::kFlip);
    if (!json)
      std::cout << rpm << "\t" << (std::isfinite(p.depth) ? std::to_string(p.depth) : "-") << "\t"
                << stability::onset_name(p.onset) << "\n";
  }
  out["operating_point"] = {{"spindle_rpm", rpm0},
                            {"depth_mm", ap0},
                            {"multiplier", at.modulus()},
                            {"stable", resolved ? nlohmann::json(at.modulus() < 1) : nullptr}};
  out["depth_max_mm"] = depth_max;
  if (!png.empty()) {
    curve.operating_rpm = rpm0, curve.operating_depth = ap0,
    curve.operating_stable = resolved && at.modulus() < 1;
    curve.title = "Stability lobes: " + scene.table("scene").string("name");
    try {
      write_lobes_chart(png, curve);
    } catch (const std::exception& e) {
      throw InputError(SourceRef{"command line"}, "--png", e.what());
    }
  }
  if (json) std::cout << out.dump(2) << "\n";
  if (resolved)
    log_info(std::string("operating point ") + (at.modulus() < 1 ? "stable" : "unstable") +
             " (largest multiplier " + std::to_string(at.modulus()) + ")");
  else
    log_info("operating point below " + std::to_string(slowest) + " rpm: not analysed");
  return 0;
}

}  // namespace topomill::cli
