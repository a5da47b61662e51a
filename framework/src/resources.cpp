#include "resources.hpp"

#include <sched.h>
#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <sstream>
#include <thread>

#include "log.hpp"
#include "metrology/parameters.hpp"
#include "topomill/cut_state.hpp"

namespace topomill {

namespace {

// Height maps per node the core holds at its peak (raw map, residual, the roughness pass and the
// writers' buffers), in bytes.
constexpr std::uint64_t kCoreBytesPerNode = 40;
// One sample of the force/dynamics time grid: its cut state (with the material test's closure on
// the heap), its force, the dynamics' input and output, the correction, and an evaluator's index
// of it (tooth_passage's range table and path-length sums hold 48 bytes a sample).
constexpr std::uint64_t kBytesPerSample =
    sizeof(CutState) + sizeof(CuttingForce) + 3 * sizeof(Vec3) + 128 + 64;

std::uint64_t parse_bytes(const std::string& text) {
  std::size_t end = 0;
  const double v = std::stod(text, &end);
  double scale = 1;
  const std::string suffix = text.substr(end);
  if (suffix == "K" || suffix == "k")
    scale = 1024.0;
  else if (suffix == "M")
    scale = 1024.0 * 1024;
  else if (suffix == "G")
    scale = 1024.0 * 1024 * 1024;
  else if (!suffix.empty())
    throw std::invalid_argument(suffix);
  if (!(v > 0)) throw std::invalid_argument(text);
  // Beyond what 64 bits count (1e99 used to wrap around to 0 bytes): no limit at all.
  const double bytes = v * scale;
  return bytes < 1.8e19 ? static_cast<std::uint64_t>(bytes)
                        : std::numeric_limits<std::uint64_t>::max();
}

// Where a "table.key" of the scene was set (a core table's or a model's), for messages.
SourceRef where_of(const Scene& scene, const std::string& key) {
  const auto dot = key.find('.');
  const std::string table = key.substr(0, dot), name = key.substr(dot + 1);
  if (scene.core.count(table)) return scene.table(table).where(name);
  if (scene.slots.count(table)) return scene.slot(table).params.where(name);
  return SourceRef{scene.file};
}

}  // namespace

std::uint64_t available_memory() {
  if (const char* env = std::getenv("TOPOMILL_MEMORY_LIMIT")) {
    try {
      return parse_bytes(env);
    } catch (const std::exception&) {
      throw InputError(SourceRef{"environment"}, "TOPOMILL_MEMORY_LIMIT",
                       std::string("'") + env +
                           "' is not a positive byte count (examples: 500000000, 800M, 2G)");
    }
  }
  std::uint64_t avail = std::numeric_limits<std::uint64_t>::max();
  std::ifstream meminfo("/proc/meminfo");
  std::string key;
  std::uint64_t kib = 0;
  std::string unit;
  while (meminfo >> key >> kib >> unit)
    if (key == "MemAvailable:") avail = kib * 1024;
  for (int resource : {RLIMIT_AS, RLIMIT_DATA}) {
    rlimit lim{};
    if (getrlimit(resource, &lim) == 0 && lim.rlim_cur != RLIM_INFINITY)
      avail = std::min<std::uint64_t>(avail, lim.rlim_cur);
  }
  return avail;
}

namespace {
// What a node costs after the evaluation, on one thread (measured on quick.toml at a 0.3 um
// spacing, 1001 x 995 nodes, `--set 'output.formats=["F"]'`, summary.json's timing_s): form
// removal, and writing each format's two maps.
constexpr double kFormSecondsPerNode = 0.07e-6;
double format_seconds_per_node(const std::string& format) {
  if (format == "x3p") return 6.4e-6;  // deflate over float64s
  if (format == "vts") return 4.7e-6;  // ASCII
  if (format == "png") return 0.5e-6;
  if (format == "csv") return 0.43e-6;
  if (format == "gsf") return 0.08e-6;
  if (format == "sdf") return 0.04e-6;
  return 0.0;  // cl: the passes, not the grid
}
}  // namespace

unsigned usable_cores() {
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof set, &set) == 0 && CPU_COUNT(&set) > 0)
    return static_cast<unsigned>(CPU_COUNT(&set));
  return std::max(1u, std::thread::hardware_concurrency());
}

double effect_time_step(const Prepared& m) {
  const ToolPath& path = *m.layout.path;
  const double tooth_period = 2 * M_PI / std::abs(path.spindle_rate()) / m.tool->teeth();
  double dt = tooth_period / 64;  // resolves the force's variation over a tooth passage
  if (m.dynamics) dt = std::min(dt, m.dynamics->suggested_step());
  return dt;
}

std::uint64_t effect_samples(const Prepared& m) {
  if (!m.force) return 0;
  const double dt = effect_time_step(m);
  const ToolPath& path = *m.layout.path;
  double samples = 0;
  for (std::size_t p = 0; p < path.passes(); ++p) samples += std::ceil(path.pass(p).t_end / dt) + 1;
  return samples > 1e18 ? std::numeric_limits<std::uint64_t>::max()
                        : static_cast<std::uint64_t>(samples);
}

EvaluationCost evaluation_cost(const Prepared& m, unsigned threads) {
  return m.evaluator->estimate_cost(evaluation_request(m, threads), m.layout.grid);
}

MemoryEstimate estimate_memory(const Prepared& m, const EvaluationCost& cost) {
  MemoryEstimate e;
  const Grid& g = m.layout.grid;
  const double nodes = static_cast<double>(g.nx) * static_cast<double>(g.ny);
  const double effects = static_cast<double>(effect_samples(m)) * kBytesPerSample;
  // Capped (and NaN taken as the cap) so that absurd scenes (1e12 nodes) do not overflow.
  auto bytes = [](double b) {
    constexpr double cap = 1e18;
    return static_cast<std::uint64_t>(b < cap ? std::max(b, 0.0) : cap);
  };
  e.grid_bytes = bytes(nodes * kCoreBytesPerNode);
  // The parameters' stage, on the residual (about the grid's size) while the maps are held.
  e.analysis_bytes = bytes(nodes * parameter_bytes_per_point(m.parameter_names));
  e.evaluator_bytes = bytes(cost.bytes);
  e.evaluator_key = cost.bytes_key;
  e.effect_bytes = bytes(effects);
  return e;
}

std::string format_bytes(double bytes) {
  std::ostringstream os;
  os.precision(3);
  if (bytes >= 1024.0 * 1024 * 1024)
    os << bytes / (1024.0 * 1024 * 1024) << " GiB";
  else
    os << bytes / (1024.0 * 1024) << " MiB";
  return os.str();
}

void check_memory(const Scene& scene, const Prepared& m, const EvaluationCost& cost,
                  unsigned threads, std::uint64_t available) {
  const MemoryEstimate e = estimate_memory(m, cost);
  // Leave a tenth for the program, the libraries and the allocator.
  if (static_cast<double>(e.total()) <= 0.9 * static_cast<double>(available)) return;
  const Grid& g = m.layout.grid;
  const std::string evaluator = scene.slot("evaluator").plugin;
  std::ostringstream os;
  os << "the run would need about " << format_bytes(static_cast<double>(e.total())) << " (" << g.nx
     << " x " << g.ny << " nodes: " << format_bytes(static_cast<double>(e.grid_bytes)) << "; "
     << evaluator << "'s own: " << format_bytes(static_cast<double>(e.evaluator_bytes)) << "; "
     << effect_samples(m)
     << " force/dynamics samples: " << format_bytes(static_cast<double>(e.effect_bytes))
     << "; analysis.parameters: " << format_bytes(static_cast<double>(e.analysis_bytes))
     << "), and " << format_bytes(static_cast<double>(available)) << " are available: ";
  // The largest part names the key to turn.
  if (e.evaluator_bytes > e.grid_bytes && e.evaluator_bytes >= e.effect_bytes &&
      !e.evaluator_key.empty() && e.evaluator_key != "region.spacing") {
    os << "raise " << e.evaluator_key << " (what " << evaluator
       << "'s memory grows with) or shrink region.size";
    throw InputError(where_of(scene, e.evaluator_key), e.evaluator_key, os.str());
  }
  if (e.grid_bytes + e.evaluator_bytes + e.analysis_bytes >= e.effect_bytes) {
    os << "raise region.spacing (memory grows as 1/spacing^2) or shrink region.size";
    if (e.analysis_bytes > e.grid_bytes)
      os << ", or choose fewer analysis.parameters (Sal and Str take the most)";
    if (threads > 1) os << ", or use fewer --threads";
    const Params& region = scene.table("region");
    throw InputError(region.where("spacing"), "region.spacing", os.str());
  }
  if (m.dynamics) {
    os << "the fastest vibration mode sets the time step (" << effect_time_step(m)
       << " s); remove or soften it, or shrink region.size (fewer and shorter passes)";
    throw InputError(scene.slot("vibration").where, "vibration", os.str());
  }
  os << "shrink region.size (fewer and shorter passes) or raise cutting.feed_per_tooth (the force "
        "is sampled 64 times per tooth passage)";
  throw InputError(scene.table("region").where("size"), "region.size", os.str());
}

double finishing_seconds(const Scene& scene, const Prepared& m) {
  const Grid& g = m.layout.grid;
  const double nodes = static_cast<double>(g.nx) * static_cast<double>(g.ny);
  double per_node = kFormSecondsPerNode + parameter_seconds_per_point(m.parameter_names);
  for (const auto& format : scene.table("output").strings("formats"))
    per_node += format_seconds_per_node(format);
  return nodes * per_node;
}

void check_duration(const Scene& scene, const Prepared& m, const EvaluationCost& cost,
                    unsigned threads) {
  // Threads beyond the cores share them: 256 threads on 2 cores run as fast as 2. What follows
  // the evaluation (form removal, parameters, writing) runs on one.
  threads = std::clamp(threads, 1u, usable_cores());
  const double finishing = finishing_seconds(scene, m);
  const double seconds = cost.seconds / threads + finishing;
  if (!(seconds > 60)) return;
  const std::string evaluator = scene.slot("evaluator").plugin;
  std::ostringstream os;
  os.precision(2);
  if (seconds < 3600)
    os << seconds / 60 << " min";
  else if (seconds < 86400 * 3)
    os << seconds / 3600 << " h";
  else
    os << seconds / 86400 << " days";
  // The larger share names what drives it.
  const bool evaluation = cost.seconds / threads >= finishing && !cost.seconds_key.empty();
  const std::string driver =
      evaluation ? cost.seconds_key
                 : "region.spacing (the grid's form removal, analysis.parameters and "
                   "output.formats: x3p and vts take the longest)";
  const std::string what = (evaluation ? evaluator : std::string("topomill")) +
                           " estimates this run at about " + os.str() + " on " +
                           std::to_string(threads) + " thread(s), driven by " + driver;
  if (seconds > 1e8 || !std::isfinite(seconds)) {
    const std::string key = driver.substr(0, driver.find(' '));
    throw InputError(where_of(scene, key), key,
                     what + ": expected a run that ends within three years");
  }
  log_warning(what + " (an estimate, within a factor of a few)");
}

}  // namespace topomill
