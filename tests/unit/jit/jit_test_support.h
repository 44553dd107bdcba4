// Runs a Function through the IR interpreter and the LLVM JIT and compares
// the tool paths: the same events in the same order, numbers within 1e-9 mm
// (NaN matching NaN, infinities of the same sign matching).
#pragma once

#include "cncc/backends/jit_compiler.h"
#include "cncc/ir/interpreter.h"
#include "cncc/ir/machine_event_sink.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

namespace cncc::jit_test {

inline constexpr double kTolerance = 1e-9;

inline bool sameNumber(double expected, double actual) {
  if (std::isnan(expected) || std::isnan(actual)) {
    return std::isnan(expected) && std::isnan(actual);
  }
  if (std::isinf(expected) || std::isinf(actual)) {
    return expected == actual;
  }
  return std::abs(expected - actual) <= kTolerance;
}

inline ::testing::AssertionResult samePaths(const ir::ToolPath& expected,
                                            const ir::ToolPath& actual) {
  if (expected.events.size() != actual.events.size()) {
    return ::testing::AssertionFailure() << "the interpreter records " << expected.events.size()
                                         << " events, the JIT " << actual.events.size();
  }
  for (std::size_t i = 0; i < expected.events.size(); ++i) {
    const ir::MachineEvent& a = expected.events[i];
    const ir::MachineEvent& b = actual.events[i];
    bool same = a.kind == b.kind && sameNumber(a.x, b.x) && sameNumber(a.y, b.y) &&
                sameNumber(a.z, b.z) && sameNumber(a.feed, b.feed) &&
                sameNumber(a.number, b.number) && sameNumber(a.diameter, b.diameter) &&
                sameNumber(a.centreX, b.centreX) && sameNumber(a.centreY, b.centreY) &&
                a.clockwise == b.clockwise && a.alongZ == b.alongZ && a.text == b.text &&
                a.offsetRegister == b.offsetRegister;
    if (!same) {
      return ::testing::AssertionFailure()
             << "event " << i << " differs: interpreter kind " << static_cast<int>(a.kind) << " ("
             << a.x << ", " << a.y << ", " << a.z << ", " << a.feed << ", " << a.number << ", "
             << a.diameter << ", " << a.offsetRegister << ", \"" << a.text << "\"), JIT kind "
             << static_cast<int>(b.kind) << " (" << b.x << ", " << b.y << ", " << b.z << ", "
             << b.feed << ", " << b.number << ", " << b.diameter << ", " << b.offsetRegister
             << ", \"" << b.text << "\")";
    }
  }
  return ::testing::AssertionSuccess();
}

// What a run gives: its tool path, or the error message.
struct RunOutcome {
  ir::ToolPath path;
  bool failed = false;
  std::string error;
};

template <typename Run> RunOutcome outcomeOf(Run run) {
  RunOutcome outcome;
  try {
    outcome.path = run();
  } catch (const ir::InterpreterError& error) {
    outcome.failed = true;
    outcome.error = error.what();
  }
  return outcome;
}

// Both runs end alike: the same error, or tool paths that agree.
inline ::testing::AssertionResult sameOutcome(const RunOutcome& interpreted,
                                              const RunOutcome& compiled) {
  if (interpreted.failed != compiled.failed || interpreted.error != compiled.error) {
    return ::testing::AssertionFailure()
           << "interpreter: " << (interpreted.failed ? interpreted.error : "finishes")
           << "; JIT: " << (compiled.failed ? compiled.error : "finishes");
  }
  return samePaths(interpreted.path, compiled.path);
}

inline ::testing::AssertionResult
jitMatchesInterpreter(const ir::Function& function, const ir::InterpreterOptions& options = {}) {
  backends::CompiledFunction compiled(function);
  return sameOutcome(outcomeOf([&] { return ir::interpret(function, options); }),
                     outcomeOf([&] { return compiled.run(options); }));
}

// A sink that keeps what it is handed.
class CollectingSink : public ir::MachineEventSink {
public:
  void event(const ir::MachineEvent& event) override { path.events.push_back(event); }
  ir::ToolPath path;
};

// A run into a stored path and a streamed run, each with the events made
// before an error, if one stops it.
inline RunOutcome storedOutcome(const backends::CompiledFunction& compiled,
                                const ir::InterpreterOptions& options = {}) {
  RunOutcome outcome;
  try {
    compiled.run(options, outcome.path);
  } catch (const ir::InterpreterError& error) {
    outcome.failed = true;
    outcome.error = error.what();
  }
  return outcome;
}

inline RunOutcome streamedOutcome(const backends::CompiledFunction& compiled,
                                  const ir::InterpreterOptions& options = {}) {
  CollectingSink sink;
  RunOutcome outcome;
  try {
    compiled.run(options, sink);
  } catch (const ir::InterpreterError& error) {
    outcome.failed = true;
    outcome.error = error.what();
  }
  outcome.path = std::move(sink.path);
  return outcome;
}

inline bool sameBits(double expected, double actual) {
  return expected == actual || (std::isnan(expected) && std::isnan(actual));
}

// Not within a tolerance: the same code made both, so every field is equal.
inline ::testing::AssertionResult identicalOutcomes(const RunOutcome& stored,
                                                    const RunOutcome& streamed) {
  if (stored.failed != streamed.failed || stored.error != streamed.error) {
    return ::testing::AssertionFailure()
           << "stored: " << (stored.failed ? stored.error : "finishes")
           << "; streamed: " << (streamed.failed ? streamed.error : "finishes");
  }
  if (stored.path.events.size() != streamed.path.events.size()) {
    return ::testing::AssertionFailure() << "stored " << stored.path.events.size()
                                         << " events, streamed " << streamed.path.events.size();
  }
  for (std::size_t i = 0; i < stored.path.events.size(); ++i) {
    const ir::MachineEvent& a = stored.path.events[i];
    const ir::MachineEvent& b = streamed.path.events[i];
    bool same = a.kind == b.kind && sameBits(a.x, b.x) && sameBits(a.y, b.y) &&
                sameBits(a.z, b.z) && sameBits(a.feed, b.feed) && sameBits(a.number, b.number) &&
                sameBits(a.diameter, b.diameter) && sameBits(a.centreX, b.centreX) &&
                sameBits(a.centreY, b.centreY) && a.clockwise == b.clockwise && a.text == b.text &&
                a.offsetRegister == b.offsetRegister && a.splineTable == b.splineTable &&
                a.splineStart == b.splineStart;
    if (!same) {
      return ::testing::AssertionFailure()
             << "event " << i << " differs: stored kind " << static_cast<int>(a.kind) << " (" << a.x
             << ", " << a.y << ", " << a.z << ", \"" << a.text << "\"), streamed kind "
             << static_cast<int>(b.kind) << " (" << b.x << ", " << b.y << ", " << b.z << ", \""
             << b.text << "\")";
    }
  }
  return ::testing::AssertionSuccess();
}

inline ::testing::AssertionResult
streamedMatchesStored(const backends::CompiledFunction& compiled,
                      const ir::InterpreterOptions& options = {}) {
  return identicalOutcomes(storedOutcome(compiled, options), streamedOutcome(compiled, options));
}

// The examples' .cdl files (CNCC_SOURCE_DIR/examples), sorted.
inline std::vector<std::filesystem::path> exampleFiles() {
  std::vector<std::filesystem::path> examples;
  for (const auto& entry :
       std::filesystem::directory_iterator(std::string(CNCC_SOURCE_DIR) + "/examples")) {
    if (entry.path().extension() == ".cdl") {
      examples.push_back(entry.path());
    }
  }
  std::sort(examples.begin(), examples.end());
  return examples;
}

} // namespace cncc::jit_test
