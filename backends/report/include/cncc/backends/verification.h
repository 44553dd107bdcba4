// `cncc verify`: a compiled program run as its controller runs it and
// measured against the part's true curves. The program's path is matched to
// the cuts of the part run on the host with the same parameter values (the
// reference): each executed feed move belongs to the reference cut whose
// path it lies on. A program passes when it runs without a controller error,
// every cut the reference cuts is cut, every feed move lies on the
// reference's path, no cut strays from its curve by more than its
// tolerance, and no cut beside its curve (side=) leaves a contour that
// gouges the drawn curve or leaves material on it by more than that
// (contour_left.h).
#pragma once

#include "cncc/backends/contour_left.h"
#include "cncc/backends/path_statistics.h"
#include "cncc/backends/program_execution.h"
#include "cncc/ir/cut_geometry.h"

#include <Eigen/Core>

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace cncc::backends {

struct VerificationInput {
  std::string target;
  ProgramExecutor execute = nullptr; // how the target's programs run
  ExecutionRequest execution;
  // The part run on the host with the same parameter values, its feed
  // moves carrying their cuts (executedPathOfToolPath).
  ExecutedPath reference;
  std::span<const ir::CutGeometry> cuts;
};

// Feed moves that are on no cut of the reference: the program cuts
// something the part does not.
struct StrayMoves {
  std::size_t count = 0;
  double largestDistance = 0; // from the reference path, 3D
  Eigen::Vector3d where = Eigen::Vector3d::Zero();
};

struct VerificationReport {
  std::string target;
  std::size_t blocks = 0;
  std::size_t bytes = 0;
  std::size_t bytesWithoutComments = 0;
  std::optional<std::size_t> variables;
  std::optional<sim::LoopOperationCounts> operations;
  PathStatistics statistics;           // its cuts: the deviations
  std::vector<ContourLeft> contours;   // of its cuts beside their curves
  std::vector<std::size_t> missedCuts; // the reference cuts them, the program does not
  StrayMoves stray;
  std::optional<ControllerFailure> failure;
  std::vector<std::string> notes; // the execution's (ProgramExecution::notes)

  bool passed() const;
};

// Gives each feed move of `path` a cut of the reference path, following the
// reference's order of cuts and how far along the current cut the program
// has got: the current cut while the move keeps within its allowance of it,
// at or after where the last move got to and short of the cut's end (a
// later cut over the same place does not take it), else the nearest of the
// current cut and the next few (a tie goes to the earlier, unless a move has
// ended where the current cut ends; a move nearest to a reference feed move
// outside every cut gets none); moves farther than `allowance[cut]`
// (`outsideAllowance` outside cuts) from that reference path are counted in
// the result.
StrayMoves assignCuts(ExecutedPath& path, const ExecutedPath& reference,
                      const std::vector<double>& allowance, double outsideAllowance);

// Runs the program with the input's executor and measures it. Throws
// std::invalid_argument when no executor exists for the target.
VerificationReport verifyProgram(const VerificationInput& input, const StatisticsOptions& options);

std::string formatVerification(const VerificationReport& report, const StatisticsOptions& options);

} // namespace cncc::backends
