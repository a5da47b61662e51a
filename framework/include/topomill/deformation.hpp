// Slot: a quasi-static path correction (tool deflection, surface springback; Eq. 27-31).
#pragma once

#include "topomill/cut_state.hpp"
#include "topomill/model.hpp"
#include "topomill/tool_geometry.hpp"

namespace topomill {

class TOPOMILL_API Deformation : public Model {
 public:
  // Translation (du, dv, dw) in mm to add to the tool path at this instant (Eq. 32-33).
  virtual Vec3 correction(const CuttingForce& force, const ToolGeometry& tool,
                          const CutState& state) const = 0;
};

template <>
struct SlotOf<Deformation> {
  static constexpr Slot value = Slot::Deformation;
};

}  // namespace topomill
