#include "run/effects_stage.hpp"

#include <atomic>
#include <cmath>
#include <exception>
#include <memory>
#include <thread>

#include "interrupt.hpp"
#include "resources.hpp"
#include "run/in_table.hpp"
#include "run/swept_solid.hpp"
#include "swept_path.hpp"

namespace topomill {

namespace {

void require_finite(const std::vector<Vec3>& v, const std::string& what) {
  for (std::size_t i = 0; i < v.size(); ++i)
    if (!v[i].allFinite())
      throw std::runtime_error(what + " is not finite at sample " + std::to_string(i) +
                               "; nothing was written");
}

// Material at the tool's position: below the uncut surface, and outside what the previous pass
// swept (one step-over back, along the same feed direction).
std::function<bool(const Vec3&)> material_test(const ToolPath& path, std::size_t p,
                                               const CutState& st, double R) {
  const Vec3 centre = path.nominal_centre(p, st.time);
  const Vec3 feed = st.feed_direction;
  const Vec3 step = path.feed_axis() == ToolPath::FeedAxis::Y
                        ? Vec3(1, 0, 0)
                        : Vec3(0, std::cos(st.inclination), -std::sin(st.inclination));
  const Vec3 back = st.stepover * step;
  const SurfaceShape* surface = &path.surface();
  const Vec3 axis = path.axis(p, st.time);
  const double ring = path.ring();
  return [=](const Vec3& offset) {
    if (in_swept(offset + back, feed, axis, R, ring)) return false;  // the cheaper test first
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
void to_tool_frame(const ToolPath& path, std::size_t p, double kappa, const ToolGeometry& tool,
                   CutState& st) {
  const Eigen::Matrix3d q = path.tool_frame(p, st.time);
  st.feed_direction = q.transpose() * st.feed_direction;
  st.inclination = path.contact_angle(p, st.time);
  st.alpha_min = std::max(0.0, st.inclination - kappa);
  st.alpha_max = std::min(M_PI / 2, st.inclination + kappa);
  if (tool.ring() > 0) st.alpha_min = tool.first_polar_angle(), st.alpha_max = M_PI / 2;
  st.in_material = [q, world = std::move(st.in_material)](const Vec3& offset) {
    return world(q * offset);
  };
}

// Every pass's cut states and forces on the effects' time grid, and cutter-location data's swept
// path, which the states' material tests ask (kept as long as they are: deformation models see
// the states too).
struct Samples {
  std::unique_ptr<SweptPath> swept;
  std::vector<std::vector<CutState>> states;
  std::vector<std::vector<CuttingForce>> forces;
};

void sample_forces(const Scene& scene, const Prepared& m, unsigned threads, double dt,
                   Samples& samples, RunResult& result) {
  const Layout& L = m.layout;
  ToolPath& path = *L.path;
  const Params& cut = scene.table("cutting");
  auto& states = samples.states;
  auto& forces = samples.forces;
  const std::unique_ptr<SweptPath>& swept = samples.swept;
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
    st.feed_per_tooth = waypoints ? path.speed(p, st.time) *
                                        (2 * M_PI / std::abs(path.spindle_rate())) / m.tool->teeth()
                                  : fz;
    st.inclination = path.surface().inclination(path.surface_y(p, st.time));
    st.alpha_min = std::max(0.0, std::abs(st.inclination) - L.kappa);
    st.alpha_max = std::min(M_PI / 2, std::abs(st.inclination) + L.kappa);
    if (m.tool->ring() > 0) st.alpha_min = m.tool->first_polar_angle(), st.alpha_max = M_PI / 2;
    st.spindle_rate = path.spindle_rate();
    st.depth_of_cut = ap;
    st.stepover = ae;
    st.runout = path.runout().offset, st.runout_angle = path.runout().angle;
    st.edge_radial = path.runout().edge_radial, st.edge_axial = path.runout().edge_axial;
    st.in_material = waypoints ? material_test(path, *swept, p, st, m.tool->radius())
                               : material_test(path, p, st, m.tool->radius());
    if (!path.pass(p).posture.vertical()) to_tool_frame(path, p, L.kappa, *m.tool, st);
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
  std::uint64_t count = 0;
  for (const auto& pass : states) count += pass.size();
  result.work["force_samples"] = count;
}

// The vibration's response to the forces, added to the corrections.
void add_response(const Scene& scene, const Prepared& m, double dt, const Samples& samples,
                  std::vector<std::vector<Vec3>>& corrections) {
  const ToolPath& path = *m.layout.path;
  const auto& forces = samples.forces;
  for (std::size_t p = 0; p < path.passes(); ++p) {
    std::vector<Vec3> f;
    for (const auto& c : forces[p]) f.push_back(c.force);
    const auto x = in_table(scene.slot("vibration"), [&] { return m.dynamics->respond(f, dt); });
    require_finite(x, "the vibration response");
    for (std::size_t k = 0; k < x.size(); ++k) corrections[p][k] += x[k];
  }
}

// Each deformation's correction, added to the corrections.
void add_deformations(const Scene& scene, const Prepared& m, const Samples& samples,
                      std::vector<std::vector<Vec3>>& corrections) {
  const ToolPath& path = *m.layout.path;
  const auto& states = samples.states;
  const auto& forces = samples.forces;
  for (const auto& named : m.deformations) {
    const Deformation& model = *named.second;  // (C++17 lambdas cannot capture a binding)
    for (std::size_t p = 0; p < path.passes(); ++p) {
      const bool vertical = path.pass(p).posture.vertical();
      for (std::size_t k = 0; k < states[p].size(); ++k) {
        // Models see the state and the force in the tool frame, as the force model does,
        // and their correction comes back in it.
        CuttingForce f = forces[p][k];
        Eigen::Matrix3d q;
        if (!vertical) q = path.tool_frame(p, states[p][k].time), f.force = q.transpose() * f.force;
        const Vec3 c = in_table(scene.slot(named.first),
                                [&] { return model.correction(f, *m.tool, states[p][k]); });
        corrections[p][k] += vertical ? c : Vec3(q * c);
      }
    }
  }
}

// The corrections as the path's, once checked: finite, and within the tool's radius (its reach).
void set_corrections(const Scene& scene, const Prepared& m, double dt, const Samples& samples,
                     std::vector<std::vector<Vec3>>& corrections, RunResult& result) {
  ToolPath& path = *m.layout.path;
  const auto& forces = samples.forces;
  // A linear model moving the tool by more than its own radius is outside its range (a mode far
  // too soft, a force far too large): refuse rather than draw a meaningless surface.
  double largest = 0;
  for (const auto& c : corrections)
    for (const auto& v : c) largest = std::max(largest, v.cwiseAbs().maxCoeff());
  result.peak_correction = largest;
  for (const auto& pass : forces)
    for (const auto& f : pass) result.peak_force = std::max(result.peak_force, f.force.norm());
  if (largest > m.tool->reach()) {
    const std::string table = m.dynamics ? "vibration" : m.deformations.front().first;
    throw InputError(scene.slot(table).where, table,
                     "the path correction reaches " + format_number(largest) +
                         " mm, more than the tool's radius " + format_number(m.tool->reach()) +
                         " mm: the effects' parameters (a mode's stiffness, the overhang) are "
                         "outside the range the linear models describe");
  }
  for (std::size_t p = 0; p < path.passes(); ++p) {
    require_finite(corrections[p], "the path correction");
    path.set_correction(p, dt, std::move(corrections[p]));
  }
}

}  // namespace

void apply_effects(const Scene& scene, const Prepared& m, unsigned threads, StageClock& clock,
                   RunResult& result) {
  const ToolPath& path = *m.layout.path;
  const double dt = effect_time_step(m);
  result.dynamics_step = dt;
  Samples samples;
  for (std::size_t p = 0; p < path.passes() && !samples.swept; ++p)
    if (!path.pass(p).waypoints.empty()) samples.swept = std::make_unique<SweptPath>(path);
  // What cutter-location data swept is tested for a ball only (SweptPath).
  if (samples.swept && m.tool->ring() > 0)
    throw InputError(scene.slot("force").where, "force",
                     "the force along cutter-location data is computed for a ball end only, and "
                     "the cutter is '" +
                         scene.slot("tool").plugin +
                         "': expected a ball end, or a path model's passes (raster, zigzag)");
  samples.states.resize(path.passes()), samples.forces.resize(path.passes());
  clock.run("force", [&] { sample_forces(scene, m, threads, dt, samples, result); });
  std::vector<std::vector<Vec3>> corrections(path.passes());
  for (std::size_t p = 0; p < path.passes(); ++p)
    corrections[p].assign(samples.states[p].size(), Vec3::Zero());
  if (m.dynamics) clock.run("dynamics", [&] { add_response(scene, m, dt, samples, corrections); });
  if (!m.deformations.empty())
    clock.run("deformation", [&] { add_deformations(scene, m, samples, corrections); });
  set_corrections(scene, m, dt, samples, corrections, result);
  result.effects = scene.enabled_effects();
}

}  // namespace topomill
