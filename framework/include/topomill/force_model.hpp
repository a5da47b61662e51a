// Slot: cutting force from the tool state (docs/model.md Eq. 18-21).
#pragma once

#include "topomill/cut_state.hpp"
#include "topomill/model.hpp"
#include "topomill/tool_geometry.hpp"

namespace topomill {

class TOPOMILL_API ForceModel : public Model {
 public:
  virtual CuttingForce evaluate(const ToolGeometry& tool, const CutState& state) const = 0;
};

template <>
struct SlotOf<ForceModel> {
  static constexpr Slot value = Slot::ForceModel;
};

}  // namespace topomill
