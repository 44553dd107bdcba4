#include "cncc/backends/jit_compiler.h"

#include "jit_runtime.h"
#include "module_generator.h"
#include "optimiser.h"

#include "cncc/ir/verifier.h"

#include <llvm/ExecutionEngine/Orc/ExecutionUtils.h>
#include <llvm/ExecutionEngine/Orc/JITTargetMachineBuilder.h>
#include <llvm/ExecutionEngine/Orc/LLJIT.h>
#include <llvm/ExecutionEngine/Orc/ThreadSafeModule.h>
#include <llvm/IR/LLVMContext.h>
#include <llvm/IR/Module.h>
#include <llvm/IR/Verifier.h>
#include <llvm/Support/TargetSelect.h>
#include <llvm/Support/raw_ostream.h>
#include <llvm/Target/TargetMachine.h>

#include <atomic>

namespace cncc::backends {

namespace {

std::string describe(llvm::Error error) {
  return llvm::toString(std::move(error));
}

template <typename T> T orThrow(llvm::Expected<T> expected, const char* doing) {
  if (!expected) {
    throw JitError(std::string(doing) + ": " + describe(expected.takeError()));
  }
  return std::move(*expected);
}

void orThrow(llvm::Error error, const char* doing) {
  if (error) {
    throw JitError(std::string(doing) + ": " + describe(std::move(error)));
  }
}

// The callbacks and libm functions by address; anything else the optimiser
// introduces (such as sincos) from the process itself.
void defineRuntimeSymbols(llvm::orc::LLJIT& jit) {
  llvm::orc::SymbolMap symbols;
  for (const jit::RuntimeSymbol& symbol : jit::runtimeSymbols()) {
    symbols[jit.mangleAndIntern(llvm::StringRef(symbol.name.data(), symbol.name.size()))] =
        llvm::JITEvaluatedSymbol(llvm::pointerToJITTargetAddress(symbol.address),
                                 llvm::JITSymbolFlags::Exported | llvm::JITSymbolFlags::Callable);
  }
  llvm::orc::JITDylib& library = jit.getMainJITDylib();
  orThrow(library.define(llvm::orc::absoluteSymbols(std::move(symbols))),
          "cannot define the runtime symbols");
  library.addGenerator(orThrow(llvm::orc::DynamicLibrarySearchGenerator::GetForCurrentProcess(
                                   jit.getDataLayout().getGlobalPrefix()),
                               "cannot search the process for symbols"));
}

std::unique_ptr<llvm::Module> optimisedModule(const ir::Function& function,
                                              llvm::LLVMContext& context,
                                              llvm::orc::JITTargetMachineBuilder machineBuilder,
                                              std::vector<std::string>& comments) {
  jit::GeneratedModule generated = jit::generateModule(function, context);
  comments = std::move(generated.comments);
  llvm::Module& module = *generated.module;
  std::string problems;
  llvm::raw_string_ostream problemStream(problems);
  if (llvm::verifyModule(module, &problemStream)) {
    throw JitError("the generated LLVM IR does not verify: " + problemStream.str());
  }
  std::unique_ptr<llvm::TargetMachine> machine =
      orThrow(machineBuilder.createTargetMachine(), "cannot create the target machine");
  module.setDataLayout(machine->createDataLayout());
  module.setTargetTriple(machine->getTargetTriple().str());
  jit::optimiseModule(module, *machine);
  return std::move(generated.module);
}

} // namespace

bool jitAvailable() {
  static const bool available = [] {
    return !llvm::InitializeNativeTarget() && !llvm::InitializeNativeTargetAsmPrinter();
  }();
  return available;
}

struct CompiledFunction::Compiled {
  std::unique_ptr<llvm::orc::LLJIT> jit;
  jit::EntryFunction entry = nullptr;
  std::vector<ir::Parameter> parameters;
  std::vector<std::string> comments;
  std::vector<std::vector<double>> tables;
  std::atomic<std::size_t> lastEventCount = 0;
};

CompiledFunction::CompiledFunction(const ir::Function& function)
    : compiled_(std::make_unique<Compiled>()) {
  if (!jitAvailable()) {
    throw JitError("LLVM cannot generate code for this host");
  }
  std::vector<std::string> problems = ir::verifyFunction(function);
  if (!problems.empty()) {
    throw JitError("the IR does not verify: " + problems.front());
  }
  compiled_->parameters = function.parameters;
  compiled_->tables = function.tables;

  llvm::orc::JITTargetMachineBuilder machineBuilder =
      orThrow(llvm::orc::JITTargetMachineBuilder::detectHost(), "cannot detect the host");
  machineBuilder.setCodeGenOptLevel(llvm::CodeGenOpt::Default);
  auto context = std::make_unique<llvm::LLVMContext>();
  std::unique_ptr<llvm::Module> module =
      optimisedModule(function, *context, machineBuilder, compiled_->comments);

  compiled_->jit =
      orThrow(llvm::orc::LLJITBuilder().setJITTargetMachineBuilder(machineBuilder).create(),
              "cannot create the JIT");
  defineRuntimeSymbols(*compiled_->jit);
  orThrow(compiled_->jit->addIRModule(
              llvm::orc::ThreadSafeModule(std::move(module), std::move(context))),
          "cannot add the module");
  llvm::JITEvaluatedSymbol entry =
      orThrow(compiled_->jit->lookup(llvm::StringRef(jit::entryName.data(), jit::entryName.size())),
              "cannot compile the function");
  compiled_->entry = reinterpret_cast<jit::EntryFunction>(entry.getAddress());
}

CompiledFunction::~CompiledFunction() = default;
CompiledFunction::CompiledFunction(CompiledFunction&&) noexcept = default;
CompiledFunction& CompiledFunction::operator=(CompiledFunction&&) noexcept = default;

ir::ToolPath CompiledFunction::run(const ir::InterpreterOptions& options) const {
  ir::ToolPath path;
  // The last run's length: one allocation instead of a doubling series.
  path.events.reserve(compiled_->lastEventCount.load(std::memory_order_relaxed));
  run(options, path);
  compiled_->lastEventCount.store(path.events.size(), std::memory_order_relaxed);
  return path;
}

void CompiledFunction::run(const ir::InterpreterOptions& options, ir::ToolPath& path) const {
  path.events.clear();
  jit::RunContext context;
  context.events = &path.events;
  execute(options, context);
}

void CompiledFunction::run(const ir::InterpreterOptions& options,
                           ir::MachineEventSink& sink) const {
  jit::RunContext context;
  context.sink = &sink;
  execute(options, context);
}

void CompiledFunction::execute(const ir::InterpreterOptions& options,
                               jit::RunContext& context) const {
  std::vector<double> parameters;
  for (const ir::Parameter& parameter : compiled_->parameters) {
    auto given = options.parameters.find(parameter.name);
    parameters.push_back(given == options.parameters.end() ? parameter.defaultValue
                                                           : given->second);
  }
  context.comments = &compiled_->comments;
  context.tables = &compiled_->tables;
  std::uint64_t steps = 0;
  if (compiled_->entry(parameters.data(), &context, options.maximumSteps, &steps) != 0) {
    if (context.exception) {
      std::rethrow_exception(context.exception);
    }
    throw ir::InterpreterError(context.errorMessage);
  }
}

ir::ToolPath runJit(const ir::Function& function, const ir::InterpreterOptions& options) {
  return CompiledFunction(function).run(options);
}

} // namespace cncc::backends
