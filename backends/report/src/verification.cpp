#include "cncc/backends/verification.h"

#include "cncc/backends/macro_program.h"
#include "cncc/geom/deviation.h"
#include "plane_projection.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <vector>

namespace cncc::backends {

namespace {

bool hasFeedMoves(const ExecutedPath& path, std::size_t cut) {
  for (const ExecutedMove& move : path.moves) {
    if (!move.rapid && move.cut == cut) {
      return true;
    }
  }
  return false;
}

// The ends of a path's feed moves, by cut, in order.
std::map<std::size_t, std::vector<Eigen::Vector3d>> feedEndsByCut(const ExecutedPath& path) {
  std::map<std::size_t, std::vector<Eigen::Vector3d>> ends;
  for (const ExecutedMove& move : path.moves) {
    if (!move.rapid && move.cut) {
      ends[*move.cut].push_back(move.end);
    }
  }
  return ends;
}

// Whether the program cut `cut` as another cut of the same path: a part
// that cuts one hole twice (a hole pattern whose angle is 0) has two cuts
// whose reference moves agree within `rounding`, and the executed moves
// are matched to one of them.
bool cutAsAnother(const std::map<std::size_t, std::vector<Eigen::Vector3d>>& referenceEnds,
                  const ExecutedPath& executed, std::size_t cut, double rounding) {
  auto own = referenceEnds.find(cut);
  if (own == referenceEnds.end()) {
    return false;
  }
  for (const auto& [other, theirs] : referenceEnds) {
    if (other == cut || theirs.size() != own->second.size()) {
      continue;
    }
    bool same = true;
    for (std::size_t k = 0; same && k < theirs.size(); ++k) {
      same = (theirs[k] - own->second[k]).norm() <= rounding;
    }
    if (same && hasFeedMoves(executed, other)) {
      return true;
    }
  }
  return false;
}

// How far the reference's own feed moves of `cut` are from its curve: the
// promise of a cut whose points samples= or spacing= chose.
double referenceDeviation(const ExecutedPath& reference, std::size_t cut,
                          const ir::CutGeometry& geometry) {
  double largest = 0;
  if (geometry.curve == nullptr) {
    return largest;
  }
  PlaneProjection plan(*geometry.curve);
  for (const std::vector<Eigen::Vector3d>& polyline : cutPolylines(reference, cut)) {
    largest = std::max(
        largest, geom::measureDeviation(polyline, plan,
                                        {.maximumWork = maximumMeasurementWork(polyline.size())})
                     .maxDeviation());
  }
  return largest;
}

// How far a feed move may be from the reference's path of its cut: both
// paths keep within the cut's promise of the curve, and each coordinate is
// rounded by up to half the increment (twice that, to be safe).
std::vector<double> allowances(const VerificationInput& input, double rounding) {
  std::vector<double> allowance;
  for (std::size_t cut = 0; cut < input.cuts.size(); ++cut) {
    double promise = input.cuts[cut].tolerance;
    if (std::isnan(promise)) {
      promise = referenceDeviation(input.reference, cut, input.cuts[cut]);
    }
    allowance.push_back(2 * promise + rounding);
  }
  return allowance;
}

std::string formatOperations(const sim::LoopOperationCounts& counts) {
  using Counts = sim::OperationCounts;
  return fmt::format("operations per point: {:.2f} ({:.2f} arithmetic, {:.2f} function calls, "
                     "{:.2f} comparisons, {:.2f} assignments; {} feed moves in loops)\n",
                     counts.totalPerFeedMove(), counts.perFeedMove(&Counts::arithmetic),
                     counts.perFeedMove(&Counts::functions),
                     counts.perFeedMove(&Counts::comparisons),
                     counts.perFeedMove(&Counts::assignments), counts.feedMoves);
}

std::string formatCut(const CutDeviation& cut, const StatisticsOptions& options) {
  std::string name = cut.cut < options.cutNames.size() ? options.cutNames[cut.cut]
                                                       : fmt::format("cut {}", cut.cut + 1);
  if (std::isnan(cut.maxDeviation)) {
    return fmt::format("  {}: no feed moves\n", name);
  }
  std::string tolerance = std::isnan(cut.tolerance)
                              ? std::string("no tolerance (samples= or spacing= chose the points)")
                              : fmt::format("tolerance {:g} {}, {}", cut.tolerance, options.unit,
                                            cut.withinTolerance() ? "within" : "EXCEEDED");
  return fmt::format("  {}: max deviation {:.5f} {} at ({:.4f}, {:.4f}), {}\n", name,
                     cut.maxDeviation, options.unit, cut.where.x(), cut.where.y(), tolerance);
}

std::string cutName(std::size_t cut, const StatisticsOptions& options) {
  return cut < options.cutNames.size() ? options.cutNames[cut] : fmt::format("cut {}", cut + 1);
}

// The contour each cut beside its curve leaves, from its own feed moves.
std::vector<ContourLeft> contoursLeft(const ExecutedPath& path,
                                      std::span<const ir::CutGeometry> cuts) {
  std::vector<ContourLeft> contours;
  for (std::size_t cut = 0; cut < cuts.size(); ++cut) {
    const ir::CutGeometry& geometry = cuts[cut];
    std::vector<std::vector<Eigen::Vector3d>> polylines = cutPolylines(path, cut);
    if (geometry.drawnCurve == nullptr || polylines.empty()) {
      continue;
    }
    // As the deviation is measured (path_statistics.cpp).
    double accuracy =
        std::isnan(geometry.tolerance) ? 1e-7 : std::max(1e-7, geometry.tolerance * 1e-3);
    contours.push_back(measureContourLeft(cut, geometry, polylines, accuracy));
  }
  return contours;
}

std::string formatContour(const ContourLeft& contour, const StatisticsOptions& options) {
  auto amount = [&](double value, const Eigen::Vector3d& where) {
    return value > 0 ? fmt::format("{:.5f} {} at ({:.4f}, {:.4f})", value, options.unit, where.x(),
                                   where.y())
                     : std::string("none");
  };
  std::string tolerance =
      std::isnan(contour.tolerance)
          ? std::string("no tolerance")
          : fmt::format("tolerance {:g} {}, {}", contour.tolerance, options.unit,
                        contour.withinTolerance() ? "within" : "EXCEEDED");
  return fmt::format("  {}: tool radius {:g}, material left {}, cut past the curve {}, {}\n",
                     cutName(contour.cut, options), contour.toolRadius,
                     amount(contour.largestUndercut, contour.undercutAt),
                     amount(contour.largestGouge, contour.gougeAt), tolerance);
}

} // namespace

bool VerificationReport::passed() const {
  if (failure || !missedCuts.empty() || stray.count > 0) {
    return false;
  }
  for (const CutDeviation& cut : statistics.cuts) {
    if (!cut.withinTolerance()) {
      return false;
    }
  }
  for (const ContourLeft& contour : contours) {
    if (!contour.withinTolerance()) {
      return false;
    }
  }
  return true;
}

VerificationReport verifyProgram(const VerificationInput& input, const StatisticsOptions& options) {
  if (input.execute == nullptr) {
    throw std::invalid_argument(fmt::format("target '{}' cannot be verified", input.target));
  }
  ProgramExecution execution = input.execute(input.execution);
  VerificationReport report;
  report.target = input.target;
  MacroProgramStatistics size = measureMacroProgram(execution.text);
  report.blocks = countProgramBlocks(execution.text);
  report.bytes = size.bytes;
  report.bytesWithoutComments = size.bytesWithoutComments;
  report.variables = execution.variables;
  report.operations = execution.operations;
  report.failure = execution.failure;
  report.notes = execution.notes;
  if (report.failure) {
    return report;
  }
  double rounding = 2 * execution.increment;
  try {
    report.stray =
        assignCuts(execution.path, input.reference, allowances(input, rounding), rounding);
    report.statistics =
        measureProgram({execution.text, report.blocks, execution.path}, input.cuts, options);
    report.contours = contoursLeft(execution.path, input.cuts);
  } catch (const geom::MeasurementTooLarge& error) {
    report.failure = ControllerFailure{
        0, fmt::format("{} in one stretch of a cut: too large to verify", error.what()), ""};
    return report;
  }
  std::map<std::size_t, std::vector<Eigen::Vector3d>> referenceEnds =
      feedEndsByCut(input.reference);
  for (std::size_t cut = 0; cut < input.cuts.size(); ++cut) {
    if (hasFeedMoves(input.reference, cut) && !hasFeedMoves(execution.path, cut) &&
        !cutAsAnother(referenceEnds, execution.path, cut, rounding)) {
      report.missedCuts.push_back(cut);
    }
  }
  return report;
}

std::string formatVerification(const VerificationReport& report, const StatisticsOptions& options) {
  std::string text = fmt::format("target: {}\n", report.target);
  text += fmt::format("program: {} blocks, {} bytes ({} without comments)\n", report.blocks,
                      report.bytes, report.bytesWithoutComments);
  if (report.variables) {
    text += fmt::format("variables used: {}\n", *report.variables);
  }
  if (report.operations) {
    text += formatOperations(*report.operations);
  }
  for (const std::string& note : report.notes) {
    text += fmt::format("note: {}\n", note);
  }
  if (report.failure && report.failure->line == 0) { // no block of the program
    return text + fmt::format("the program cannot be verified: {}\nverdict: FAILED\n",
                              report.failure->message);
  }
  if (report.failure) {
    text += fmt::format("the controller stopped the program: line {}: {}\n", report.failure->line,
                        report.failure->message);
    if (!report.failure->lineText.empty()) {
      text += fmt::format("    {}\n", report.failure->lineText);
    }
    return text + "verdict: FAILED\n";
  }
  text += "deviation of the executed path from the true curve (in XY):\n";
  for (const CutDeviation& cut : report.statistics.cuts) {
    text += formatCut(cut, options);
  }
  for (std::size_t cut : report.missedCuts) {
    text +=
        fmt::format("  {}: NOT CUT: the program makes no feed move of it\n", cutName(cut, options));
  }
  if (report.stray.count > 0) {
    text += fmt::format("  {} feed moves are off the part's path, the farthest by {:.5f} {} at "
                        "({:.4f}, {:.4f}, {:.4f})\n",
                        report.stray.count, report.stray.largestDistance, options.unit,
                        report.stray.where.x(), report.stray.where.y(), report.stray.where.z());
  }
  text += fmt::format("  overall: max deviation {:.5f} {}\n", report.statistics.maxDeviation(),
                      options.unit);
  if (!report.contours.empty()) {
    text += "contour the tool leaves beside the drawn curve (side=), in XY:\n";
    for (const ContourLeft& contour : report.contours) {
      text += formatContour(contour, options);
    }
  }
  return text + (report.passed() ? "verdict: PASSED\n" : "verdict: FAILED\n");
}

} // namespace cncc::backends
