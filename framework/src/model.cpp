#include "topomill/model.hpp"

namespace topomill {

// Out of line so that Model's vtable and type information live once, in the core library.
Model::~Model() = default;

const char* slot_name(Slot slot) {
  switch (slot) {
    case Slot::ToolGeometry:
      return "tool geometry";
    case Slot::SurfaceShape:
      return "surface shape";
    case Slot::ForceModel:
      return "force model";
    case Slot::DynamicsModel:
      return "dynamics model";
    case Slot::Deformation:
      return "deformation";
    case Slot::Evaluator:
      return "topography evaluator";
    case Slot::Path:
      return "tool path";
  }
  return "?";
}

const char* slot_id(Slot slot) {
  switch (slot) {
    case Slot::ToolGeometry:
      return "tool_geometry";
    case Slot::SurfaceShape:
      return "surface_shape";
    case Slot::ForceModel:
      return "force_model";
    case Slot::DynamicsModel:
      return "dynamics_model";
    case Slot::Deformation:
      return "deformation";
    case Slot::Evaluator:
      return "topography_evaluator";
    case Slot::Path:
      return "tool_path";
  }
  return "?";
}

std::vector<Slot> all_slots() {
  return {Slot::ToolGeometry,  Slot::SurfaceShape, Slot::Path,     Slot::ForceModel,
          Slot::DynamicsModel, Slot::Deformation,  Slot::Evaluator};
}

}  // namespace topomill
