#include "cncc/ir/curve_lap_steps.h"

#include "cncc/geom/discretisation.h"
#include "cncc/geom/evaluation_budget.h"
#include "cncc/geom/geometry_error.h"
#include "cncc/ir/curve_lap.h"
#include "cncc/ir/printed_grid.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace cncc::ir {

bool uniformStepsFit(const geom::Curve& curve, double from, double to, int steps, double budget) {
  double previous = from;
  for (int j = 1; j <= steps; ++j) {
    double next = j == steps ? to : from + (to - from) * j / steps;
    if (!(geom::chordDeviation(curve, previous, next) <= budget)) {
      return false;
    }
    previous = next;
  }
  return true;
}

int fewestUniformSteps(const geom::Curve& curve, double from, double to, double budget) {
  auto fits = [&](int steps) { return uniformStepsFit(curve, from, to, steps, budget); };
  int high = 1;
  while (!fits(high)) {
    high *= 2;
    if (high > maximumStepsPerRegion) {
      return 0;
    }
  }
  int low = high / 2; // does not fit (or 0)
  while (high - low > 1) {
    int middle = low + (high - low) / 2;
    (fits(middle) ? high : low) = middle;
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
    if (steps != stepsChosenByLegalisation) {
      continue;
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
