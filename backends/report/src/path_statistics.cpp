#include "cncc/backends/path_statistics.h"

#include "cncc/geom/deviation.h"
#include "plane_projection.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace cncc::backends {

namespace {

Eigen::Vector3d inPlane(const Eigen::Vector3d& point) {
  return {point.x(), point.y(), 0.0};
}

// A thousandth of the cut's tolerance (1e-7 without one): fine enough for
// the verdict and the printed figures, and ten times fewer samples than
// 1e-7 on a 0.01 mm cut (a helix's turns overlap in plan view, so each
// sample is compared with every turn).
// The work limit grows with the stretch (maximumMeasurementWork).
geom::DeviationOptions measurementOptions(double tolerance, std::size_t points) {
  return {std::isnan(tolerance) ? 1e-7 : std::max(1e-7, tolerance * 1e-3),
          maximumMeasurementWork(points)};
}

// The deviation of every stretch of the cut, the largest kept.
CutDeviation measureCut(const ExecutedPath& path, std::size_t cut,
                        const ir::CutGeometry& geometry) {
  CutDeviation deviation;
  deviation.cut = cut;
  deviation.tolerance = geometry.tolerance;
  deviation.maxDeviation = std::numeric_limits<double>::quiet_NaN();
  for (const ExecutedMove& move : path.moves) {
    deviation.feedMoves += !move.rapid && move.cut == cut ? 1 : 0;
  }
  if (deviation.feedMoves == 0 || geometry.curve == nullptr) {
    return deviation;
  }
  PlaneProjection plan(*geometry.curve);
  std::vector<std::vector<Eigen::Vector3d>> polylines = cutPolylines(path, cut);
  // A stretch that is a single point in XY (a plunge apart from the rest of
  // the cut) covers nothing of the curve: only its distance to it counts.
  bool hasExtent = std::any_of(polylines.begin(), polylines.end(),
                               [](const auto& polyline) { return polyline.size() > 1; });
  for (const std::vector<Eigen::Vector3d>& polyline : polylines) {
    if (hasExtent && polyline.size() == 1) {
      // Newton's method refines the closest point: the samples need only the
      // measurement's accuracy (finer ones cost a long curve millions).
      double accuracy = measurementOptions(geometry.tolerance, 1).accuracy;
      double distance =
          geom::CurveProximity(plan, accuracy).closestPoint(polyline.front()).distance;
      if (!(distance <= deviation.maxDeviation)) {
        deviation.maxDeviation = distance;
        deviation.where = polyline.front();
      }
      continue;
    }
    geom::DeviationReport report = geom::measureDeviation(
        polyline, plan, measurementOptions(geometry.tolerance, polyline.size()));
    if (!(report.maxDeviation() <= deviation.maxDeviation)) {
      deviation.maxDeviation = report.maxDeviation();
      deviation.where = report.worst().polylinePoint;
    }
  }
  return deviation;
}

std::string formatMinutes(double minutes) {
  double seconds = minutes * 60.0;
  if (seconds < 60.0) {
    return fmt::format("{:.1f} s", seconds);
  }
  double wholeMinutes = std::floor(seconds / 60.0);
  return fmt::format("{} min {:.1f} s", wholeMinutes, seconds - 60.0 * wholeMinutes);
}

std::string formatCutLine(const CutDeviation& cut, const StatisticsOptions& options) {
  std::string name = cut.cut < options.cutNames.size() ? options.cutNames[cut.cut]
                                                       : fmt::format("cut {}", cut.cut + 1);
  if (std::isnan(cut.maxDeviation)) {
    return fmt::format("  {}: no feed moves\n", name);
  }
  std::string tolerance = std::isnan(cut.tolerance)
                              ? "no tolerance (samples= or spacing= chose the points)"
                              : fmt::format("tolerance {:g} {}, {}", cut.tolerance, options.unit,
                                            cut.withinTolerance() ? "within" : "EXCEEDED");
  return fmt::format("  {}: max deviation {:.5f} {} at ({:.4f}, {:.4f}), {}; {} feed moves\n", name,
                     cut.maxDeviation, options.unit, cut.where.x(), cut.where.y(), tolerance,
                     cut.feedMoves);
}

} // namespace

double PathStatistics::maxDeviation() const {
  double largest = 0;
  for (const CutDeviation& cut : cuts) {
    largest = std::isnan(cut.maxDeviation) ? largest : std::max(largest, cut.maxDeviation);
  }
  return largest;
}

std::vector<std::vector<Eigen::Vector3d>> cutPolylines(const ExecutedPath& path, std::size_t cut) {
  std::vector<std::vector<Eigen::Vector3d>> polylines;
  bool inStretch = false;
  for (std::size_t i = 0; i < path.moves.size(); ++i) {
    const ExecutedMove& move = path.moves[i];
    if (move.rapid || move.cut != cut) {
      inStretch = false;
      continue;
    }
    if (!inStretch) {
      polylines.push_back({inPlane(path.startOf(i))});
      inStretch = true;
    }
    Eigen::Vector3d point = inPlane(move.end);
    if (point != polylines.back().back()) {
      polylines.back().push_back(point);
    }
  }
  return polylines;
}

PathStatistics measureProgram(const ExecutedProgram& program, std::span<const ir::CutGeometry> cuts,
                              const StatisticsOptions& options) {
  PathStatistics statistics;
  statistics.blocks = program.blocks;
  statistics.bytes = program.text.size();
  const ExecutedPath& path = program.path;
  for (std::size_t i = 0; i < path.moves.size(); ++i) {
    const ExecutedMove& move = path.moves[i];
    if (move.cut && *move.cut >= cuts.size()) {
      throw ExecutionMismatch(
          fmt::format("a move of cut {} but the part has {} cuts", *move.cut, cuts.size()));
    }
    double length = (move.end - path.startOf(i)).norm();
    if (move.rapid) {
      ++statistics.rapidMoves;
      statistics.rapidLength += length;
      statistics.rapidMinutes += length / options.rapidRate;
    } else {
      ++statistics.feedMoves;
      statistics.feedLength += length;
      // A move without a feed (F0) has no duration to estimate.
      statistics.feedMinutes += move.feed > 0 ? length / move.feed : 0.0;
    }
  }
  for (std::size_t cut = 0; cut < cuts.size(); ++cut) {
    statistics.cuts.push_back(measureCut(path, cut, cuts[cut]));
  }
  return statistics;
}

std::string formatStatistics(const PathStatistics& statistics, const StatisticsOptions& options) {
  const std::string& unit = options.unit;
  std::string text =
      fmt::format("program: {} blocks, {} bytes\n", statistics.blocks, statistics.bytes);
  text += fmt::format("path: feed moves {:.3f} {} ({} moves), rapids {:.3f} {} ({} moves)\n",
                      statistics.feedLength, unit, statistics.feedMoves, statistics.rapidLength,
                      unit, statistics.rapidMoves);
  text +=
      fmt::format("time: {} (feed moves {}, rapids {}), at the programmed feeds and rapids at "
                  "{:g} {}/min, without acceleration\n",
                  formatMinutes(statistics.totalMinutes()), formatMinutes(statistics.feedMinutes),
                  formatMinutes(statistics.rapidMinutes), options.rapidRate, unit);
  text += "deviation of the executed path from the true curve (in XY):\n";
  for (const CutDeviation& cut : statistics.cuts) {
    text += formatCutLine(cut, options);
  }
  if (statistics.cuts.empty()) {
    text += "  the part has no cuts\n";
  } else {
    std::size_t exceeding = static_cast<std::size_t>(
        std::count_if(statistics.cuts.begin(), statistics.cuts.end(),
                      [](const CutDeviation& cut) { return !cut.withinTolerance(); }));
    text += fmt::format("  overall: max deviation {:.5f} {}; {}\n", statistics.maxDeviation(), unit,
                        exceeding == 0 ? "no cut exceeds its tolerance"
                                       : fmt::format("{} of {} cuts EXCEED their tolerance",
                                                     exceeding, statistics.cuts.size()));
  }
  return text;
}

} // namespace cncc::backends
