// What the native code calls: the state of one run, and the C functions that
// record machine events and errors into it. The native code receives a
// RunContext pointer and passes it back to every callback.
#pragma once

#include "cncc/ir/machine_event_sink.h"
#include "cncc/ir/tool_path.h"

#include <array>
#include <cstdint>
#include <exception>
#include <string>
#include <string_view>
#include <vector>

namespace cncc::backends::jit {

inline ir::MachineEvent feedMove() {
  ir::MachineEvent event;
  event.kind = ir::MachineEvent::Kind::Feed;
  return event;
}

struct RunContext {
  // Where the events go: appended to `events`, or, when it is null, handed
  // to `sink` one by one.
  std::vector<ir::MachineEvent>* events = nullptr;
  ir::MachineEventSink* sink = nullptr;
  // Where the last rapid, feed or arc ended (the origin before any): where
  // move.arc, move.nurbs and move.polynomial start. With the kind of that
  // move and where the one before it ended, a streaming run's move.spline
  // finds the direction it arrives in.
  std::array<double, 3> position{0, 0, 0};
  ir::MachineEvent::Kind positionKind = ir::MachineEvent::Kind::Rapid;
  std::array<double, 3> previousPosition{0, 0, 0};
  int motions = 0; // how many of those two there are (0 .. 2)
  // A streaming run's feed moves: this one event, its target and feed set
  // for each (a feed move is most of a run's events; none is made anew).
  ir::MachineEvent feedEvent = feedMove();
  // A streaming run's events of one move.nurbs, move.polynomial or
  // move.spline, made as a vector and then handed on (its storage reused).
  std::vector<ir::MachineEvent> pendingMoves;
  // The texts of the function's comments, by the index the code passes.
  const std::vector<std::string>* comments = nullptr;
  // The function's constant tables (move.nurbs reads its block data there).
  const std::vector<std::vector<double>>* tables = nullptr;
  // The weights of the move.nurbs being called, passed one by one before it.
  std::vector<double> nurbsWeights;
  // Set before the native code returns a failure: the interpreter's message
  // for the same error, or an exception raised while recording an event.
  std::string errorMessage;
  std::exception_ptr exception;
};

// The native entry point: 0 when the run finished, 1 after an error was
// recorded in the context.
using EntryFunction = std::int32_t (*)(const double* parameters, RunContext* context,
                                       std::uint64_t maximumSteps, std::uint64_t* steps);
inline constexpr std::string_view entryName = "cncc_part";

// A C function the native code may call, by the name it is declared under.
struct RuntimeSymbol {
  std::string_view name;
  void* address;
};

// The event and error callbacks, and the libm functions the IR's
// operations call (the ones the interpreter calls).
const std::vector<RuntimeSymbol>& runtimeSymbols();

} // namespace cncc::backends::jit
