// Checks the IR's rules; run after every pass in tests.
#pragma once

#include "cncc/ir/ir.h"

#include <string>
#include <vector>

namespace cncc::ir {

// Every operand is defined before its use, in the same region or one that
// encloses it (a loop's induction variable only in its body); operand
// counts and types match the operation; tables and parameters exist; every
// instruction sits in exactly one region. Returns the problems found.
std::vector<std::string> verifyFunction(const Function& function);

} // namespace cncc::ir
