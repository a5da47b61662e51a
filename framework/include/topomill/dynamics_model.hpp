// Slot: the structure's vibration under the cutting force (docs/model.md Eq. 17, 22-26).
#pragma once

#include <limits>
#include <vector>

#include "topomill/model.hpp"
#include "topomill/types.hpp"

namespace topomill {

// One mode of the structure along a workpiece axis: natural frequency (rad/s), damping ratio and
// modal stiffness (N/m); the axis's displacement is the sum of its modes'.
struct ModalMode {
  int axis;  // 0 x, 1 y, 2 z
  double omega, damping, stiffness;
};

class TOPOMILL_API DynamicsModel : public Model {
 public:
  // Displacement (mm, CS2) at each sample of a force history (N) sampled every `dt` seconds,
  // starting from rest. The force is held constant over each step.
  virtual std::vector<Vec3> respond(const std::vector<Vec3>& force, double dt) const = 0;
  // Largest stable step (s) of the scheme for this model's modes; +infinity when unconditional.
  // The core refuses a larger step with a message naming the limit, or sub-steps on request.
  virtual double max_stable_step() const { return std::numeric_limits<double>::infinity(); }
  // The step (s) this model wants for accuracy (e.g. a fraction of its fastest mode's period); the
  // core samples forces and the response at the smaller of this and its own force resolution.
  virtual double suggested_step() const { return std::numeric_limits<double>::infinity(); }
  // The modes, where the model is modal (the linear stability analysis, topomill lobes, needs
  // them); empty otherwise.
  virtual std::vector<ModalMode> modes() const { return {}; }
};

template <>
struct SlotOf<DynamicsModel> {
  static constexpr Slot value = Slot::DynamicsModel;
};

}  // namespace topomill
