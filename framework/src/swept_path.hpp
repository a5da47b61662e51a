// What cutter-location data has cut before a moment: the ball swept along the centre's earlier
// path. The raster's passes are parallel lines and the force model's material test asks only
// for the previous one (pipeline.cpp); radial and spiral passes meet and wind around, so here
// every earlier pass counts, and the same pass's own earlier loops.
#pragma once

#include <utility>
#include <vector>

#include "topomill/tool_path.hpp"

namespace topomill {

class SweptPath {
 public:
  explicit SweptPath(const ToolPath& path);

  // The segments of the nominal centre's path (ends a, b) that come within `reach` of `centre`
  // and were travelled before pass p's time t less `recent` (the tool's own trail, which the
  // force model's chip already leaves out), on pass p or an earlier one. Edge points within R of
  // one of them were cut away.
  std::vector<std::pair<Vec3, Vec3>> before(std::size_t p, double t, double recent,
                                            const Vec3& centre, double reach) const;

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
