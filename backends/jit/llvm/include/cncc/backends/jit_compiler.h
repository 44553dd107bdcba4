// The LLVM JIT: compiles a part's IR Function to one native function with
// LLVM 14's ORC JIT (optimised with LLVM's O2 pipeline) and runs it. It means
// what the IR interpreter (cncc/ir/interpreter.h) means: the same tool path,
// the same libm calls, the same errors (ir::InterpreterError) for a table
// index out of range, a loop bound that is not finite, or more steps than
// InterpreterOptions::maximumSteps.
#pragma once

#include "cncc/ir/interpreter.h"
#include "cncc/ir/ir.h"
#include "cncc/ir/machine_event_sink.h"
#include "cncc/ir/tool_path.h"

#include <memory>
#include <stdexcept>

namespace cncc::backends {

namespace jit {
struct RunContext;
}

// A Function the JIT cannot compile: it does not verify, or LLVM failed.
class JitError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

// Whether LLVM can generate code for this host.
bool jitAvailable();

// A Function compiled to native code: compile once, run many times.
class CompiledFunction {
public:
  // Throws JitError.
  explicit CompiledFunction(const ir::Function& function);
  ~CompiledFunction();
  CompiledFunction(CompiledFunction&&) noexcept;
  CompiledFunction& operator=(CompiledFunction&&) noexcept;

  // Runs the native code for these parameter values, as ir::interpret
  // would. Throws ir::InterpreterError.
  ir::ToolPath run(const ir::InterpreterOptions& options = {}) const;
  // The same into `path`, whose events it replaces, reusing their storage
  // (no allocation when a previous run left enough). After an error the
  // path holds the events recorded before it.
  void run(const ir::InterpreterOptions& options, ir::ToolPath& path) const;
  // The same events handed to `sink` one by one as the run makes them, not
  // stored (at most one move.nurbs, move.spline or move.polynomial's chords
  // are held at a time). After an error the sink has had the events made
  // before it; an exception the sink throws stops the run and is rethrown
  // here.
  void run(const ir::InterpreterOptions& options, ir::MachineEventSink& sink) const;

private:
  struct Compiled;
  void execute(const ir::InterpreterOptions& options, jit::RunContext& context) const;
  std::unique_ptr<Compiled> compiled_;
};

// Compiles and runs once: CompiledFunction(function).run(options).
ir::ToolPath runJit(const ir::Function& function, const ir::InterpreterOptions& options = {});

} // namespace cncc::backends
