// LLVM's O2 pipeline (new pass manager), tuned for the machine the code
// will run on.
#pragma once

namespace llvm {
class Module;
class TargetMachine;
} // namespace llvm

namespace cncc::backends::jit {

void optimiseModule(llvm::Module& module, llvm::TargetMachine& machine);

} // namespace cncc::backends::jit
