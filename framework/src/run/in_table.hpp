// A model's ParamError, raised while it works (not only when it is made), named at its scene
// table's key: InputError, exit 2, the file, line and column of the key.
#pragma once

#include "scene.hpp"
#include "topomill/error.hpp"

namespace topomill {

template <class F>
auto in_table(const SlotTable& table, F&& f) {
  try {
    return f();
  } catch (const ParamError& e) {
    throw InputError(table.params.has(e.key()) ? table.params.where(e.key()) : table.where,
                     table.table + "." + e.key(), e.what());
  }
}

}  // namespace topomill
