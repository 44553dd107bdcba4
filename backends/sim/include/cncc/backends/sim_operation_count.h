// What a macro program costs the controller per point it cuts: the
// operations the blocks inside WHILE loops executed, divided by the feed
// moves those loops commanded. Counted from a run of the virtual controller
// (SimulationResult::blockExecutions), not estimated from the text.
#pragma once

#include "cncc/backends/sim_program.h"
#include "cncc/backends/virtual_controller.h"

#include <cstddef>

namespace cncc::backends::sim {

struct OperationCounts {
  std::size_t arithmetic = 0;  // + - * / MOD, negation, AND OR XOR
  std::size_t functions = 0;   // SIN, SQRT, ATAN, ... calls
  std::size_t comparisons = 0; // EQ NE GT LT GE LE
  std::size_t assignments = 0; // `#n = e`, and `IF [..] THEN #n = e` whether or not it assigned

  std::size_t total() const { return arithmetic + functions + comparisons + assignments; }
};

struct LoopOperationCounts {
  OperationCounts operations; // executed by blocks inside loops
  std::size_t feedMoves = 0;  // feed blocks executed inside loops (a NURBS or SPL once)

  // Each kind per loop feed move (0 without such moves).
  double perFeedMove(std::size_t OperationCounts::*kind) const;
  double totalPerFeedMove() const;
};

// The operations one execution of `block` performs.
OperationCounts countBlockOperations(const Block& block);

// `result` must be a run of `program` (its blockExecutions index its blocks).
LoopOperationCounts countLoopOperations(const ProgramText& program, const SimulationResult& result);

} // namespace cncc::backends::sim
