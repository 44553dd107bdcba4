// Before a Function is printed as a macro program: constant folding and the
// algebraic identities that cannot change a finite result (x+0, x*1, x*0,
// x/1), so the controller does not compute at run time what the compiler
// knows already. The result is a copy whose operands skip the folded
// instructions; the folded ones stay in place, unused.
#pragma once

#include "cncc/ir/ir.h"

namespace cncc::backends {

ir::Function simplifyForMacroProgram(const ir::Function& function);

} // namespace cncc::backends
