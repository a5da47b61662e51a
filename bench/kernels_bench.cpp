// Google Benchmark micro-benchmarks of the hot kernels: the edge transform, the fast evaluator's
// per-node solve and the Z-map's per-time-step sweep, one force evaluation, and a dynamics step.
// Built with -DTOPOMILL_BUILD_BENCH=ON; scripts/bench runs them (docs/performance.md).
#include <benchmark/benchmark.h>

#include <cmath>

#include "log.hpp"
#include "plugin_catalog.hpp"
#include "run/pipeline.hpp"
#include "scene.hpp"

namespace {

// The paper's lambda = 30 deg scene with the given overrides, prepared (models, grid, path).
struct Prepared {
  topomill::PluginCatalog catalog{{{topomill::PluginCatalog::builtin_dir(), "built-in"}}};
  std::optional<topomill::Scene> scene;
  topomill::Prepared m;
  explicit Prepared(const std::vector<std::string>& overrides) {
    auto doc = topomill::SceneDocument::parse_file(std::string(TOPOMILL_SOURCE_DIR) +
                                                   "/configs/paper/lambda30_fz01_dynamics.toml");
    for (const auto& o : overrides) doc.apply_override(o);
    scene = doc.resolve(catalog);
    m = topomill::prepare(*scene, catalog);
  }
  topomill::EvaluationRequest request() const { return topomill::evaluation_request(m, 1); }
};

void BM_EdgePoint(benchmark::State& state) {
  const Prepared p({});
  double alpha = 0.1, spindle = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(p.m.tool->edge_point(1, alpha, spindle));
    alpha = alpha > 1.5 ? 0.1 : alpha + 1e-3;
    spindle += 0.01;
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_EdgePoint);

// Per node: the 0.86 mm patch at the spacing given (um), one thread, ideal kinematics.
void BM_ToothPassageNodes(benchmark::State& state) {
  const double spacing = static_cast<double>(state.range(0)) * 1e-3;
  const Prepared p({"evaluator.plugin=\"tooth_passage\"", "vibration.enabled=false",
                    "deflection.enabled=false", "region.spacing=" + std::to_string(spacing)});
  const auto rq = p.request();
  const topomill::Grid& g = p.m.layout.grid;
  for (auto _ : state) {
    topomill::HeightMap map(g, 1e9);
    topomill::WorkCounts counts;
    p.m.evaluator->evaluate(rq, map, counts);
    benchmark::DoNotOptimize(map.z.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(g.size()));
  state.counters["nodes"] = static_cast<double>(g.size());
}
BENCHMARK(BM_ToothPassageNodes)->Arg(20)->Arg(10)->Unit(benchmark::kMillisecond);

// Per time step of the reference Z-map: a 0.1 mm patch at 20 um (its cost is in the time steps).
void BM_ZMapSteps(benchmark::State& state) {
  const Prepared p({"evaluator.plugin=\"zmap\"", "vibration.enabled=false",
                    "deflection.enabled=false", "region.size=[0.1, 0.1]", "region.spacing=0.02"});
  const auto rq = p.request();
  std::uint64_t steps = 0;
  for (auto _ : state) {
    topomill::HeightMap map(p.m.layout.grid, 1e9);
    topomill::WorkCounts counts;
    p.m.evaluator->evaluate(rq, map, counts);
    steps += counts["time_steps"];
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(steps));
}
BENCHMARK(BM_ZMapSteps)->Unit(benchmark::kMillisecond);

// One Armarego force evaluation at the paper's conditions, mid-cut.
void BM_ArmaregoForce(benchmark::State& state) {
  const Prepared p({});
  topomill::CutState st;
  st.feed_per_tooth = 0.1;
  st.inclination = M_PI / 6;
  st.alpha_min = 0.3, st.alpha_max = 0.75;
  st.spindle_rate = 4000 * 2 * M_PI / 60;
  st.depth_of_cut = 0.3, st.stepover = 0.3;
  st.in_material = [](const topomill::Vec3& o) { return o.z() < -4.7; };
  for (auto _ : state) {
    benchmark::DoNotOptimize(p.m.force->evaluate(*p.m.tool, st));
    st.spindle_angle += 0.05;
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_ArmaregoForce);

// The modal response per time step (Table 4's six modes), RK4 against the exact solution.
void BM_DynamicsStep(benchmark::State& state, const char* model) {
  const Prepared p({std::string("vibration.plugin=\"") + model + "\""});
  const double dt = p.m.dynamics->suggested_step();
  std::vector<topomill::Vec3> force(4096);
  for (std::size_t k = 0; k < force.size(); ++k)
    force[k] = topomill::Vec3(100 * std::sin(0.01 * k), 50 * std::cos(0.013 * k), -20);
  for (auto _ : state) benchmark::DoNotOptimize(p.m.dynamics->respond(force, dt));
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(force.size()));
}
BENCHMARK_CAPTURE(BM_DynamicsStep, modal_rk4, "modal_rk4");
BENCHMARK_CAPTURE(BM_DynamicsStep, modal_exact, "modal_exact");

}  // namespace

int main(int argc, char** argv) {
  topomill::set_log_level(topomill::LogLevel::Quiet);  // one model log line per setup otherwise
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
