// What a compiled program amounts to (`cncc FILE -t TARGET --stats`): its
// size, how far the path it executes strays from each cut's true curve, how
// long the path is and how long it takes at the programmed feeds.
#pragma once

#include "cncc/backends/executed_path.h"
#include "cncc/ir/cut_geometry.h"

#include <Eigen/Core>

#include <cstddef>
#include <span>
#include <string>
#include <vector>

namespace cncc::backends {

struct StatisticsOptions {
  // The rate rapids are assumed to move at (units per minute): controllers
  // differ, and the programs do not say.
  double rapidRate = 10000;
  // "mm" or "in": the unit of every length and rate.
  std::string unit = "mm";
  // How to name cut i for a person (say, where its curve is written); "cut
  // i+1" when absent.
  std::vector<std::string> cutNames;
};

// The deviation of one cut's executed path from its true curve.
struct CutDeviation {
  std::size_t cut = 0;
  double tolerance = 0; // NaN: samples= or spacing= chose the points
  // The largest distance either way between the executed feed moves (in XY)
  // and the curve; NaN when the cut has no feed move.
  double maxDeviation = 0;
  Eigen::Vector3d where = Eigen::Vector3d::Zero(); // on the path, where it is largest
  std::size_t feedMoves = 0;

  bool withinTolerance() const { return !(maxDeviation > tolerance); }
};

struct PathStatistics {
  std::size_t blocks = 0;
  std::size_t bytes = 0;
  std::size_t feedMoves = 0;
  std::size_t rapidMoves = 0;
  double feedLength = 0;  // along feed moves, 3D
  double rapidLength = 0; // along rapids, 3D, as the program orders the axes
  double feedMinutes = 0; // feed moves at their programmed feeds
  double rapidMinutes = 0;
  std::vector<CutDeviation> cuts;

  double totalMinutes() const { return feedMinutes + rapidMinutes; }
  // The largest of the cuts' deviations (0 without cuts).
  double maxDeviation() const;
};

// The XY polylines the feed moves of cut `cut` trace (z = 0), one per
// stretch of consecutive feed moves, without repeated points.
std::vector<std::vector<Eigen::Vector3d>> cutPolylines(const ExecutedPath& path, std::size_t cut);

// The segment distances measuring one stretch of a cut of `points` points
// may take (geom::DeviationOptions::maximumWork): a path along its curve
// takes a few hundred a point, a helix of twelve turns (each sample near
// every turn in plan view) about 2,800; a path wandering over the inside of
// a large closed curve, every point about as near to all of it, ten
// thousand and more, and minutes in all.
inline double maximumMeasurementWork(std::size_t points) {
  return 50e6 + 4000.0 * static_cast<double>(points);
}

// Measures `program` against the part's cuts (indexed as the moves' cut).
// Throws ExecutionMismatch for a move whose cut is not in `cuts`, and
// geom::MeasurementTooLarge past maximumMeasurementWork.
PathStatistics measureProgram(const ExecutedProgram& program, std::span<const ir::CutGeometry> cuts,
                              const StatisticsOptions& options);

// The statistics as lines of text for a person, saying how time is estimated.
std::string formatStatistics(const PathStatistics& statistics, const StatisticsOptions& options);

} // namespace cncc::backends
