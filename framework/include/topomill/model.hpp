// The common base of everything a plugin makes, and the seven slots a model can fill.
#pragma once

#include <string>
#include <vector>

#include "topomill/export.hpp"

namespace topomill {

// Every slot interface derives from Model so that the host can own any model through one
// type and keep its library loaded for as long as the object lives.
class TOPOMILL_API Model {
 public:
  virtual ~Model();
};

// New slots go at the end: a slot's number is part of the plugin ABI.
enum class Slot {
  ToolGeometry,
  SurfaceShape,
  ForceModel,
  DynamicsModel,
  Deformation,
  Evaluator,
  Path
};

// "tool geometry", "surface shape", ... for messages.
TOPOMILL_API const char* slot_name(Slot slot);
// "tool_geometry", ... for JSON and the command line.
TOPOMILL_API const char* slot_id(Slot slot);
TOPOMILL_API std::vector<Slot> all_slots();

// The slot type behind each enum value, used by Registrar::add<Interface, Impl>.
template <class Interface>
struct SlotOf;

}  // namespace topomill
