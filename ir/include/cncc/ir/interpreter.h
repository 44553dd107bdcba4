// Runs a Function for given parameter values and records the tool path.
#pragma once

#include "cncc/ir/ir.h"
#include "cncc/ir/machine_event_sink.h"
#include "cncc/ir/tool_path.h"

#include <array>
#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>

namespace cncc::ir {

// A run that cannot finish: a table index out of range, a loop bound that
// is not finite, more work than `maximumSteps` or more events than
// `maximumEvents`, an arc without a radius, a curve.lap whose points cannot
// be chosen (CurveLapError's message), or an `alarm` ("alarm: " and its
// text). A curve.lap's points count as steps.
class InterpreterError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

struct InterpreterOptions {
  // Values of the function's parameters by name; missing ones take their
  // defaults.
  std::map<std::string, double> parameters;
  std::size_t maximumSteps = 200'000'000;
  // The tool path's events (moves, settings, comments) kept at most.
  std::size_t maximumEvents = SIZE_MAX;
};

ToolPath interpret(const Function& function, const InterpreterOptions& options = {});
// The same run, its events handed to `sink` one at a time and not kept
// (maximumEvents does not apply).
void interpret(const Function& function, MachineEventSink& sink,
               const InterpreterOptions& options = {});

// The event of an effect op that records one (a move.rapid or move.feed, a
// setting, a comment or pass.begin, ...) from its immediates and the values
// of its first four operands.
MachineEvent effectEvent(const Instruction& instruction, const std::array<double, 4>& operands);

// The event of a setting op (origin, coolant, contouring, compensation) or move.home from its
// immediates: what the interpreter records and the JIT's code too.
MachineEvent settingEvent(Opcode opcode, double number, std::uint32_t index);

// The event `move.climb %z` records when the machine is at `from`: a rapid
// to z, x and y staying (MachineEvent::alongZ). The interpreter and the JIT
// both record it so.
MachineEvent climbEvent(const std::array<double, 3>& from, double z);

// The event `move.arc` records when the machine is at `start`: centre at
// (i, j) from it. Throws InterpreterError, as a controller alarms, for an
// arc without a radius or whose end lies off its circle (by more than 0.005
// in the part's units). The interpreter and the JIT both record arcs so.
MachineEvent arcMove(const std::array<double, 3>& start, ArcTurn turn, double x, double y, double z,
                     double i, double j, double feed);

} // namespace cncc::ir
