// The edge elements of one tooth that cut in steady side-by-side passes, for the linear stability
// analysis (topomill lobes): a vertical tool on a level floor, feeding along `feed`, the uncut
// material on the `side` of the pass (the next pass's side) with `stepover` of it left by the
// last pass, `depth` deep from the tool's lowest point.
//
// An element at polar angle alpha of the section (docs/model.md, "Cutters"), azimuth psi, has the
// outward normal n = (sin a cos psi, sin a sin psi, -cos a) and meridian tangent a = (cos a cos
// psi, cos a sin psi, sin a). It cuts where it is in material: it faces the feed (feed . n > 0: a
// chip), lies no higher than `depth` above the tool's lowest point, and is not where the last pass
// already cut, whose tool removed everything within the element's own radius rho of its line at
// that height: (side . position) >= rho - stepover. Both conditions are arcs of psi; their common
// arc, relative to the feed's azimuth, is [lo, hi].
//
// Left out, and said so in docs/stability.md: the flat bottom's elements (their chip is the
// axial vibration alone, no static chip), an insert's inner side, posture and curvature.
#pragma once

#include <vector>

#include "topomill/tool_geometry.hpp"

namespace topomill::stability {

struct CuttingElement {
  double psi0;          // azimuth (rad) of tooth 0's element at spindle angle 0
  double sin_a, cos_a;  // the section's normal angle
  double width;         // chip width: the element's length along the section (mm)
  double lo, hi;        // the arc of (psi - feed azimuth) in which it cuts, within [-pi/2, pi/2]
};

struct Engagement {
  double feed_azimuth;     // rad
  int side;                // +1: the uncut material lies at +90 deg from the feed, -1 at -90 deg
  double stepover, depth;  // mm
};

// One tooth's elements: the section's from its lowest point up, `per_mm` of them per mm of its
// length (at least 16), and the side edge's above the tube's centre plane up to `depth`, each
// turning the lag by at most half a degree (one for a straight flute). Elements that never cut
// are left out.
std::vector<CuttingElement> cutting_elements(const ToolGeometry& tool, const Engagement& e,
                                             double per_mm);

}  // namespace topomill::stability
