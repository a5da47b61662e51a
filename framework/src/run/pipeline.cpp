#include "run/pipeline.hpp"

#include <chrono>
#include <cmath>
#include <memory>

#include "code_fingerprint.hpp"
#include "interrupt.hpp"
#include "log.hpp"
#include "metrology/form_removal.hpp"
#include "resources.hpp"
#include "run/effects_stage.hpp"
#include "run/in_table.hpp"
#include "topomill/input_files.hpp"
#include "topomill/surface_shape.hpp"
#include "topomill/tool_geometry.hpp"

namespace topomill {

namespace {

void require_finite(const HeightMap& map, const std::string& what) {
  for (std::size_t j = 0; j < map.grid.ny; ++j)
    for (std::size_t i = 0; i < map.grid.nx; ++i)
      if (!std::isfinite(map.at(i, j)))
        throw std::runtime_error(what + " has a non-finite height at node (" + std::to_string(i) +
                                 ", " + std::to_string(j) + "); nothing was written");
}

// The model a scene table selects, constructed; the log names the library it came from.
template <class T>
std::shared_ptr<T> make(const Scene& scene, const PluginCatalog& catalog,
                        const std::string& table) {
  const SlotTable& st = scene.slot(table);
  log_info(table + ": " + st.plugin + " from " + st.model->library->path);
  return catalog.create<T>(*st.model, st.params);
}

// Each pass's posture, refused where the evaluator does not follow it, or not with this cutter
// (a ringed cutter or a per-edge runout), at the key that sets it.
void check_postures(const Scene& scene, const Prepared& out, const std::string& evaluator) {
  const SlotTable& path = scene.slot("path");
  for (std::size_t p = 0; p < out.layout.path->passes(); ++p) {
    const ToolPath::Posture& q = out.layout.path->pass(p).posture;
    const bool posture = out.evaluator->follows(q);
    if (posture && out.evaluator->follows_cutter(*out.tool, out.layout.path->runout(), q)) continue;
    const std::string key = q.given ? "file" : q.normal ? "posture" : q.tilt != 0 ? "tilt" : "lead";
    const std::string what =
        q.given ? std::string(q.turns ? "a tool axis that turns along a pass"
                                      : "the tilted tool axis the data give") +
                      " (pass " + std::to_string(p + 1) + " of the cutter-location data)"
                : "the tool's posture " +
                      std::string(q.normal ? "along the surface normal (turning with it over the "
                                             "curvature)"
                                           : "fixed") +
                      " with lead " + format_number(q.lead * 180 / M_PI) + " deg and tilt " +
                      format_number(q.tilt * 180 / M_PI) + " deg";
    const std::string expected =
        !posture  ? q.given ? "a fixed axis over each pass (its README says which)"
                            : "a posture it follows (its README says which)"
        : q.given ? "a vertical axis over each pass"
                  : "a vertical tool (lead and tilt 0)";
    const std::string cutter =
        posture ? " with the cutter '" + scene.slot("tool").plugin + "'" +
                      (out.layout.path->runout().per_edge() ? " and its per-edge runout" : "")
                : "";
    throw InputError(path.params.has(key) ? path.params.where(key) : path.where, "path." + key,
                     "the evaluator '" + evaluator + "' does not follow " + what + cutter +
                         ": expected " + expected +
                         ", or evaluator.plugin = \"zmap\", which "
                         "follows any");
  }
}
}  // namespace

EvaluationRequest evaluation_request(const Prepared& m, unsigned threads) {
  EvaluationRequest rq;
  rq.tool = m.tool.get();
  rq.path = m.layout.path.get();
  rq.kappa = m.layout.kappa;
  rq.lambda_max = m.layout.lambda_max;
  rq.threads = threads;
  return rq;
}

Prepared prepare(const Scene& scene, const PluginCatalog& catalog, unsigned threads) {
  Prepared out;
  clear_recorded_input_files();  // the models below record the files they read
  out.tool = make<ToolGeometry>(scene, catalog, "tool");
  out.surface = make<SurfaceShape>(scene, catalog, "workpiece");
  out.path = make<PathModel>(scene, catalog, "path");
  out.evaluator = make<TopographyEvaluator>(scene, catalog, "evaluator");
  if (scene.enabled("force")) out.force = make<ForceModel>(scene, catalog, "force");
  if (scene.enabled("vibration")) out.dynamics = make<DynamicsModel>(scene, catalog, "vibration");
  for (const std::string name : {"deflection", "springback"})
    if (scene.enabled(name))
      out.deformations.emplace_back(name, make<Deformation>(scene, catalog, name));
  out.layout = make_layout(scene, *out.tool, out.surface, *out.path);
  out.parameter_settings = parameter_settings(scene.table("analysis"));
  out.parameter_names = select_parameters(scene.table("analysis").strings("parameters"));
  const SlotTable& path_slot = scene.slot("path");
  const std::string evaluator = scene.slot("evaluator").plugin;
  if (out.layout.path->feed_axis() == ToolPath::FeedAxis::None && !out.evaluator->follows_curves())
    throw InputError(path_slot.where, "path",
                     "the evaluator '" + evaluator +
                         "' follows straight passes along X or Y only, all one way at one speed, "
                         "and this path has others (radial, spiral or bent passes, or a change of "
                         "feed): expected evaluator.plugin = \"zmap\", which follows any");
  const ToolPath::Posture vertical;
  if (!out.evaluator->follows_cutter(*out.tool, ToolPath::Runout{}, vertical))
    throw InputError(scene.slot("tool").where, "tool",
                     "the evaluator '" + evaluator + "' does not follow the cutter '" +
                         scene.slot("tool").plugin +
                         "': expected evaluator.plugin = \"zmap\", which follows any cutter");
  if (!out.evaluator->follows_cutter(*out.tool, out.layout.path->runout(), vertical)) {
    const Params& runout = scene.table("runout");
    const std::string key =
        runout.number("edge_radial_step") != 0 ? "edge_radial_step" : "edge_axial_step";
    throw InputError(runout.where(key), "runout." + key,
                     "the evaluator '" + evaluator +
                         "' does not follow a per-edge runout: expected evaluator.plugin = "
                         "\"zmap\", which follows any");
  }
  check_postures(scene, out, evaluator);
  const EvaluationCost cost = evaluation_cost(out, threads);
  check_memory(scene, out, cost, threads, available_memory());
  check_duration(scene, out, cost, threads);
  return out;
}

RunResult run_pipeline(const Scene& scene, const PluginCatalog& catalog,
                       const RunOptions& options) {
  RunResult result;
  result.settings = RunSettings::read(scene);
  const RunSettings& settings = result.settings;
  StageClock clock(result.stages);

  Prepared m = clock.run("setup", [&] { return prepare(scene, catalog, options.threads); });
  // The files the models read, with their bytes' checksums as read (a sweep's resume compares).
  for (const std::string& f : recorded_input_files())
    result.input_files.emplace_back(f, file_checksum(f));
  throw_if_interrupted();
  if (m.force) apply_effects(scene, m, options.threads, clock, result);
  throw_if_interrupted();
  result.layout = m.layout;
  const Layout& L = result.layout;
  log_info("evaluation grid (height_raw, in plan): " + std::to_string(L.grid.nx) + " x " +
           std::to_string(L.grid.ny) + " nodes, dx " + format_number(L.grid.dx * 1e3) + " um, dy " +
           format_number(L.grid.dy * 1e3) + " um; " + std::to_string(L.path->passes()) + " passes");

  result.raw = clock.run("evaluate", [&] {
    HeightMap map(L.grid);
    for (std::size_t j = 0; j < L.grid.ny; ++j) {
      const double v = m.surface->height(L.grid.y(j));
      for (std::size_t i = 0; i < L.grid.nx; ++i) map.at(i, j) = v;
    }
    EvaluationRequest rq = evaluation_request(m, options.threads);
    if (options.progress) rq.progress = [&](double f) { options.progress("evaluate", f); };
    rq.stop = &stop_flag();
    in_table(scene.slot("evaluator"), [&] { m.evaluator->evaluate(rq, map, result.work); });
    throw_if_interrupted();  // the map of an interrupted evaluation is incomplete
    return map;
  });
  require_finite(result.raw, "the evaluator's height map");

  result.residual = clock.run("form_removal", [&] {
    if (settings.form == "none") return result.raw;
    if (settings.form == "plane") {  // on the raw XY grid, as `measure --form plane` would fit it
      Surface raw;
      raw.map = result.raw;
      return remove_form(raw, Form::parse("plane", "analysis.form")).map;
    }
    return unroll_residual(result.raw, *m.surface, settings.depth_of_cut, L.s_lo, L.s_hi,
                           L.spacing);
  });
  require_finite(result.residual, "the residual height map");

  result.roughness = clock.run("parameters", [&] {
    Surface residual;
    residual.map = result.residual;
    const Roughness height = roughness(result.residual);
    result.parameters =
        compute_parameters(residual, m.parameter_names, m.parameter_settings, &height);
    return height;
  });
  return result;
}

}  // namespace topomill
