// Least-squares form removal of measured surfaces: plane, polynomial of total order N, and an
// arc (a cylinder with its axis along X, convex or concave), over the valid points.
#pragma once

#include <string>

#include "metrology/surface.hpp"

namespace topomill {

struct Form {
  enum class Kind { None, Plane, Polynomial, Arc } kind = Kind::None;
  int order = 1;  // Polynomial

  // "none", "plane", "poly:N" (N = 1..6), "arc"; throws InputError naming `option` otherwise.
  static Form parse(const std::string& text, const std::string& option);
  std::string name() const;
};

// The residual heights (mm): the map minus the fitted form; for the arc, the signed distance from
// the fitted circle along its radius (outward positive). Invalid points stay as they are.
Surface remove_form(const Surface& surface, const Form& form);

}  // namespace topomill
