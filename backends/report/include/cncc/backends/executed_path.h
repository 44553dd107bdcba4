// The path a controller executes when it runs a program, move by move, with
// the cut each feed move belongs to: what `--stats` and `cncc plot` measure
// against the true curves. A backend whose program text differs from the IR's
// tool path (rounded numbers, split rapids, or macro programs run in a
// virtual controller) provides its own ExecutedProgram.
#pragma once

#include "cncc/ir/tool_path.h"

#include <Eigen/Core>

#include <cstddef>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace cncc::backends {

struct ExecutedMove {
  bool rapid = false;
  Eigen::Vector3d end = Eigen::Vector3d::Zero(); // the move starts where the previous ended
  double feed = 0;                               // mm/min (in/min in inch parts); feed moves
  std::optional<std::size_t> cut;                // index into the part's cut table
};

struct ExecutedPath {
  // Where the first move starts: the first position at which every axis is
  // known (moves before it, from an unknown position, are left out).
  Eigen::Vector3d start = Eigen::Vector3d::Zero();
  std::vector<ExecutedMove> moves;

  // The start of move i.
  const Eigen::Vector3d& startOf(std::size_t i) const { return i == 0 ? start : moves[i - 1].end; }
};

// A program and what running it does.
struct ExecutedProgram {
  std::string text;       // the program as written
  std::size_t blocks = 0; // what the target counts as a block
  ExecutedPath path;
};

// The executed path does not match the tool path the program was printed
// from: a bug in a backend, not in the input.
class ExecutionMismatch : public std::logic_error {
public:
  using std::logic_error::logic_error;
};

// The tool path itself, exactly: what a host run (the jit target) executes;
// its arcs as chords within `arcSagitta` of them.
inline constexpr double executedArcSagitta = 1e-5;
// A program's executed arcs are flattened this finely (mm; a 25.4th in an
// inch part): below a tenth of the rounding room the arc output leaves
// inside a tolerance, so the chords add little to the deviation measured,
// and coarse enough that the many turns of a helix stay quick to measure.
inline constexpr double controllerArcSagitta = 2e-5;
// The points of an executed path (arcs flattened) that verification measures
// at most: measuring costs a few microseconds a point, and a 2.5D part
// within a controller's range has far fewer.
inline constexpr double maximumMeasuredPoints = 4'000'000;
ExecutedPath executedPathOfToolPath(const ir::ToolPath& toolPath,
                                    double arcSagitta = executedArcSagitta);

// An executed path past its limit of points (maximumMeasuredPoints), found
// before its points are all made; what() says so, naming the limit and the
// arcs' chord error.
class PathTooLargeToMeasure : public std::runtime_error {
public:
  PathTooLargeToMeasure(double limit, double arcSagitta);
};
// Throws PathTooLargeToMeasure when the path's arcs, as chords within
// `arcSagitta`, make more than maximumMeasuredPoints points.
void checkMeasurablePath(const ir::ToolPath& toolPath, double arcSagitta);

// Runs plain G-code as a controller would: G00/G01 blocks with modal X, Y, Z,
// F and motion mode; other words and comments are ignored. Each feed move is
// given the cut of the tool path event it was printed from (`toolPath` is what
// the program was printed from; coordinates match after rounding to
// `decimals`). Throws ExecutionMismatch when the two disagree.
ExecutedPath executeGcode(std::string_view program, const ir::ToolPath& toolPath, int decimals);

// Lines other than empty ones and `%` tape marks.
std::size_t countProgramBlocks(std::string_view program);

} // namespace cncc::backends
