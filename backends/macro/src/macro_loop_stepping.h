// Loop stepping for the macro printers: a loop whose index is only used
// scaled (a curve's parameter u = i * c) gets u itself in its variable,
// stepped by c, which saves a multiplication and an assignment per point.
#pragma once

#include "cncc/ir/ir.h"
#include "cncc/ir/register_allocation.h"

#include <cstdint>
#include <map>
#include <set>

namespace cncc::backends {

// The loops stepped so, and the products they replace.
struct SteppedLoops {
  // loop index value -> c; NaN: u = i / high, the loop from 1 to high.
  std::map<std::uint32_t, double> scaleOfIndex;
  std::set<std::uint32_t> scaledValues; // the products, not printed
};

// Finds the loops and rewrites `allocation`: each product shares its loop
// index's variable, and the used variables are counted again.
SteppedLoops stepLoopsByTheirScale(const ir::Function& function, ir::Allocation& allocation);

} // namespace cncc::backends
