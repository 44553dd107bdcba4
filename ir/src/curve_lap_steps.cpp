#include "cncc/ir/curve_lap_steps.h"

#include "cncc/geom/discretisation.h"
#include "cncc/geom/evaluation_budget.h"
#include "cncc/geom/geometry_error.h"
#include "cncc/ir/curve_lap.h"
#include "cncc/ir/printed_grid.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <span>

namespace cncc::ir {

namespace {

// Whether `steps` uniform chords keep the budget, the largest deviation
// when they do, and where one that does not starts. The chord at `first`
// (where a count too few failed before) is measured first: a count that
// is still too few fails there at once.
struct UniformChords {
  bool fit = true;
  double largest = 0;
  double failingAt = 0;
};

UniformChords measureUniformChords(const geom::Curve& curve, std::span<const double> breaks,
                                   double from, double to, int steps, double budget, double first) {
  auto chordStart = [&](int j) { return j == 0 ? from : from + (to - from) * j / steps; };
  auto chordEnd = [&](int j) { return j + 1 == steps ? to : from + (to - from) * (j + 1) / steps; };
  int firstChord =
      std::clamp(static_cast<int>(std::floor((first - from) / (to - from) * steps)), 0, steps - 1);
  UniformChords chords;
  for (int k = 0; k < steps; ++k) {
    int j = k == 0 ? firstChord : (k <= firstChord ? k - 1 : k);
    double deviation = geom::chordDeviation(curve, chordStart(j), chordEnd(j), breaks);
    if (!(deviation <= budget)) {
      return {false, deviation, chordStart(j)};
    }
    chords.largest = std::max(chords.largest, deviation);
  }
  return chords;
}

} // namespace

bool uniformStepsFit(const geom::Curve& curve, double from, double to, int steps, double budget) {
  std::vector<double> breaks = curve.breakpoints();
  return measureUniformChords(curve, breaks, from, to, steps, budget, from).fit;
}

int fewestUniformSteps(const geom::Curve& curve, double from, double to, double budget) {
  constexpr int maximumPredictedProbes = 4;
  double failingAt = from;
  std::vector<double> breaks = curve.breakpoints(); // once for every count measured
  auto measure = [&](int steps) {
    UniformChords chords = measureUniformChords(curve, breaks, from, to, steps, budget, failingAt);
    if (!chords.fit) {
      failingAt = chords.failingAt;
    }
    return chords;
  };
  int high = 1;
  UniformChords atHigh = measure(high);
  while (!atHigh.fit) {
    high *= 2;
    if (high > maximumStepsPerRegion) {
      return 0;
    }
    atHigh = measure(high);
  }
  int low = high / 2; // does not fit (or 0)
  // A chord's deviation falls as the square of the step, so each count
  // measured predicts the fewest: those predictions are tried first (a
  // few), then bisection closes what is left.
  auto predicted = [&](int steps, const UniformChords& chords) {
    double count = std::ceil(steps * std::sqrt(chords.largest / budget));
    double inward = chords.fit ? std::min(count, steps - 1.0) : std::max(count, steps + 1.0);
    return std::isfinite(inward) ? inward : steps;
  };
  double next = predicted(high, atHigh);
  for (int guided = 0; high - low > 1; ++guided) {
    int steps = low + (high - low) / 2;
    if (guided < maximumPredictedProbes) {
      steps = static_cast<int>(std::clamp(next, low + 1.0, high - 1.0));
    }
    UniformChords chords = measure(steps);
    (chords.fit ? high : low) = steps;
    next = predicted(steps, chords);
  }
  return high;
}

int searchedSteps(const std::function<int()>& search, frontend::SourceSpan cutSpan,
                  frontend::SourceSpan curveSpan) {
  int steps = 0;
  try {
    steps = search();
  } catch (const geom::EvaluationBudgetExceeded&) {
    throw CurveLapError(
        CurveLapError::Kind::ProgramTooLarge, cutSpan,
        fmt::format("choosing this curve's uniform steps within its tolerance asks more than "
                    "{} points of it; that is the limit of one cut",
                    maximumStepSearchEvaluations));
  } catch (const geom::GeometryError& error) {
    throw CurveLapError(CurveLapError::Kind::DegenerateCurve, curveSpan,
                        fmt::format("cannot discretise this curve: {}", error.what()));
  }
  if (steps == 0) {
    throw CurveLapError(CurveLapError::Kind::ProgramTooLarge, cutSpan,
                        fmt::format("this curve needs more than {} uniform steps on one piece "
                                    "within its tolerance",
                                    maximumStepsPerRegion));
  }
  return steps;
}

bool hasChosenSteps(const CurveTableEntry& entry) {
  return std::find(entry.regionSteps.begin(), entry.regionSteps.end(), stepsChosenByLegalisation) !=
         entry.regionSteps.end();
}

CurveTableEntry withChosenSteps(const CurveTableEntry& entry, const geom::Curve& curve) {
  CurveTableEntry counted = entry;
  if (hasChosenSteps(entry)) {
    checkFiniteAlong(entry, curve);
  }
  std::vector<CurveTableEntry::RegionPlace> places = entry.regionPlaces();
  // One bound over the lap's searches.
  geom::BudgetedCurve budgeted(curve, maximumStepSearchEvaluations);
  for (std::size_t region = 0; region < counted.regionSteps.size() && region < places.size();
       ++region) {
    int& steps = counted.regionSteps[region];
    if (steps != stepsChosenByLegalisation || entry.offsetGrowth) {
      continue; // an offset's grow with the radius (curve_lap_offset_steps.h)
    }
    auto [from, to] = entry.regionRange(places[region]);
    // A region's parameter lies on the whole curve's at a shift (a piece
    // without knot spans): uniform steps of the one are the other's.
    double wholeFrom = entry.wholeParameter(places[region], from);
    double wholeTo = entry.wholeParameter(places[region], to);
    steps = searchedSteps(
        [&] { return fewestUniformSteps(budgeted, wholeFrom, wholeTo, entry.amount); },
        entry.cutSpan, entry.curveSpan);
  }
  return counted;
}

void checkStepDrift(const CurveTableEntry& entry, const geom::Curve& curve, int digits,
                    double tolerance) {
  if (digits <= 0) {
    return;
  }
  bool closed = (curve.point(entry.from) - curve.point(entry.to)).norm() < 1e-9;
  std::vector<CurveTableEntry::RegionPlace> places = entry.regionPlaces();
  for (std::size_t region = 0; region < entry.regionSteps.size() && region < places.size();
       ++region) {
    int steps = entry.regionSteps[region];
    bool runsOntoItsStart = closed && region + 1 == entry.regionSteps.size();
    // An arc's blocks end on points the host computes (whole turns: its start).
    if (steps < 2 || runsOntoItsStart || entry.arcRegion(region) != nullptr) {
      continue;
    }
    auto [from, to] = entry.regionRange(places[region]);
    double step = (to - from) / steps;
    double drift = steps * (controllerReading(step, digits) - step);
    if (!(drift > 0)) {
      continue;
    }
    double probe = (to - from) * 1e-6;
    Eigen::Vector3d end = curve.point(entry.wholeParameter(places[region], to));
    Eigen::Vector3d before = curve.point(entry.wholeParameter(places[region], to - probe));
    double movement = drift * (end - before).norm() / probe;
    if (movement > tolerance / 4) {
      throw CurveLapError(
          CurveLapError::Kind::LiteralRounding, entry.cutSpan,
          fmt::format("the controller's {} significant digits round this curve's parameter "
                      "step {} to {}: after its {} steps the last point lies {:.3g} mm past "
                      "the curve's end, more than a quarter of the tolerance {:g} mm (a "
                      "coarser tolerance takes fewer steps)",
                      digits, step, controllerReading(step, digits), steps, movement, tolerance));
    }
  }
}

} // namespace cncc::ir
