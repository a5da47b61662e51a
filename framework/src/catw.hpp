// Contact area between tool and workpiece, CATW (docs/model.md Eq. 39-42).
#pragma once

namespace topomill {

// Depth H3H4 of the intersection chord below the uncut surface, for a ball of radius R whose
// centre is R - ap from the surface, on a surface of signed curvature radius r (> 0 convex,
// < 0 concave, infinite flat): (2 r ap - ap^2) / (2 (R - ap + r)), computed through 1/r so that
// the flat limit is exactly ap.
double catw_chord_depth(double R, double ap, double r);

// Half-width kappa = arccos(O1H3 / R) of the contact angle range, rad.
double catw_kappa(double R, double ap, double r);

}  // namespace topomill
