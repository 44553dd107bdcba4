// How deep and long a value's inline Custom Macro B text would be, for the
// register allocator: the rules MacroExpressionWriter prints by (functions,
// then * /, then + -; SIN/COS/TAN take degrees, ASIN/ACOS give them).
#pragma once

#include "cncc/backends/controller_profile.h"
#include "cncc/ir/register_allocation.h"

#include <span>

namespace cncc::backends {

// The shape with `operations` counted as the characters of the text but
// its variables' names (the allocator adds those), for the block length
// limit.
ir::InlineShape macroInlineShape(const ControllerProfile& profile, const ir::Function& function,
                                 const ir::Instruction& instruction,
                                 std::span<const ir::InlineShape> operands);
ir::InlineShape macroInlineShape(const ir::Function& function, const ir::Instruction& instruction,
                                 std::span<const ir::InlineShape> operands);

} // namespace cncc::backends
