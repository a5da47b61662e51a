// What cutter-location data has cut before a moment: the ball swept along the centre's earlier
// path. The raster's passes are parallel lines and the force model's material test asks only
// for the previous one (pipeline.cpp); radial and spiral passes meet and wind around, so here
// every earlier pass counts, and the same pass's own earlier loops.
#pragma once

#include <vector>

#include "topomill/tool_path.hpp"

namespace topomill {

class SweptPath {
 public:
  explicit SweptPath(const ToolPath& path);

  // Whether x lies within R of a segment of the nominal centre's path travelled before pass p's
  // time `until` (the tool's own trail, which the force model's chip already leaves out, is
  // after it), on pass p or an earlier one: then the ball swept it away. Asked per edge point,
  // so nothing is kept per moment (a force sample's test holds only where and when it is: a
  // list of the segments near each sample took 8 GB for the radial-then-spiral example with
  // effects), and chunks whose box lies R or more away are passed over whole.
  bool swept(std::size_t p, double until, const Vec3& x, double R) const;

  // Distance from x to the segment [a, b].
  static double distance(const Vec3& x, const Vec3& a, const Vec3& b);

 private:
  struct Segment {
    Vec3 a, b;
    std::size_t pass;
    double t_end;  // when the centre leaves b
  };
  // Runs of up to kChunk consecutive segments of one pass, with their box, so that a query
  // looks at a segment only when its chunk's box is near.
  struct Chunk {
    std::size_t first, last;  // [first, last) into segments_
    Vec3 lo, hi;
  };
  static constexpr std::size_t kChunk = 32;
  std::vector<Segment> segments_;
  std::vector<Chunk> chunks_;
};

}  // namespace topomill
