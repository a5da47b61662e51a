#include "pipeline.hpp"

#include <chrono>
#include <cmath>

#include "form_removal.hpp"
#include "log.hpp"
#include "topomill/surface_shape.hpp"
#include "topomill/tool_geometry.hpp"

namespace topomill {

namespace {

class StageClock {
 public:
  explicit StageClock(std::vector<StageTime>& out) : out_(out) {}
  template <class F>
  auto run(const std::string& name, F&& f) {
    const auto t0 = std::chrono::steady_clock::now();
    struct Record {
      std::vector<StageTime>& out;
      std::string name;
      std::chrono::steady_clock::time_point t0;
      ~Record() {
        out.push_back(
            {name, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count()});
        log_debug("stage '" + name + "': " + std::to_string(out.back().seconds) + " s");
      }
    } record{out_, name, t0};
    return f();
  }

 private:
  std::vector<StageTime>& out_;
};

void require_finite(const HeightMap& map, const std::string& what) {
  for (std::size_t j = 0; j < map.grid.ny; ++j)
    for (std::size_t i = 0; i < map.grid.nx; ++i)
      if (!std::isfinite(map.at(i, j)))
        throw std::runtime_error(what + " has a non-finite height at node (" + std::to_string(i) +
                                 ", " + std::to_string(j) + "); nothing was written");
}

}  // namespace

Prepared prepare(const Scene& scene, const PluginCatalog& catalog) {
  Prepared out;
  const auto& t = scene.slot("tool");
  const auto& w = scene.slot("workpiece");
  const auto& e = scene.slot("evaluator");
  out.tool = catalog.create<ToolGeometry>(*t.model, t.params);
  out.surface = catalog.create<SurfaceShape>(*w.model, w.params);
  out.evaluator = catalog.create<TopographyEvaluator>(*e.model, e.params);
  for (const auto* st : {&t, &w, &e})
    log_info(st->table + ": " + st->plugin + " from " + st->model->library->path);
  out.layout = make_layout(scene, *out.tool, out.surface);
  return out;
}

RunResult run_pipeline(const Scene& scene, const PluginCatalog& catalog,
                       const RunOptions& options) {
  RunResult result;
  StageClock clock(result.stages);

  Prepared m = clock.run("setup", [&] { return prepare(scene, catalog); });
  result.layout = m.layout;
  const Layout& L = result.layout;
  log_info("grid " + std::to_string(L.grid.nx) + " x " + std::to_string(L.grid.ny) + " nodes, " +
           std::to_string(L.path->passes()) + " passes");

  result.raw = clock.run("evaluate", [&] {
    HeightMap map(L.grid);
    for (std::size_t j = 0; j < L.grid.ny; ++j) {
      const double v = m.surface->height(L.grid.y(j));
      for (std::size_t i = 0; i < L.grid.nx; ++i) map.at(i, j) = v;
    }
    EvaluationRequest rq;
    rq.tool = m.tool.get();
    rq.path = L.path.get();
    rq.kappa = L.kappa;
    rq.lambda_max = L.lambda_max;
    rq.threads = options.threads;
    if (options.progress) rq.progress = [&](double f) { options.progress("evaluate", f); };
    m.evaluator->evaluate(rq, map, result.work);
    return map;
  });
  require_finite(result.raw, "the evaluator's height map");

  const std::string form = scene.table("analysis").string("form");
  result.residual = clock.run("form_removal", [&] {
    if (form == "none") return result.raw;
    const double ap = scene.table("cutting").number("depth_of_cut");
    return unroll_residual(result.raw, *m.surface, ap, L.s_lo, L.s_hi, L.spacing);
  });
  require_finite(result.residual, "the residual height map");

  result.roughness = clock.run("parameters", [&] { return roughness(result.residual); });
  return result;
}

}  // namespace topomill
