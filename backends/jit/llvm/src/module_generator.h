// Translates an IR Function into an LLVM module holding one function,
// `int32 cncc_part(const double* parameters, RunContext*, uint64 maximumSteps)`
// (see jit_runtime.h). Every value is an f64, as in the interpreter (bools are
// 0 and 1); loops and ifs become basic blocks; tables become constant global
// arrays; effects and errors become calls of the runtime's callbacks.
#pragma once

#include "cncc/ir/ir.h"

#include <memory>
#include <string>
#include <vector>

namespace llvm {
class LLVMContext;
class Module;
} // namespace llvm

namespace cncc::backends::jit {

struct GeneratedModule {
  std::unique_ptr<llvm::Module> module;
  // The comment texts, by the index the code passes to cncc_jit_comment.
  std::vector<std::string> comments;
};

// The function must verify (ir::verifyFunction).
GeneratedModule generateModule(const ir::Function& function, llvm::LLVMContext& context);

} // namespace cncc::backends::jit
