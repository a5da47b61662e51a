#include "layout_checks.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "resources.hpp"

namespace topomill {

namespace {
// A laid-out pass in memory: the model's PassLine and the core's ToolPath::Pass, with the
// vectors' growth (measured: 420 bytes a pass at 1e6 passes, `topomill check` under
// /usr/bin/time -f %M).
constexpr double kLayoutBytesPerPass = 512;
constexpr double kPassesBeyond = 3;  // a step-over beyond each side, and one rounded up
}  // namespace

std::string format_count(double n) {
  std::ostringstream os;
  os.precision(3);
  os << n;
  return os.str();
}

// A tilted tool: only the ball may cut (the contact range within the ball's lower half, about
// the axis), and the steepest contact sets the evaluators' steps (lambda_max). The contact angle
// is the angle between the axis and the normal: fixed, it varies with the surface along the pass;
// normal, it is constant. Either way it is largest at a pass's ends or its middle on the
// surfaces here (their inclination is monotone in y), and the CATW margin stands for the rest.
void check_posture(const ToolPath& path, const ToolGeometry& tool, Layout& L,
                   const SlotTable& slot) {
  L.lambda_max = 0;  // the contact's polar angle about the axis, no longer the inclination
  for (std::size_t p = 0; p < path.passes(); ++p) {
    if (!path.pass(p).waypoints.empty()) continue;  // check_waypoints
    const double t_end = path.pass(p).t_end;
    for (double t : {0.0, 0.5 * t_end, t_end}) {
      const double angle = path.contact_angle(p, t);
      L.lambda_max = std::max(L.lambda_max, angle);
      // An end mill has a side edge above its corner: it may cut, and is meant to.
      if (angle + L.kappa < M_PI / 2 || tool.has_bottom()) continue;
      const char* key = slot.params.has("tilt") && slot.params.number("tilt") != 0 ? "tilt"
                        : slot.params.has("lead")                                  ? "lead"
                                                                                   : nullptr;
      throw InputError(
          key ? slot.params.where(key) : slot.where,
          key ? "path." + std::string(key) : std::string("path"),
          "the tool's axis is " + format_number(angle / kDeg) +
              " deg from the surface normal at y = " + format_number(path.surface_y(p, t)) +
              " mm, and with the cut's half-width of " + format_number(L.kappa / kDeg) +
              " deg the ball's equator would cut (the shank above it would "
              "rub): expected a smaller lead or tilt");
    }
  }
}

// What laying `steps` passes out holds, estimated before any pass is laid out, against the
// memory there is: a step-over of 21 nm on a 0.1 mm patch is 4.8e6 passes, 2.1 GB and tens of
// seconds to lay out, too late for the memory check after the layout.
void check_layout_memory(double steps, double ae, const Params& cut) {
  const double layout_bytes = (steps + kPassesBeyond) * kLayoutBytesPerPass;
  const double available = static_cast<double>(available_memory());
  if (layout_bytes > 0.9 * available)
    throw InputError(cut.where("stepover"), "cutting.stepover",
                     "the patch would need about " + format_count(steps) +
                         " passes at a step-over of " + format_number(ae) +
                         " mm, whose layout alone needs about " + format_bytes(layout_bytes) +
                         ", and " + format_bytes(available) +
                         " are available: raise cutting.stepover or shrink region.size");
}

// Every point of cutter-location data: its contact within the ball's lower half (about the
// given axis, or the vertical), named by file and line, for the scene's depth or the point's own
// if deeper (a centre below the surface puts the ball's equator in the material); the steepest
// contact (lambda_max); and some point near the patch within the ball's reach of the surface (a
// path that never touches the part left a flat map: centres read as tips, passes above the
// part).
void check_waypoints(const ToolPath& path, const std::vector<PassLine>& lines, const Reach& reach,
                     const ToolGeometry& tool, Layout& L) {
  const double R = tool.radius();
  const SurfaceShape& surface = path.surface();
  double lowest = INFINITY;  // the least distance of a centre near the patch from the surface
  SourceRef lowest_at;
  for (std::size_t p = 0; p < path.passes(); ++p) {
    const ToolPath::Pass& pass = path.pass(p);
    if (pass.waypoints.empty()) continue;
    const std::vector<ClPoint>& points = lines[p].points;
    for (std::size_t k = 0; k < points.size(); ++k) {
      const double t = path.waypoint_time(p, k);
      const double y = path.surface_y(p, t), angle = path.contact_angle(p, t);
      const SourceRef at{lines[p].source, points[k].line, 1};
      const Vec3& centre = pass.waypoints[k].centre;
      // (The foot point is searched on the surface: off it, the search ends at an end.)
      const double edge = 1e-9 * (1 + std::abs(y));
      if (!(y > surface.y_min() + edge && y < surface.y_max() - edge) || !std::isfinite(angle))
        throw InputError(at, "path.file",
                         "the ball centre at y = " + format_number(centre.y()) +
                             " mm has no point of the workpiece surface beneath it (y from " +
                             format_number(surface.y_min()) + " to " +
                             format_number(surface.y_max()) + " mm): expected points over it");
      const double above = surface.normal_residual(centre.y(), centre.z(), 0.0);
      if (reach.holds(centre) && above < lowest) lowest = above, lowest_at = at;
      // An end mill's side edge above its corner may cut: its centres may be below the surface.
      if (above <= 0 && !tool.has_bottom())
        throw InputError(at, "path.file",
                         "the ball centre is " + format_number(-above) +
                             " mm below the workpiece surface (along its normal): the ball's "
                             "equator and the shank above it would cut; expected centres above "
                             "the surface, less than the ball radius " +
                             format_number(R) + " mm (tool tips read as centres? see path.point)");
      // The half-angle of the ball's cap in the material at this point's own depth.
      const double own = above < R ? std::acos(above / R) : 0.0;
      const double kappa = std::max(L.kappa, own);
      L.lambda_max = std::max(L.lambda_max, angle);
      if (angle + kappa < M_PI / 2) continue;
      throw InputError(at, "path.file",
                       "the tool's axis is " + format_number(angle / kDeg) +
                           " deg from the surface normal here, and with the cut's half-width of " +
                           format_number(kappa / kDeg) +
                           " deg the ball's equator would cut (the shank above it would rub): "
                           "expected an axis nearer the normal");
    }
  }
  if (std::isfinite(lowest) && lowest >= R)
    throw InputError(lowest_at, "path.file",
                     "the tool never touches the workpiece near the patch: the lowest ball "
                     "centre there (this line) is " +
                         format_number(lowest) + " mm from the surface along its normal, " +
                         format_number(lowest - R) + " mm more than the ball radius " +
                         format_number(R) +
                         " mm, so the map would be the uncut surface; expected centres less than "
                         "a ball radius from the surface (passes above the part? centres read as "
                         "tips: see path.point)");
}

}  // namespace topomill
