// LinuxCNC's o-word programs as a dialect of the macro family: the table
// the macro printer prints them by, and the register allocator's view of
// their expressions.
#pragma once

#include "macro_dialect.h"

#include "cncc/ir/register_allocation.h"

#include <span>
#include <vector>

namespace cncc::backends {

// `coordinateDecimals`: of a literal coordinate (more in inches).
MacroDialect linuxcncDialect(int coordinateDecimals);

// How long a value's inline text would be (LinuxCNC has no small
// bracket-nesting limit; the line length is what counts).
ir::InlineShape linuxcncInlineShape(const ir::Function& function,
                                    const ir::Instruction& instruction,
                                    std::span<const ir::InlineShape> operands);

// Opcodes that take statements of their own: min, max, select, rem.
std::vector<ir::Opcode> linuxcncStatementOpcodes();

} // namespace cncc::backends
