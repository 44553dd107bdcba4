// The entry point of the loadable JIT module (cncc/backends/jit_module.h).
// Also built into the static cncc_jit, where nothing calls it.
#include "cncc/backends/jit_module.h"

#include "cncc/backends/jit_compiler.h"
#include "cncc/ir/interpreter.h"

#include <exception>
#include <type_traits>

extern "C" cncc::backends::JitModuleStatus
cncc_jit_module_run_v1(const cncc::ir::Function& function, cncc::ir::ToolPath& path,
                       std::string& error) noexcept {
  using cncc::backends::JitModuleStatus;
  static_assert(std::is_same_v<decltype(&cncc_jit_module_run_v1), cncc::backends::JitModuleEntry>);
  try {
    if (!cncc::backends::jitAvailable()) {
      return JitModuleStatus::Unavailable;
    }
    path = cncc::backends::runJit(function);
    return JitModuleStatus::Ran;
  } catch (const cncc::backends::JitError& failure) {
    error = failure.what();
    return JitModuleStatus::CompileError;
  } catch (const cncc::ir::InterpreterError& failure) {
    error = failure.what();
    return JitModuleStatus::RunError;
  } catch (const std::exception& failure) {
    error = failure.what();
  } catch (...) {
    error = "an exception that is not a std::exception";
  }
  return JitModuleStatus::OtherError;
}
