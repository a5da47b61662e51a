#include "io/cl_csv.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "io/atomic_file.hpp"
#include "topomill/surface_shape.hpp"

namespace topomill {

namespace {

struct Point {
  double t;
  Vec3 centre, axis;
};

// The centre on the spindle's axis (the runout is the scene's [runout], not the path's).
Vec3 spindle_centre(const ToolPath& path, std::size_t p, double t) {
  return path.nominal_centre(p, t) - path.runout_offset(p, t);
}

// A pass's points: its waypoints; a line over a plate, its ends; a line over a curve, times
// close enough that each chord sags at most `sag` from the path (a circle of radius rho sags
// c^2 / 8 rho under a chord c).
std::vector<Point> pass_points(const ToolPath& path, std::size_t p, double sag) {
  const ToolPath::Pass& pass = path.pass(p);
  std::vector<Point> out;
  if (!pass.waypoints.empty()) {
    for (std::size_t k = 0; k < pass.waypoints.size(); ++k)
      out.push_back({path.waypoint_time(p, k), pass.waypoints[k].centre, pass.waypoints[k].axis});
    return out;
  }
  const double r = std::abs(path.surface().curvature_radius());
  std::size_t n = 1;
  if (std::isfinite(r)) {
    const double bend = std::max(r - path.offset(), 1e-3);  // the centre's curve, at its tightest
    double length = 0;  // of the centre's curve: its chords at 64 steps (short of it by far less
    Vec3 prev = spindle_centre(path, p, 0);  // than the chord's margin below)
    for (int k = 1; k <= 64; ++k) {
      const Vec3 c = spindle_centre(path, p, pass.t_end * k / 64);
      length += (c - prev).norm(), prev = c;
    }
    n = static_cast<std::size_t>(std::ceil(length / std::sqrt(8 * bend * sag)));
  }
  for (std::size_t k = 0; k <= n; ++k) {
    const double t = k == n ? pass.t_end : pass.t_end * static_cast<double>(k) / n;
    out.push_back({t, spindle_centre(path, p, t), path.axis(p, t)});
  }
  return out;
}

std::string number(double v) {
  return exact_text(v == 0 ? 0.0 : v);  // no "-0"
}

}  // namespace

void write_cl_csv(const std::string& file, const ToolPath& path, const FileInfo& info, double sag) {
  std::vector<std::vector<Point>> passes;
  // The feed column is needed where a segment's length over the scene's feed is not its time.
  bool feeds = false;
  for (std::size_t p = 0; p < path.passes(); ++p) {
    passes.push_back(pass_points(path, p, sag));
    const auto& q = passes.back();
    for (std::size_t k = 1; k < q.size(); ++k)
      feeds = feeds ||
              (q[k].centre - q[k - 1].centre).norm() / path.feed_speed() != q[k].t - q[k - 1].t;
  }
  const bool axes = !path.vertical();
  const double deg = 180 / M_PI;
  write_atomically(file, [&](std::ostream& out) {
    out << "# " << one_line(info.title) << "\n# " << one_line(info.description) << "\n# "
        << file_creator() << ", " << iso8601_utc(created_time(info)) << "\n"
        << "# The ball centre on the spindle's axis (mm), a blank line between passes. Read it "
           "with [path] plugin = \"cl_file\", point = \"centre\", start_angle = "
        << number(path.pass(0).phase * deg) << ", phase_shift = "
        << number(path.passes() > 1 ? (path.pass(1).phase - path.pass(0).phase) * deg : 0.0)
        << " (deg), and the scene's [runout] if it has one.\n"
        << "x,y,z" << (axes ? ",i,j,k" : "") << (feeds ? ",f" : "") << "\n";
    for (const auto& q : passes) {
      for (std::size_t k = 0; k < q.size(); ++k) {
        const Point& a = q[k];
        out << number(a.centre.x()) << "," << number(a.centre.y()) << "," << number(a.centre.z());
        if (axes)
          out << "," << number(a.axis.x()) << "," << number(a.axis.y()) << ","
              << number(a.axis.z());
        if (feeds) {  // the move to this point (to the next, for the first)
          const std::size_t j = std::max<std::size_t>(k, 1);
          out << "," << number((q[j].centre - q[j - 1].centre).norm() / (q[j].t - q[j - 1].t) * 60);
        }
        out << "\n";
      }
      out << "\n";
    }
  });
}

}  // namespace topomill
