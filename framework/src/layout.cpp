#include "layout.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "catw.hpp"
#include "interrupt.hpp"
#include "layout_checks.hpp"
#include "resources.hpp"

namespace topomill {

namespace {
constexpr double kMaxCells = 1e12;          // grid spacings along a side: far beyond any memory
constexpr double kMaxPasses = 1e7;          // passes across the patch
constexpr double kMinFeedPerTooth = 1e-6;   // mm, as cutting.feed_per_tooth's least
constexpr double kLargestCoordinate = 1e6;  // mm: a kilometre, as the workpiece's radius

double arc_of(const SurfaceShape& s, double y) {
  return s.arc_coordinate(y, s.height(y));
}
}  // namespace

double y_at_arc(const SurfaceShape& surface, double s, double y_guess, double span) {
  double lo = std::max(surface.y_min(), y_guess - span);
  double hi = std::min(surface.y_max(), y_guess + span);
  for (int i = 0; i < 200 && hi - lo > 1e-13 * (1.0 + std::abs(lo)); ++i) {
    double mid = 0.5 * (lo + hi);
    (arc_of(surface, mid) < s ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// The feed rates cutter-location data may give, from the scene's feed per tooth fz at feed
// speed vf: a tooth's feed from kMinFeedPerTooth (as cutting.feed_per_tooth: below it the spindle
// angle's rounding moves the edge by nanometres, and a pass lasts for ever) to the ball's
// diameter (beyond it each tooth leaves a dimple of its own, and 1e300 overflowed the times).
struct FeedLimits {
  double lo, hi;  // mm/s
};

// A pass of cutter-location data, checked point by point against what the core can follow: each
// named by its file and line.
template <class Defect>
static ToolPath::Pass waypoint_pass(const PassLine& l, const FeedLimits& feed,
                                    const Defect& defect) {
  if (!std::isfinite(l.phase)) throw defect("laid out a pass whose phase is not finite");
  if (l.points.size() < 2) throw defect("laid out a pass of fewer than two points");
  if (l.posture.normal || l.posture.lead != 0 || l.posture.tilt != 0)
    throw defect("laid out points with a lead, tilt or normal posture (the points give the axis)");
  ToolPath::Pass p{};
  p.phase = l.phase;
  for (std::size_t k = 0; k < l.points.size(); ++k) {
    const ClPoint& c = l.points[k];
    const SourceRef at{l.source, c.line, 1};
    auto refuse = [&](const std::string& what) { return InputError(at, "path.file", what); };
    const ToolPath::Waypoint& w = c.at;
    if (!w.centre.allFinite() || !w.axis.allFinite() || !std::isfinite(w.speed))
      throw defect("read a point that is not finite");
    if (std::abs(w.axis.norm() - 1) > 1e-9) throw defect("read an axis that is not a unit vector");
    // Far points overflow the path's lengths and times, and a later check would then name
    // another point (a y of 1e308 mm, the next line).
    if (!(w.centre.cwiseAbs().maxCoeff() <= kLargestCoordinate))
      throw refuse("the point lies " + format_number(w.centre.cwiseAbs().maxCoeff()) +
                   " mm from the origin along an axis: expected coordinates of a part, within " +
                   format_number(kLargestCoordinate) + " mm");
    if (k + 1 < l.points.size() && !(w.speed >= feed.lo && w.speed <= feed.hi))
      throw refuse("the feed to the next point is " + format_number(w.speed * 60) +
                   " mm/min: expected " + format_number(feed.lo * 60) + " to " +
                   format_number(feed.hi * 60) +
                   " mm/min (a feed per tooth from 1 nm to the ball's diameter at this spindle "
                   "speed and number of teeth)");
    if (k + 1 < l.points.size() && w.centre == l.points[k + 1].at.centre)
      throw defect("laid out two equal points in a row (from lines " + std::to_string(c.line) +
                   " and " + std::to_string(l.points[k + 1].line) + " of " + l.source + ")");
    p.waypoints.push_back(w);
    // Not vertical as soon as one point's axis is not: then the tool frame follows the points.
    p.posture.given = p.posture.given || w.axis != Vec3::UnitZ();
  }
  return p;
}

namespace {

// make_layout's steps over one scene, in order, sharing what each reads and finds: the checks of
// the cut, the patch's place on the surface and its projection in plan, the grid, the passes the
// path model lays out, and the tool path.
struct LayoutSteps {
  LayoutSteps(const Scene& scene_, const ToolGeometry& tool_,
              std::shared_ptr<const SurfaceShape> surface_, const PathModel& path_model_)
      : scene(scene_),
        tool(tool_),
        surface(std::move(surface_)),
        path_model(path_model_),
        cut(scene.table("cutting")),
        region(scene.table("region")),
        work(scene.slot("workpiece")),
        path_slot(scene.slot("path")),
        R(tool.radius()),
        rim(tool.reach()),
        ap(cut.number("depth_of_cut")),
        ae(cut.number("stepover")),
        fz(cut.number("feed_per_tooth")),
        rpm(cut.number("spindle_speed")),
        h(region.number("spacing")),
        r(surface->curvature_radius()),
        size(region.numbers("size")),
        teeth(tool.teeth()) {}

  void check_cut() const;
  void place_patch();
  void project_patch();
  void make_grid();
  void request_passes();
  std::vector<ToolPath::Pass> to_passes();
  void make_path(std::vector<ToolPath::Pass> passes);
  // A model's defect, not the user's: said so, with the model's name.
  InputError defect(const std::string& what) const {
    return InputError(
        path_slot.where, "path",
        "the path model '" + path_slot.plugin + "' " + what + " (a defect of the model)");
  }

  const Scene& scene;
  const ToolGeometry& tool;
  std::shared_ptr<const SurfaceShape> surface;
  const PathModel& path_model;
  const Params &cut, &region;
  const SlotTable &work, &path_slot;
  // R: the tube's radius (the ball's); rim: how far the edges reach from the axis (R for a ball,
  // D/2 for an end mill).
  const double R, rim, ap, ae, fz, rpm, h, r;
  const std::vector<double>& size;
  const int teeth;
  Layout L;
  // The patch's place: by region.centre or by region.lambda (the key, for the messages), its
  // centre, inclination and arc position, and its rows' extent in plan.
  bool by_centre = false;
  SourceRef place_at;
  std::string place_name;
  double x_c = 0, y_c = 0, lambda_c = 0, s_c = 0, y_lo = 0, y_hi = 0;
  // The passes: their run-in, feed speed and spindle rate, what the path model was asked and
  // laid out, and how far along Y the laid-out lines reach.
  double run = 0, vf = 0, omega = 0;
  PathRequest rq;
  std::vector<PassLine> lines;
  double y_first = INFINITY, y_last = -INFINITY, reach = 0;
};

void LayoutSteps::check_cut() const {
  // The workpiece's radius is a key of its own plugin's table: point at it when it is there.
  const SourceRef radius_at = work.params.has("radius") ? work.params.where("radius") : work.where;
  // An end mill's side edge may cut above its corner; a ball's or an insert's nothing may.
  if (ap > R && !tool.has_bottom())
    throw InputError(cut.where("depth_of_cut"), "cutting.depth_of_cut",
                     "depth of cut " + format_number(ap) + " mm exceeds the " +
                         (tool.ring() > 0 ? "insert" : "ball") + " radius " + format_number(R) +
                         " mm: only the " + (tool.ring() > 0 ? "insert" : "ball") + " may cut");
  if (r < 0 && -r <= rim)
    throw InputError(radius_at, "workpiece.radius",
                     "a concave radius of " + format_number(-r) +
                         " mm is not larger than the tool's radius " + format_number(rim) +
                         " mm: expected a radius above it (the tool cannot follow it without "
                         "gouging)");
  if (r > 0 && ap >= r)
    throw InputError(cut.where("depth_of_cut"), "cutting.depth_of_cut",
                     "depth of cut " + format_number(ap) + " mm reaches the convex radius " +
                         format_number(r) + " mm: expected less (the cut would remove the arc)");
  if (h > std::min(size[0], size[1]) / 2)
    throw InputError(region.where("spacing"), "region.spacing",
                     "spacing is larger than half the patch: expected at least 3 nodes per side");
}

void LayoutSteps::place_patch() {
  // The patch's centre: over the uncut surface point at region.lambda, or at region.centre.
  by_centre = region.has("centre");
  if (by_centre == region.has("lambda"))
    throw InputError(region.table_where(), "region",
                     by_centre ? "both lambda and centre place the patch: expected one of them"
                               : "missing key: expected lambda (deg, the inclination at the "
                                 "patch's centre) or centre ([x, y] in mm) to place the patch");
  // The key that placed it, for the messages below.
  const char* place_key = by_centre ? "centre" : "lambda";
  place_at = region.where(place_key);
  place_name = std::string("region.") + place_key;
  if (by_centre) {
    x_c = region.numbers("centre")[0], y_c = region.numbers("centre")[1];
    if (!(y_c > surface->y_min() && y_c < surface->y_max()))
      throw InputError(place_at, place_name,
                       "y = " + format_number(y_c) + " mm is off the workpiece surface (y from " +
                           format_number(surface->y_min()) + " to " +
                           format_number(surface->y_max()) + " mm): expected a y on it");
  } else {
    try {
      y_c = surface->y_at_inclination(region.number("lambda") * kDeg);
    } catch (const ParamError& e) {
      throw InputError(place_at, place_name, e.what());
    }
  }
  lambda_c = surface->inclination(y_c);
  s_c = arc_of(*surface, y_c);
  L.s_lo = s_c - size[1] / 2;
  L.s_hi = s_c + size[1] / 2;
  // Checked before anything is laid out along the patch (found by the scene fuzzer: a patch of
  // 2.6e6 mm on a 20 mm arc laid out millions of passes before the run-in check refused it).
  const double arc_min = arc_of(*surface, surface->y_min());
  const double arc_max = arc_of(*surface, surface->y_max());
  if (L.s_lo <= arc_min || L.s_hi >= arc_max)
    throw InputError(region.where("size"), "region.size",
                     "the patch runs past the end of the workpiece surface (its arc spans " +
                         format_number(arc_min) + " to " + format_number(arc_max) +
                         " mm; the patch " + format_number(L.s_lo) + " to " +
                         format_number(L.s_hi) + " mm): expected a smaller region.size or " +
                         place_name);
}

void LayoutSteps::project_patch() {
  // The patch lies on the machined surface, ap below the uncut one along the normal: its ends
  // project to y = y_s - ap sin(lambda(y_s)), y_s the uncut surface point at the same arc position.
  const double span = size[1] + 1.0;
  auto cut_y = [&](double s) {
    const double ys = y_at_arc(*surface, s, y_c, span);
    return ys - ap * std::sin(surface->inclination(ys));
  };
  y_lo = cut_y(L.s_lo);
  y_hi = cut_y(L.s_hi);
  if (!(y_hi > y_lo))  // a surface plugin whose y does not grow along its arc
    throw InputError(work.where, "workpiece",
                     "the patch's ends project to y = " + format_number(y_lo) + " and " +
                         format_number(y_hi) +
                         " mm: expected y to grow along the surface's arc (a defect of the "
                         "surface model)");
}

void LayoutSteps::make_grid() {
  // Z-map grid: spacing h in X; in Y h cos(lambda), so that the resolution on the surface is about
  // h wherever the patch sits up to lambda = 60 deg. Steeper, the Y spacing stays h/2 (a height
  // field over XY sees a near-vertical surface edge-on; finer Y spacing would make the paper's
  // time step, tied to it, vanish) and the resolution along the surface is coarser than h.
  // Counts are checked as numbers before they become integers (a patch of 1e80 mm would
  // overflow them); sizes that merely do not fit in memory are explained by check_memory.
  const double dy_target = h * std::max(std::cos(lambda_c), 0.5);
  for (const double cells : {size[0] / h, (y_hi - y_lo) / dy_target})
    if (!(cells < kMaxCells))
      throw InputError(region.where("size"), "region.size",
                       "the patch would be " + format_count(cells) +
                           " spacings long: expected fewer than 1e12 (shrink region.size or "
                           "raise region.spacing)");
  Grid& g = L.grid;
  g.nx = static_cast<std::size_t>(std::llround(size[0] / h)) + 1;
  g.dx = size[0] / static_cast<double>(g.nx - 1);
  g.x0 = x_c - size[0] / 2;
  g.ny = static_cast<std::size_t>(std::ceil((y_hi - y_lo) / dy_target)) + 1;
  if (g.ny >= 3) {
    g.dy = (y_hi - y_lo) / static_cast<double>(g.ny - 1);
    g.y0 = y_lo;
  } else {  // the patch projects to less than two rows: three rows around it
    g.ny = 3;
    g.dy = dy_target;
    g.y0 = 0.5 * (y_lo + y_hi) - dy_target;
  }
}

void LayoutSteps::request_passes() {
  // Only the ball's bottom, near the nominal contact point, leaves the final surface: a node is
  // finished by the nearest pass on either side and by the teeth passing it along the feed. So
  // the passes run from one step-over before the patch to one after, and each pass feeds from a
  // few feeds per revolution (and the depth, for the contact point's offset on a slope) before
  // the patch to as far after it, and past the grid's first row where that lies before the
  // patch (a patch of less than two rows). Never by a length tied to the spacing: the spindle is
  // at its start angle where a pass begins, so the run-in places the teeth's marks, and a surface
  // must not move when only its grid is refined (tests/integration/closed_form_test.cpp; the run
  // once held 2 spacings, which moved the marks by twice the change of spacing).
  const Grid& g = L.grid;
  run = 3 * fz * teeth + ap + 2 * (y_lo - g.y0);
  // A cutter with a ring leaves the final surface anywhere under its bottom or its ring: both its
  // leading and its trailing side (an insert's back-cutting) pass a node, a rim apart.
  if (tool.ring() > 0) run += rim;
  vf = fz * teeth * rpm / 60.0;
  omega = 2 * M_PI * rpm / 60.0 * (cut.string("spindle_direction") == "cw" ? -1.0 : 1.0);
  // The passes could be a step-over apart across the patch's width or along its arc.
  const double steps = std::max(size[0], L.s_hi - L.s_lo) / ae;
  if (!(steps < kMaxPasses))
    throw InputError(region.where("size"), "region.size",
                     "the patch would need " + format_count(steps) + " passes at a step-over of " +
                         format_number(ae) +
                         " mm: expected fewer than 1e7 (shrink region.size or raise "
                         "cutting.stepover)");
  check_layout_memory(steps, ae, cut);
  rq.surface = surface.get();
  rq.stepover = ae, rq.feed_speed = vf, rq.run = run;
  rq.radius = R, rq.offset = R - ap;
  // The grid is symmetric about x_c: its far side is -x0 exactly when that is 0.
  rq.x_lo = g.x0, rq.x_hi = x_c == 0 ? -g.x0 : x_c + size[0] / 2, rq.y_lo = y_lo, rq.y_hi = y_hi;
  rq.s_lo = L.s_lo, rq.s_hi = L.s_hi, rq.s_c = s_c, rq.y_c = y_c;
  rq.stop = &stop_flag();
  try {
    lines = path_model.passes(rq);
  } catch (const ParamError& e) {
    throw InputError(path_slot.params.where(e.key()), "path." + e.key(), e.what());
  }
  throw_if_interrupted();
  if (lines.empty()) throw defect("laid out no pass");
}

std::vector<ToolPath::Pass> LayoutSteps::to_passes() {
  // Evaluators may look two revolutions beyond a pass's ends (tooth_passage tabulates the centre
  // there), and the path is only defined over the surface: that reach must lie on it too. (With
  // 49 teeth on the paper's arc it did not: the centre was NaN there and tooth_passage's table
  // halved its step until memory ran out.)
  const FeedLimits feed_limits{vf * kMinFeedPerTooth / fz, vf * 2 * rim / fz};
  std::vector<ToolPath::Pass> passes;
  bool near_patch = false;  // some waypoint segment's box comes within R of the patch
  for (const PassLine& l : lines) {
    if (!l.points.empty()) {
      passes.push_back(
          waypoint_pass(l, feed_limits, [this](const std::string& what) { return defect(what); }));
      for (std::size_t k = 0; k + 1 < l.points.size(); ++k) {
        const Vec3 &a = l.points[k].at.centre, &b = l.points[k + 1].at.centre;
        near_patch =
            near_patch ||
            (std::max(a.x(), b.x()) > rq.x_lo - rim && std::min(a.x(), b.x()) < rq.x_hi + rim &&
             std::max(a.y(), b.y()) > y_lo - rim && std::min(a.y(), b.y()) < y_hi + rim);
      }
      continue;
    }
    near_patch = true;
    const double along_x = l.x1 - l.x0, along_y = l.y1 - l.y0;
    if (!(std::isfinite(along_x) && std::isfinite(along_y) && std::isfinite(l.phase) &&
          std::isfinite(l.posture.lead) && std::isfinite(l.posture.tilt)))
      throw defect("laid out a pass with a coordinate, phase or posture that is not finite");
    if ((along_x != 0) == (along_y != 0))
      throw defect("laid out a pass that is not along X or Y, or has no length");
    // One of the two is zero: the sum is the length exactly.
    ToolPath::Pass p{l.x0, l.y0, (std::abs(along_x) + std::abs(along_y)) / vf, l.phase, 0, 0,
                     {},   {}};
    p.dx = along_x > 0 ? 1 : along_x < 0 ? -1 : 0;
    p.dy = along_y > 0 ? 1 : along_y < 0 ? -1 : 0;
    p.posture = l.posture;
    passes.push_back(p);
    y_first = std::min({y_first, l.y0, l.y1}), y_last = std::max({y_last, l.y0, l.y1});
    if (along_y != 0) reach = 2 * fz * teeth;
  }
  if (!near_patch)
    throw InputError(place_at, place_name,
                     "no pass of the cutter-location data comes within the ball's radius of the "
                     "patch (x " +
                         format_number(rq.x_lo) + " to " + format_number(rq.x_hi) + " mm, y " +
                         format_number(y_lo) + " to " + format_number(y_hi) +
                         " mm): expected the patch where the data cuts");
  if (y_first - reach <= surface->y_min() || y_last + reach >= surface->y_max())
    throw InputError(
        place_at, place_name,
        std::string(by_centre ? "the patch there" : "the patch at this lambda") +
            ", with the tool's run-in and run-out, reaches past the end of the workpiece surface "
            "(the tool path runs " +
            format_number(run + reach) + " mm beyond each end of the patch, at " +
            format_number(fz * teeth) +
            " mm per revolution: three revolutions of run-in or run-out and the depth" +
            (reach > 0 ? std::string(", and two an evaluator may look beyond them") : "") +
            "); choose a smaller " + (by_centre ? "|y|" : "lambda") +
            ", a larger radius, or fewer teeth or a smaller feed");
  return passes;
}

void LayoutSteps::make_path(std::vector<ToolPath::Pass> passes) {
  for (double y : {y_first, y_lo, y_c, y_hi, y_last})
    if (std::isfinite(y)) L.lambda_max = std::max(L.lambda_max, std::abs(surface->inclination(y)));

  try {
    L.path = std::make_shared<ToolPath>(surface, R - ap, vf, omega, std::move(passes));
    L.path->set_ring(tool.ring());
    if (scene.has_table("runout")) {
      const Params& runout = scene.table("runout");
      const double e = runout.number("offset");
      if (e >= rim)
        throw InputError(runout.where("offset"), "runout.offset",
                         "a runout of " + format_number(e) + " mm is not below the tool's radius " +
                             format_number(rim) + " mm: expected a few micrometres");
      // Measured from tooth 1's zero-lag azimuth, turning with the spindle (its sense).
      const double sense = omega < 0 ? -1.0 : 1.0;
      L.path->set_runout({e, tool.tooth_angle(0) + sense * runout.number("angle") * kDeg,
                          runout.number("edge_radial_step"), runout.number("edge_axial_step")});
    }
  } catch (const std::invalid_argument& e) {
    throw defect(std::string("laid out passes the core cannot follow: ") + e.what());
  }
  if (!L.path->vertical()) check_posture(*L.path, tool, L, path_slot);
  check_waypoints(*L.path, lines, {rq.x_lo - rim, rq.x_hi + rim, y_lo - rim, y_hi + rim}, tool, L);
}

}  // namespace

Layout make_layout(const Scene& scene, const ToolGeometry& tool,
                   std::shared_ptr<const SurfaceShape> surface, const PathModel& path_model) {
  LayoutSteps steps(scene, tool, std::move(surface), path_model);
  steps.check_cut();
  steps.L.spacing = steps.h;
  steps.L.kappa = catw_kappa(steps.R, steps.ap, steps.r);
  steps.place_patch();
  steps.project_patch();
  steps.make_grid();
  steps.request_passes();
  steps.make_path(steps.to_passes());
  return steps.L;
}

}  // namespace topomill
