// What the CL tests share: a small scene on a plate or an arc (or the paper's tool and cut), a
// path's passes written as cutter-location data (CSV or APT) at known times, and the largest
// difference of two maps.
#pragma once

#include <string>
#include <vector>

#include "run/pipeline.hpp"
#include "scene.hpp"
#include "topomill/tool_path.hpp"

namespace testing::cl {

inline const std::string kPlate = "plugin = 'inclined_plane'";
inline const std::string kArc = "plugin = 'convex_arc'\nradius = 20.0";

// A vertical ball end (R 1 mm, two teeth, helix 20 deg) on `workpiece` with `path` as the
// [path] table; `paper`: the paper's tool and cut (R 5 mm, fz 0.1, ae 0.3, ap 0.1), for which
// the effects' tables (testing::dynamics_tables) are made.
std::string scene(const std::string& workpiece, const std::string& path, double spacing,
                  double size, const std::string& place = "lambda = 0.0", bool paper = false);
topomill::Prepared prepared(const std::string& toml, const std::vector<std::string>& set = {});
// This run's folder for CL files.
std::string cl_dir();
// A [path] table reading `file` as ball centres or tool tips.
std::string cl_path(const std::string& file, const std::string& point = "centre");
// A pass's ball centre without the runout (the CL data locate the spindle's axis).
topomill::Vec3 spindle_centre(const topomill::ToolPath& path, std::size_t p, double t);
// Writes `path`'s passes as CL data, `points` per pass evenly in time, with the axis when
// `axes`: CSV (a blank line between passes) or APT (RAPID before each pass's first point). With
// `feeds` (CSV) each point carries the feed of the move to it, its chord over its time.
std::string write_cl(const topomill::ToolPath& path, int points, bool axes, bool apt,
                     const std::string& name, bool feeds = false);
double largest_difference(const topomill::HeightMap& a, const topomill::HeightMap& b);

}  // namespace testing::cl
