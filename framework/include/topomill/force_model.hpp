// Slot: cutting force from the tool state (docs/model.md Eq. 18-21).
#pragma once

#include <limits>

#include "topomill/cut_state.hpp"
#include "topomill/model.hpp"
#include "topomill/tool_geometry.hpp"

namespace topomill {

// The part of a force law proportional to the chip, per unit chip area (N/mm^2): what the linear
// stability analysis (topomill lobes) reads. Edge (ploughing) terms do not depend on the chip's
// thickness and do not enter it.
struct ChipCoefficients {
  double tangential, radial, axial;
};

class TOPOMILL_API ForceModel : public Model {
 public:
  virtual CuttingForce evaluate(const ToolGeometry& tool, const CutState& state) const = 0;
  // NaN where the model's force is not proportional to the chip (no linear stability analysis).
  virtual ChipCoefficients chip_coefficients() const {
    constexpr double kNone = std::numeric_limits<double>::quiet_NaN();
    return {kNone, kNone, kNone};
  }
};

template <>
struct SlotOf<ForceModel> {
  static constexpr Slot value = Slot::ForceModel;
};

}  // namespace topomill
