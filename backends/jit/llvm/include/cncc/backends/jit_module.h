// The LLVM JIT as a loadable module (cncc_jit.so beside the cncc executable),
// so that only a program that runs the JIT loads LLVM. The module holds the
// JIT alone: it takes cncc_ir's symbols from the executable that loads it,
// which exports them. One extern "C" entry point, looked up by name, runs a
// Function as backends::runJit does; no exception crosses it.
#pragma once

#include "cncc/ir/ir.h"
#include "cncc/ir/tool_path.h"

#include <string>

namespace cncc::backends {

enum class JitModuleStatus : int {
  Ran,          // the tool path is filled in
  Unavailable,  // LLVM cannot generate code for this host (jitAvailable())
  CompileError, // a JitError; its text is in `error`
  RunError,     // an ir::InterpreterError; its text is in `error`
  OtherError,   // any other exception; its text is in `error`
};

// The entry point's type; the module defines it under jitModuleEntryName.
using JitModuleEntry = JitModuleStatus (*)(const ir::Function& function, ir::ToolPath& path,
                                           std::string& error) noexcept;
// Versioned: a module from another build of the interface is not used.
inline constexpr const char* jitModuleEntryName = "cncc_jit_module_run_v1";

} // namespace cncc::backends

// The entry point (a JitModuleEntry): runs `function` with its parameters'
// defaults, as backends::runJit(function) does, into `path`.
extern "C" cncc::backends::JitModuleStatus
cncc_jit_module_run_v1(const cncc::ir::Function& function, cncc::ir::ToolPath& path,
                       std::string& error) noexcept;
