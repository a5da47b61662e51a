// A simulated surface set beside a measured one (`topomill compare`): both on a common grid, the
// measurement registered onto the simulation, the difference, and each one's parameters and
// dominant periods over the area they share. The processing before (form removal, filters) is the
// caller's, the same for both.
#pragma once

#include <string>
#include <vector>

#include "metrology/parameters.hpp"
#include "metrology/registration.hpp"
#include "metrology/surface.hpp"

namespace topomill {

struct CompareSettings {
  std::vector<std::string> names;  // parameters to report (select_parameters)
  ParameterSettings parameters;
  RegistrationOptions registration;  // its angle_guess is found from the lays when rotation is on
};

// What a surface's spectrum says of its marks.
struct Lay {
  double std_deg = 0;         // Std: the direction the marks' waves run in
  double lay_deg = 0;         // the marks themselves: Std + 90, in [0, 180)
  double across_mm = 0;       // the dominant period across the lay (along Std)
  double along_mm = 0;        // ... and along it
  double x_mm = 0, y_mm = 0;  // along X and along Y
};
Lay lay_of(const Surface& s);

struct Comparison {
  double dx = 0, dy = 0;  // the common grid's spacing (mm)
  std::string interpolation;
  Surface sim, meas;  // on the common grid; meas in its own frame
  Registration registration;
  Surface aligned;      // the measurement in the simulation's frame and grid, less the offset
  Surface difference;   // aligned - sim where both are valid
  Surface sim_overlap;  // the simulation where the aligned measurement is valid
  ParameterValues sim_parameters, meas_parameters;  // over the overlap
  Lay sim_lay, meas_lay;
  double overlap_share = 0;  // of the simulation's valid nodes
};

// Throws InputError (naming the file at fault) for inputs that cannot be compared: spacings more
// than 8 times apart, a map narrower than 4 nodes either way on the common grid (a profile), a
// flat map, heights more than 100 times apart in Sq (units that do not match), no overlap after
// registration.
Comparison compare_surfaces(const Surface& sim, const Surface& meas, const CompareSettings& s);

}  // namespace topomill
