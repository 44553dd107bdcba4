// A virtual Heidenhain TNC: reads a conversational (Klartext) program and
// runs it: Q parameters (FN 0..4, formula entry), labels with FN 9..12
// jumps, CALL LBL subprograms and repeats, FN 14 errors, and the motion
// blocks L, CC, C (helices with IZ) and SPL (polynomial_move.h), on a
// profile's limits, with radius compensation RL/RR/R0 by the tool table's
// R. What the model does not know (FN 5..8, cycles but 32) is an error
// naming the line, never a guess; so is reading a Q parameter no block has
// set, or the radius of a tool the table does not hold.
#pragma once

#include "cncc/backends/sim_operation_count.h"
#include "cncc/backends/tnc_profile.h"
#include "cncc/ir/tool_path.h"

#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <string_view>

namespace cncc::backends::heidenhain {

struct TncRunOptions {
  TncProfile profile = *findTncProfile("tnc640");
  std::size_t stepLimit = 10'000'000; // blocks executed in all
  // How far an arc's end may be off the circle through its start (mm).
  double arcRadiusTolerance = 0.001;
  // The tool table: R of each tool number, which RL/RR offset the path by.
  std::map<int, double> toolRadii;
};

struct TncError {
  int line = 0; // 1-based line of the text
  std::string message;
  std::string lineText;
};

struct TncRun {
  // Rapid, Feed, Arc and Home events; the first is where every axis is
  // first known (moves before it are left out).
  ir::ToolPath path;
  bool inches = false;
  std::size_t blocksExecuted = 0;
  // Operations of the blocks inside loops (a label a later jump or CALL
  // LBL REP goes back to, up to that jump) per feed move they command.
  sim::LoopOperationCounts loopOperations;
  std::size_t parametersNamed = 0; // distinct Q, QL, QR the text names
  std::optional<TncError> error;   // the first; the path runs up to it
};

// Never throws for a bad program.
TncRun runTncProgram(std::string_view text, const TncRunOptions& options = {});

// The text with the block `n FN 0: <parameter> = ..` given `value`: what
// the operator edits at the control; nullopt without such a block.
std::optional<std::string> withEditedParameter(std::string_view text, int encodedParameter,
                                               double value);

} // namespace cncc::backends::heidenhain
