#include "compare.hpp"

#include <algorithm>
#include <cmath>

#include "interrupt.hpp"
#include "metrology/resample.hpp"
#include "metrology/roughness.hpp"
#include "metrology/spectrum.hpp"
#include "topomill/error.hpp"

namespace topomill {

namespace {
// The largest |height| the registration's sums of squared heights over a map hold (mm).
constexpr double kLargestHeight = 1e150;

double wrap_deg(double d) {
  d = std::fmod(d, 180.0);
  return d < 0 ? d + 180 : d;
}

// The surface on a grid of spacing (dx, dy) over its own extent (itself when it has it).
Surface to_spacing(const Surface& s, double dx, double dy) {
  const Grid& g = s.map.grid;
  if (g.dx == dx && g.dy == dy) return s;
  Grid c;
  c.x0 = g.x0, c.y0 = g.y0, c.dx = dx, c.dy = dy;
  // The nodes that fit within the map (a thousandth of a node's slack for rounding).
  c.nx = static_cast<std::size_t>(static_cast<double>(g.nx - 1) * g.dx / dx + 1e-3) + 1;
  c.ny = static_cast<std::size_t>(static_cast<double>(g.ny - 1) * g.dy / dy + 1e-3) + 1;
  return resample(s, c);
}

}  // namespace

Lay lay_of(const Surface& s) {
  Lay l;
  const double theta = texture_direction(PowerSpectrum(s));
  l.std_deg = theta * 180 / M_PI;
  l.lay_deg = wrap_deg(l.std_deg + 90);
  l.across_mm = dominant_period(s, theta);
  l.along_mm = dominant_period(s, theta + M_PI / 2);
  l.x_mm = dominant_period(s, 0.0);
  l.y_mm = dominant_period(s, M_PI / 2);
  return l;
}

Comparison compare_surfaces(const Surface& sim_in, const Surface& meas_in,
                            const CompareSettings& settings) {
  const Grid &gs = sim_in.map.grid, &gm = meas_in.map.grid;
  const SourceRef where{meas_in.source};
  const double ratio = std::max({gs.dx / gm.dx, gm.dx / gs.dx, gs.dy / gm.dy, gm.dy / gs.dy});
  if (ratio > 8)
    throw InputError(
        where, "",
        "the node spacings differ " + format_number(ratio) +
            "-fold (more than 8): expected maps of similar resolution (smooth the "
            "finer one with --filter-s at the coarser spacing, or resample it, first)");
  Comparison c;
  c.dx = std::max(gs.dx, gm.dx), c.dy = std::max(gs.dy, gm.dy);
  c.interpolation = "Keys cubic convolution (a = -1/2)";
  c.sim = to_spacing(sim_in, c.dx, c.dy);
  c.meas = to_spacing(meas_in, c.dx, c.dy);
  for (const Surface* s : {&c.sim, &c.meas}) {
    const Grid& g = s->map.grid;
    if (g.nx < 4 || g.ny < 4)
      throw InputError(SourceRef{s->source}, "",
                       "on the common grid the map is " + std::to_string(g.nx) + " x " +
                           std::to_string(g.ny) +
                           " nodes: expected an areal map of 4 or more each way (a profile "
                           "cannot be registered in plane)");
  }
  // Sq about the mean (roughness(): two passes, so a level map far from zero gives 0, not the
  // round-off of a sum of squares less the mean's square), and the largest |height|.
  const Roughness rs = roughness(c.sim.map, c.sim.valid), rm = roughness(c.meas.map, c.meas.valid);
  const double sq_s = rs.Sq, sq_m = rm.Sq;
  auto top = [](const Roughness& r) {
    return std::max(std::abs(r.mean + r.Sp), std::abs(r.mean - r.Sv));
  };
  // Flat: relief below round-off of its heights (1e-12 of the largest).
  const bool flat_s = !(sq_s > 1e-12 * top(rs)), flat_m = !(sq_m > 1e-12 * top(rm));
  if (flat_s || flat_m)
    throw InputError(flat_s ? SourceRef{sim_in.source} : where, "",
                     "the map is flat after processing: expected a surface with relief");
  // The registration correlates products of heights: beyond kLargestHeight they overflow, and
  // at 1e300 mm the search would find no overlap and call the maps different places.
  for (const auto& [r, source] : {std::pair{&rs, &sim_in.source}, std::pair{&rm, &meas_in.source}})
    if (!(top(*r) < kLargestHeight))
      throw InputError(SourceRef{*source}, "",
                       "heights reach " + format_number(top(*r)) + " mm, beyond " +
                           format_number(kLargestHeight) +
                           " mm, where the registration's products of heights overflow: expected "
                           "the heights of a real surface (units that do not match?)");
  if (sq_s / sq_m > 100 || sq_m / sq_s > 100)
    throw InputError(where, "",
                     "Sq is " + format_number(sq_m * 1e3) + " um here and " +
                         format_number(sq_s * 1e3) + " um in " + sim_in.source +
                         ": heights more than 100 times apart, units that do not match (a file "
                         "in um read as mm?); expected heights on one scale");

  throw_if_interrupted();  // between the steps, each at most a few FFTs of the maps
  c.sim_lay = lay_of(c.sim);
  c.meas_lay = lay_of(c.meas);
  throw_if_interrupted();
  RegistrationOptions ro = settings.registration;
  if (ro.rotation) {
    // The lays' difference, the nearest way round (a lay has no sense: 180 deg is the same).
    double d = c.meas_lay.std_deg - c.sim_lay.std_deg;
    d = std::remainder(d, 180.0);
    ro.angle_guess = d * M_PI / 180;
  }
  c.registration = register_surfaces(c.sim, c.meas, ro);
  throw_if_interrupted();
  c.aligned = align(c.meas, c.sim, c.registration);
  c.difference = c.aligned;
  c.sim_overlap = c.sim;
  c.sim_overlap.valid.assign(c.sim.map.z.size(), 0);
  std::size_t shared = 0, sim_valid = 0;
  for (std::size_t k = 0; k < c.sim.map.z.size(); ++k) {
    const bool both = c.sim.is_valid(k) && c.aligned.is_valid(k);
    sim_valid += c.sim.is_valid(k);
    c.sim_overlap.valid[k] = both;
    c.difference.valid[k] = both;
    c.difference.map.z[k] = both ? c.aligned.map.z[k] - c.sim.map.z[k] : 0.0;
    shared += both;
  }
  c.overlap_share =
      sim_valid > 0 ? static_cast<double>(shared) / static_cast<double>(sim_valid) : 0;
  if (shared < 16)
    throw InputError(where, "",
                     "the registered maps share " + std::to_string(shared) +
                         " nodes: expected maps of the same area of the surface");
  throw_if_interrupted();
  c.sim_parameters = compute_parameters(c.sim_overlap, settings.names, settings.parameters);
  c.meas_parameters = compute_parameters(c.aligned, settings.names, settings.parameters);
  return c;
}

}  // namespace topomill
