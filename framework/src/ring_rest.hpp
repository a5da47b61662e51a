// Where a cutter with a ring sits over a curved surface. Its solid is a tube of radius r round a
// ring of radius c (tool_geometry.hpp): the points within r of the ring (with an end mill's flat
// bottom, of the disc the ring bounds, whose nearest point to a surface is on its rim: a signed
// distance has no stationary point inside a region). The cutter is set as the ball is, its centre
// on the outward normal through the foot point, at the distance s that takes its deepest point ap
// below the surface along the normal: the ring's nearest point lies r - ap from the surface.
//
// On a plane that is the tangent plane's closed form, s = (r - ap) + c |n x a|. Over a curve the
// ring's nearest point moves off the tangent plane, and s is found here: the least signed
// distance over the ring by sampling and Brent's method about each sampled minimum (no bracket
// straddling a fold of the ring seen along X: Ring in ring_rest.cpp), and s by the secant method
// from the tangent plane's s (the least distance moves at the cosine between the normals at the
// foot and at the nearest point: close to 1).
#pragma once

#include "topomill/surface_shape.hpp"
#include "topomill/types.hpp"

namespace topomill::detail {

// The distance s (mm) along the outward normal at the foot point `y` from the surface to the
// centre of a ring of radius `ring` about the unit `axis` whose nearest point lies `clearance`
// (r - ap) from the surface. Throws std::runtime_error where no s is found (a ring that hangs
// off the surface's end, where its distance stops growing with s).
double ring_rest(const SurfaceShape& surface, double y, const Vec3& axis, double ring,
                 double clearance);

}  // namespace topomill::detail
