// The interpreter's arithmetic, for folding: the same library calls on the
// same doubles, so a folded constant is the value the interpreter would
// have computed at run time, bit for bit.
#pragma once

#include "cncc/ir/ir.h"

#include <optional>
#include <vector>

namespace cncc::ir::passes {

// The result of a pure operation on constant operands (bools as 0 and 1);
// nullopt for table.load with an index the interpreter rejects, and for an
// operation without a fixed result.
std::optional<double> evaluate(const Function& function, const Instruction& instruction,
                               const std::vector<double>& operands);

} // namespace cncc::ir::passes
