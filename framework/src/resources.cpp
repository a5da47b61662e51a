#include "resources.hpp"

#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <sstream>

#include "topomill/cut_state.hpp"

namespace topomill {

namespace {

// Height maps per node the core holds at its peak (raw map, residual, the roughness pass and the
// writers' buffers), in bytes.
constexpr std::uint64_t kCoreBytesPerNode = 40;
// One sample of the force/dynamics time grid: its cut state (with the material test's closure on
// the heap), its force, the dynamics' input and output, the correction, and an evaluator's index
// of it (tooth_passage's range tables hold 40 bytes a sample).
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
  return static_cast<std::uint64_t>(v * scale);
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

MemoryEstimate estimate_memory(const Prepared& m, unsigned threads) {
  MemoryEstimate e;
  const Grid& g = m.layout.grid;
  const EvaluationRequest rq = evaluation_request(m, threads);
  const double nodes = static_cast<double>(g.nx) * static_cast<double>(g.ny);
  const double grid =
      nodes * kCoreBytesPerNode + static_cast<double>(m.evaluator->extra_memory(rq, g));
  const double effects = static_cast<double>(effect_samples(m)) * kBytesPerSample;
  constexpr double cap = 1e19;  // keeps absurd scenes (1e12 nodes) from overflowing
  e.grid_bytes = static_cast<std::uint64_t>(std::min(grid, cap));
  e.effect_bytes = static_cast<std::uint64_t>(std::min(effects, cap));
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

void check_memory(const Scene& scene, const Prepared& m, unsigned threads,
                  std::uint64_t available) {
  const MemoryEstimate e = estimate_memory(m, threads);
  // Leave a tenth for the program, the libraries and the allocator.
  if (static_cast<double>(e.total()) <= 0.9 * static_cast<double>(available)) return;
  const Grid& g = m.layout.grid;
  std::ostringstream os;
  os << "the run would need about " << format_bytes(static_cast<double>(e.total())) << " (" << g.nx
     << " x " << g.ny << " nodes: " << format_bytes(static_cast<double>(e.grid_bytes)) << "; "
     << effect_samples(m)
     << " force/dynamics samples: " << format_bytes(static_cast<double>(e.effect_bytes))
     << "), and " << format_bytes(static_cast<double>(available)) << " are available: ";
  if (e.grid_bytes >= e.effect_bytes) {
    os << "raise region.spacing (memory grows as 1/spacing^2) or shrink region.size";
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

}  // namespace topomill
