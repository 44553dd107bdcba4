// The LLVM JIT for the driver: loaded from its module (cncc_jit.so, built
// beside the executable when LLVM 14 was found) the first time a part runs
// natively, so that the commands that do not run it never load LLVM.
#pragma once

#include "cncc/ir/ir.h"
#include "cncc/ir/tool_path.h"

#include <optional>

namespace cncc::driver {

// The function run by the LLVM JIT: nullopt when there is no JIT (the module
// was not built, is missing or does not load, or LLVM cannot generate code
// for this host), for the caller to interpret it instead. Throws
// InternalError when the JIT fails and ir::InterpreterError for the errors
// the interpreter would report.
std::optional<ir::ToolPath> runOnJit(const ir::Function& function);

} // namespace cncc::driver
