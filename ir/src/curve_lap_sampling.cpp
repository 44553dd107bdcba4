// The points of a curve.lap: chosen on the whole curve as its table entry
// says, within bounds of points and curve evaluations; and the ramp's
// progress at each.
#include "cncc/ir/curve_lap.h"

#include "cncc/geom/arc_length.h"
#include "cncc/geom/discretisation.h"
#include "cncc/geom/evaluation_budget.h"
#include "cncc/geom/geometry_error.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace cncc::ir {

namespace {

CurveLapError degenerate(const CurveTableEntry& entry, const geom::GeometryError& error) {
  return CurveLapError(CurveLapError::Kind::DegenerateCurve, entry.curveSpan,
                       fmt::format("cannot discretise this curve: {}", error.what()));
}

// A curve whose chords the estimate puts well past the bound of one cut
// (a polar of 1e9 turns whose steps a legalisation turned into chords) is
// refused at once, not after the chord walk's budget of seconds; the walk
// decides nearer the bound.
void checkChordEstimate(const CurveTableEntry& entry, const geom::Curve& curve) {
  double chords = geom::estimateDiscretisation(curve, entry.amount).chords;
  if (chords > 2.0 * static_cast<double>(maximumChordsPerCut)) {
    throw CurveLapError(CurveLapError::Kind::ProgramTooLarge, entry.cutSpan,
                        fmt::format("this curve needs about {:.3g} chords within its tolerance "
                                    "{:.3g}; the limit of one cut is {}",
                                    chords, entry.amount, maximumChordsPerCut));
  }
}

geom::CurveSamples samplesOf(const CurveTableEntry& entry, const geom::Curve& curve) {
  switch (entry.sampling) {
  case CurveSampling::Samples:
    return geom::sampleUniformParameter(curve, static_cast<std::size_t>(entry.amount));
  case CurveSampling::Spacing:
    return geom::sampleEqualArcLength(curve, entry.amount);
  case CurveSampling::ChordTolerance:
    checkChordEstimate(entry, curve);
    break;
  case CurveSampling::Arcs:  // points within the arcs' tolerance, where points are asked
  case CurveSampling::Steps: // lapParameters gives the steps' own
    break;
  case CurveSampling::NurbsBlocks:
  case CurveSampling::SplineBlocks:
  case CurveSampling::PolynomialBlocks:
    throw CurveLapError(CurveLapError::Kind::DegenerateCurve, entry.curveSpan,
                        "a lap cut as curve blocks has no points of its own: its moves are the "
                        "blocks'");
  }
  return chordsWithinTolerance(curve, entry.amount, entry.cutSpan, entry.curveSpan);
}

// The whole-curve parameters of a lap cut in steps: its start, then each
// step's point.
std::vector<double> stepParameters(const CurveTableEntry& entry) {
  std::vector<double> parameters = {entry.from};
  if (!entry.walkRegions.empty()) {
    throw CurveLapError(CurveLapError::Kind::DegenerateCurve, entry.curveSpan,
                        "the points of a walked region are computed by the program");
  }
  std::vector<StepRange> ranges = lapStepRanges(entry, [&](std::size_t) -> StepRange {
    throw CurveLapError(CurveLapError::Kind::DegenerateCurve, entry.curveSpan,
                        "the steps of this lap are computed by the program");
  });
  std::vector<CurveTableEntry::RegionPlace> places = entry.regionPlaces();
  for (const LapStep& step : lapSteps(ranges)) {
    parameters.push_back(entry.wholeParameter(places[step.region], step.local));
  }
  return parameters;
}

} // namespace

geom::CurveSamples chordsWithinTolerance(const geom::Curve& curve, double tolerance,
                                         frontend::SourceSpan cutSpan,
                                         frontend::SourceSpan curveSpan) {
  try {
    geom::BudgetedCurve budgeted(curve, maximumCurveEvaluations);
    return geom::discretiseByChordTolerance(budgeted, tolerance, maximumChordsPerCut);
  } catch (const geom::EvaluationBudgetExceeded& error) {
    throw CurveLapError(
        CurveLapError::Kind::ProgramTooLarge, cutSpan,
        fmt::format("choosing this curve's points within its tolerance asks more than {} points "
                    "of it; that is the limit of one cut (a curve that turns this fast needs "
                    "more points than a program can hold)",
                    error.limit));
  } catch (const geom::ChordLimitExceeded& error) {
    throw CurveLapError(CurveLapError::Kind::ProgramTooLarge, cutSpan,
                        fmt::format("this curve needs more than {} chords within its tolerance; "
                                    "that is the limit of one cut",
                                    error.limit));
  } catch (const geom::GeometryError& error) {
    throw CurveLapError(CurveLapError::Kind::DegenerateCurve, curveSpan,
                        fmt::format("cannot discretise this curve: {}", error.what()));
  }
}

namespace {

void checkFinitePoints(const CurveTableEntry& entry, std::span<const Eigen::Vector3d> points) {
  for (const Eigen::Vector3d& point : points) {
    if (!point.allFinite()) {
      throw CurveLapError(CurveLapError::Kind::NonFiniteValue, entry.curveSpan,
                          "this curve has a point that is not a finite number");
    }
  }
}

} // namespace

void checkFiniteAlong(const CurveTableEntry& entry, const geom::Curve& curve,
                      std::span<const Eigen::Vector3d> points) {
  constexpr int probes = 16;
  geom::ParameterRange domain = curve.domain();
  std::vector<Eigen::Vector3d> probed;
  for (int k = 0; k <= probes; ++k) {
    probed.push_back(curve.point(domain.t0 + domain.length() * k / probes));
  }
  checkFinitePoints(entry, probed);
  checkFinitePoints(entry, points);
}

std::vector<double> lapParameters(const CurveTableEntry& entry, const geom::Curve& curve) {
  if (entry.chosenParameters) {
    return *entry.chosenParameters;
  }
  if (entry.sampling == CurveSampling::Steps) {
    return stepParameters(entry);
  }
  geom::CurveSamples samples;
  try {
    samples = samplesOf(entry, curve);
  } catch (const geom::GeometryError& error) {
    throw degenerate(entry, error);
  }
  checkFinitePoints(entry, samples.points);
  if (samples.parameters.size() < 2) {
    throw CurveLapError(CurveLapError::Kind::TooFewPoints, entry.curveSpan,
                        "this curve gave fewer than two points");
  }
  return std::move(samples.parameters);
}

namespace {

// The regions' lengths, for their shares of a ramp's descent, to a ten
// thousandth of a micrometre: finer than any printed height, and within
// reach of a curve whose derivatives are differences (an offset's).
constexpr double shareLengthTolerance = 1e-7;

} // namespace

std::vector<LapRegionShare> lapRegionShares(const CurveTableEntry& entry,
                                            const geom::Curve& curve) {
  std::vector<LapRegionShare> shares;
  std::vector<double> lengths;
  double total = 0;
  bool single = entry.pieces.size() == 1;
  try {
    for (const CurvePieceLayout& piece : entry.pieces) {
      // The piece's own parameter, and where it lies in the whole curve's.
      auto global = [&](double own) { return single ? own : piece.start + (own - piece.from); };
      for (std::size_t s = 0; s < piece.regionCount(); ++s) {
        double from = piece.spans.empty() ? piece.from : piece.spans[s].first;
        double to = piece.spans.empty() ? piece.to : piece.spans[s].second;
        shares.push_back({total, 0});
        lengths.push_back(geom::arcLength(curve, global(from), global(to), shareLengthTolerance));
        total += lengths.back();
      }
    }
  } catch (const geom::GeometryError& error) {
    throw CurveLapError(CurveLapError::Kind::DegenerateCurve, entry.curveSpan,
                        fmt::format("cannot measure this curve: {}", error.what()));
  }
  for (std::size_t i = 0; i < shares.size(); ++i) {
    shares[i].before = total > 0 ? shares[i].before / total : 0;
    shares[i].share = total > 0 ? lengths[i] / total : 1.0 / static_cast<double>(shares.size());
  }
  return shares;
}

std::vector<LapRegionShare> descentShares(const CurveTableEntry& entry, const geom::Curve& curve) {
  std::vector<LapRegionShare> shares = lapRegionShares(entry, curve);
  if (entry.progressFrom != 0 || entry.progressShare != 1) {
    for (LapRegionShare& share : shares) {
      share = {entry.progressFrom + entry.progressShare * share.before,
               entry.progressShare * share.share};
    }
  }
  return shares;
}

std::vector<double> lapProgress(const CurveTableEntry& entry, const geom::Curve& curve,
                                const std::vector<double>& parameters) {
  std::vector<LapRegionShare> shares = lapRegionShares(entry, curve);
  std::vector<double> progress;
  progress.reserve(parameters.size());
  for (double parameter : parameters) {
    CurveLocation location = entry.locate(parameter);
    const CurvePieceLayout& piece = entry.pieces[location.piece];
    double fraction = location.local; // a NURBS span's u
    if (piece.spans.empty()) {
      fraction = (location.local - piece.from) / (piece.to - piece.from);
    }
    const LapRegionShare& share = shares[location.region];
    double own = std::min(1.0, share.before + share.share * fraction);
    progress.push_back(entry.progressFrom == 0 && entry.progressShare == 1
                           ? own
                           : std::min(1.0, entry.progressFrom + entry.progressShare * own));
  }
  return progress;
}

} // namespace cncc::ir
