#include "jit_module.h"

#include "commands.h"

#include "cncc/backends/jit_module.h"
#include "cncc/ir/interpreter.h"

#include <dlfcn.h>

#include <filesystem>
#include <string>
#include <system_error>

namespace cncc::driver {

namespace {

#ifdef CNCC_JIT_MODULE_NAME
// The module beside the running executable (not on the library path: the
// one built with this executable).
backends::JitModuleEntry loadEntry() {
  std::error_code error;
  std::filesystem::path executable = std::filesystem::read_symlink("/proc/self/exe", error);
  if (error) {
    return nullptr;
  }
  std::filesystem::path module = executable.parent_path() / CNCC_JIT_MODULE_NAME;
  // Never closed: LLVM stays loaded until the process exits.
  void* handle = dlopen(module.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (handle == nullptr) {
    return nullptr;
  }
  return reinterpret_cast<backends::JitModuleEntry>(dlsym(handle, backends::jitModuleEntryName));
}
#else
backends::JitModuleEntry loadEntry() {
  return nullptr;
}
#endif

backends::JitModuleEntry moduleEntry() {
  static const backends::JitModuleEntry entry = loadEntry();
  return entry;
}

} // namespace

std::optional<ir::ToolPath> runOnJit(const ir::Function& function) {
  backends::JitModuleEntry entry = moduleEntry();
  if (entry == nullptr) {
    return std::nullopt;
  }
  ir::ToolPath path;
  std::string error;
  switch (entry(function, path, error)) {
  case backends::JitModuleStatus::Ran:
    return path;
  case backends::JitModuleStatus::Unavailable:
    return std::nullopt;
  case backends::JitModuleStatus::RunError:
    throw ir::InterpreterError(error);
  case backends::JitModuleStatus::CompileError:
  case backends::JitModuleStatus::OtherError:
    break;
  }
  throw InternalError("the LLVM JIT failed: " + error);
}

} // namespace cncc::driver
