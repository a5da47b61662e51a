#include "pipeline.hpp"

#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <memory>
#include <thread>

#include "code_fingerprint.hpp"
#include "form_removal.hpp"
#include "interrupt.hpp"
#include "log.hpp"
#include "metrology/form_removal.hpp"
#include "resources.hpp"
#include "swept_path.hpp"
#include "topomill/input_files.hpp"
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

// The model a scene table selects, constructed; the log names the library it came from.
template <class T>
std::shared_ptr<T> make(const Scene& scene, const PluginCatalog& catalog,
                        const std::string& table) {
  const SlotTable& st = scene.slot(table);
  log_info(table + ": " + st.plugin + " from " + st.model->library->path);
  return catalog.create<T>(*st.model, st.params);
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
  for (std::size_t p = 0; p < out.layout.path->passes(); ++p) {
    const ToolPath::Posture& q = out.layout.path->pass(p).posture;
    if (out.evaluator->follows(q)) continue;
    const SlotTable& path = path_slot;
    if (q.given)
      throw InputError(path.params.has("file") ? path.params.where("file") : path.where,
                       "path.file",
                       "the evaluator '" + evaluator + "' does not follow " +
                           (q.turns ? "a tool axis that turns along a pass"
                                    : "the tilted tool axis the data give") +
                           " (pass " + std::to_string(p + 1) +
                           " of the cutter-location data): expected a fixed axis over each pass "
                           "(its README says which), or evaluator.plugin = \"zmap\", which "
                           "follows any");
    const std::string key = q.normal ? "posture" : q.tilt != 0 ? "tilt" : "lead";
    throw InputError(path.params.has(key) ? path.params.where(key) : path.where, "path." + key,
                     "the evaluator '" + evaluator + "' does not follow the tool's posture " +
                         (q.normal ? "along the surface normal (turning with it over the "
                                     "curvature)"
                                   : "fixed") +
                         " with lead " + format_number(q.lead * 180 / M_PI) + " deg and tilt " +
                         format_number(q.tilt * 180 / M_PI) +
                         " deg: expected a posture it follows (its README says which), or "
                         "evaluator.plugin = \"zmap\", which follows any");
  }
  const EvaluationCost cost = evaluation_cost(out, threads);
  check_memory(scene, out, cost, threads, available_memory());
  check_duration(scene, out, cost, threads);
  return out;
}

namespace {

// A ParamError raised while a model works (not only when it is made) still names its scene key.
template <class F>
auto in_table(const SlotTable& table, F&& f) {
  try {
    return f();
  } catch (const ParamError& e) {
    throw InputError(table.params.where(e.key()), table.table + "." + e.key(), e.what());
  }
}

void require_finite(const std::vector<Vec3>& v, const std::string& what) {
  for (std::size_t i = 0; i < v.size(); ++i)
    if (!v[i].allFinite())
      throw std::runtime_error(what + " is not finite at sample " + std::to_string(i) +
                               "; nothing was written");
}

// Material at the tool's position: below the uncut surface, and farther than R from the previous
// pass's centre line (one step-over back, along the same feed direction).
std::function<bool(const Vec3&)> material_test(const ToolPath& path, std::size_t p,
                                               const CutState& st, double R) {
  const Vec3 centre = path.nominal_centre(p, st.time);
  const Vec3 feed = st.feed_direction;
  const Vec3 step = path.feed_axis() == ToolPath::FeedAxis::Y
                        ? Vec3(1, 0, 0)
                        : Vec3(0, std::cos(st.inclination), -std::sin(st.inclination));
  const Vec3 back = st.stepover * step;
  const SurfaceShape* surface = &path.surface();
  return [=](const Vec3& offset) {
    const Vec3 q = offset + back;  // the cheaper test first
    if ((q - q.dot(feed) * feed).squaredNorm() < R * R) return false;
    const Vec3 point = centre + offset;
    return surface->normal_residual(point.y(), point.z(), 0.0) < 0;
  };
}

// The same for cutter-location data: below the uncut surface and farther than R from the centre's
// path before the tool's own trail (the last 2 R of it), on this pass or any before it.
std::function<bool(const Vec3&)> material_test(const ToolPath& path, const SweptPath& swept,
                                               std::size_t p, const CutState& st, double R) {
  const Vec3 centre = path.nominal_centre(p, st.time);
  const double until = st.time - 2 * R / path.speed(p, st.time);
  const SurfaceShape* surface = &path.surface();
  const SweptPath* before = &swept;  // outlives every state (apply_effects)
  return [=](const Vec3& offset) {
    const Vec3 point = centre + offset;
    if (before->swept(p, until, point, R)) return false;
    return surface->normal_residual(point.y(), point.z(), 0.0) < 0;
  };
}

// A tilted tool's state as the force and deformation models read it: in the tool frame (its axis
// as z, the spindle angle measured about it), the feed direction turned into it, the contact's
// polar angle about the axis for the surface's inclination, and the material test turned back.
void to_tool_frame(const ToolPath& path, std::size_t p, double kappa, CutState& st) {
  const Eigen::Matrix3d q = path.tool_frame(p, st.time);
  st.feed_direction = q.transpose() * st.feed_direction;
  st.inclination = path.contact_angle(p, st.time);
  st.alpha_min = std::max(0.0, st.inclination - kappa);
  st.alpha_max = std::min(M_PI / 2, st.inclination + kappa);
  st.in_material = [q, world = std::move(st.in_material)](const Vec3& offset) {
    return world(q * offset);
  };
}

}  // namespace

// Forces on a time grid chosen for the dynamics, the response, the deformations, and their sum
// as the path correction TC (Eq. 32-33). Each pass starts from rest.
static void apply_effects(const Scene& scene, const Prepared& m, unsigned threads,
                          StageClock& clock, RunResult& result) {
  const Layout& L = m.layout;
  ToolPath& path = *L.path;
  const Params& cut = scene.table("cutting");
  const double dt = effect_time_step(m);
  result.dynamics_step = dt;

  // Cutter-location data's swept path, which the states' material tests ask (kept as long as
  // they are: deformation models see the states too).
  std::unique_ptr<SweptPath> swept;
  for (std::size_t p = 0; p < path.passes() && !swept; ++p)
    if (!path.pass(p).waypoints.empty()) swept = std::make_unique<SweptPath>(path);
  std::vector<std::vector<CutState>> states(path.passes());
  std::vector<std::vector<CuttingForce>> forces(path.passes());
  clock.run("force", [&] {
    // A sample's state and force depend on its time only (the force sees the nominal cut, not
    // the vibration): blocks of samples are shared among threads and the result does not depend
    // on how. An error is reported from the earliest block that raised one, as one thread would.
    constexpr std::size_t kBlock = 1024;
    std::vector<std::pair<std::size_t, std::size_t>> blocks;  // (pass, first sample)
    for (std::size_t p = 0; p < path.passes(); ++p) {
      const auto n = static_cast<std::size_t>(std::ceil(path.pass(p).t_end / dt)) + 1;
      states[p].resize(n), forces[p].resize(n);
      for (std::size_t k = 0; k < n; k += kBlock) blocks.emplace_back(p, k);
    }
    const double fz = cut.number("feed_per_tooth"), ap = cut.number("depth_of_cut"),
                 ae = cut.number("stepover");
    auto sample = [&](std::size_t p, std::size_t k) {
      CutState& st = states[p][k];
      st.time = static_cast<double>(k) * dt;
      st.spindle_angle = path.spindle_angle(p, st.time);
      st.feed_direction = path.feed_direction(p, st.time);
      // Cutter-location data sets its own feed: the chip follows it.
      const bool waypoints = !path.pass(p).waypoints.empty();
      st.feed_per_tooth = waypoints
                              ? path.speed(p, st.time) *
                                    (2 * M_PI / std::abs(path.spindle_rate())) / m.tool->teeth()
                              : fz;
      st.inclination = path.surface().inclination(path.surface_y(p, st.time));
      st.alpha_min = std::max(0.0, std::abs(st.inclination) - L.kappa);
      st.alpha_max = std::min(M_PI / 2, std::abs(st.inclination) + L.kappa);
      st.spindle_rate = path.spindle_rate();
      st.depth_of_cut = ap;
      st.stepover = ae;
      st.runout = path.runout().offset, st.runout_angle = path.runout().angle;
      st.in_material = waypoints ? material_test(path, *swept, p, st, m.tool->radius())
                                 : material_test(path, p, st, m.tool->radius());
      if (!path.pass(p).posture.vertical()) to_tool_frame(path, p, L.kappa, st);
      forces[p][k] = in_table(scene.slot("force"), [&] { return m.force->evaluate(*m.tool, st); });
      if (!path.pass(p).posture.vertical())
        forces[p][k].force = path.tool_frame(p, st.time) * forces[p][k].force;
    };
    std::vector<std::exception_ptr> errors(blocks.size());
    std::atomic<std::size_t> next{0};
    auto work = [&] {
      for (std::size_t b = next++; b < blocks.size(); b = next++) {
        try {
          throw_if_interrupted();  // a pass can take seconds
          const auto [p, first] = blocks[b];
          for (std::size_t k = first; k < std::min(first + kBlock, states[p].size()); ++k)
            sample(p, k);
        } catch (...) {
          errors[b] = std::current_exception();
        }
      }
    };
    std::vector<std::thread> pool;
    for (unsigned w = 1; w < std::min<std::size_t>(threads, blocks.size()); ++w)
      pool.emplace_back(work);
    work();
    for (auto& t : pool) t.join();
    for (const auto& e : errors)
      if (e) std::rethrow_exception(e);
    std::uint64_t samples = 0;
    for (const auto& pass : states) samples += pass.size();
    result.work["force_samples"] = samples;
  });

  std::vector<std::vector<Vec3>> corrections(path.passes());
  for (std::size_t p = 0; p < path.passes(); ++p)
    corrections[p].assign(states[p].size(), Vec3::Zero());
  if (m.dynamics) {
    clock.run("dynamics", [&] {
      for (std::size_t p = 0; p < path.passes(); ++p) {
        std::vector<Vec3> f;
        for (const auto& c : forces[p]) f.push_back(c.force);
        const auto x =
            in_table(scene.slot("vibration"), [&] { return m.dynamics->respond(f, dt); });
        require_finite(x, "the vibration response");
        for (std::size_t k = 0; k < x.size(); ++k) corrections[p][k] += x[k];
      }
    });
  }
  if (!m.deformations.empty()) {
    clock.run("deformation", [&] {
      for (const auto& named : m.deformations) {
        const Deformation& model = *named.second;  // (C++17 lambdas cannot capture a binding)
        for (std::size_t p = 0; p < path.passes(); ++p) {
          const bool vertical = path.pass(p).posture.vertical();
          for (std::size_t k = 0; k < states[p].size(); ++k) {
            // Models see the state and the force in the tool frame, as the force model does,
            // and their correction comes back in it.
            CuttingForce f = forces[p][k];
            Eigen::Matrix3d q;
            if (!vertical)
              q = path.tool_frame(p, states[p][k].time), f.force = q.transpose() * f.force;
            const Vec3 c = in_table(scene.slot(named.first),
                                    [&] { return model.correction(f, *m.tool, states[p][k]); });
            corrections[p][k] += vertical ? c : Vec3(q * c);
          }
        }
      }
    });
  }
  // A linear model moving the tool by more than its own radius is outside its range (a mode far
  // too soft, a force far too large): refuse rather than draw a meaningless surface.
  double largest = 0;
  for (const auto& c : corrections)
    for (const auto& v : c) largest = std::max(largest, v.cwiseAbs().maxCoeff());
  result.peak_correction = largest;
  for (const auto& pass : forces)
    for (const auto& f : pass) result.peak_force = std::max(result.peak_force, f.force.norm());
  if (largest > m.tool->radius()) {
    const std::string table = m.dynamics ? "vibration" : m.deformations.front().first;
    throw InputError(scene.slot(table).where, table,
                     "the path correction reaches " + format_number(largest) +
                         " mm, more than the ball radius " + format_number(m.tool->radius()) +
                         " mm: the effects' parameters (a mode's stiffness, the overhang) are "
                         "outside the range the linear models describe");
  }
  for (std::size_t p = 0; p < path.passes(); ++p) {
    require_finite(corrections[p], "the path correction");
    path.set_correction(p, dt, std::move(corrections[p]));
  }
  result.effects = scene.enabled_effects();
}

RunResult run_pipeline(const Scene& scene, const PluginCatalog& catalog,
                       const RunOptions& options) {
  RunResult result;
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
    m.evaluator->evaluate(rq, map, result.work);
    throw_if_interrupted();  // the map of an interrupted evaluation is incomplete
    return map;
  });
  require_finite(result.raw, "the evaluator's height map");

  const std::string form = scene.table("analysis").string("form");
  result.residual = clock.run("form_removal", [&] {
    if (form == "none") return result.raw;
    if (form == "plane") {  // on the raw XY grid, as `measure --form plane` would fit it
      Surface raw;
      raw.map = result.raw;
      return remove_form(raw, Form::parse("plane", "analysis.form")).map;
    }
    const double ap = scene.table("cutting").number("depth_of_cut");
    return unroll_residual(result.raw, *m.surface, ap, L.s_lo, L.s_hi, L.spacing);
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
