#include "cncc/ir/curve_lap_offset_steps.h"

#include "cncc/geom/evaluation_budget.h"
#include "cncc/geom/function_curve.h"
#include "cncc/geom/geometry_error.h"
#include "cncc/geom/math_functions.h"
#include "cncc/ir/curve_lap_steps.h"

#include "compiled_values.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <memory>

namespace cncc::ir {

namespace {

// Samples of s'^2 k^2 per drawn step, and their bound.
constexpr int growthSamplesPerStep = 16;
constexpr int largestGrowthSamples = 100'000;
// The margin on the sampled largest s'^2 k^2, and how the growth is raised
// where the exact offset needs more steps (at most growthTries times).
constexpr double growthMargin = 1.1;
constexpr double growthRaise = 1.25;
constexpr int growthTries = 40;

// The largest s'^2 k^2 = |C' x C''|^2 / |C'|^4 over [from, to], sampled.
double largestCurvatureGrowth(const geom::Curve& curve, double from, double to, int samples) {
  double largest = 0;
  for (int j = 0; j <= samples; ++j) {
    geom::CurveDerivatives d = curve.derivatives(from + (to - from) * j / samples);
    double speedSquared = d.first.head<2>().squaredNorm();
    if (!(speedSquared > 0)) {
      continue;
    }
    double cross = d.first.x() * d.second.y() - d.first.y() * d.second.x();
    largest = std::max(largest, cross * cross / (speedSquared * speedSquared));
  }
  return largest;
}

// The radii N(r) is checked at on the exact offset: a quarter of the
// compiled radius, the compiled one, and most of the largest the tool fits
// with (or four times the compiled one without such a limit).
std::vector<double> checkedRadii(const OffsetStepGrowth& growth) {
  std::vector<double> radii{growth.compiledRadius / 4, growth.compiledRadius};
  double wide =
      std::isfinite(growth.largestRadius) ? 0.9 * growth.largestRadius : 4 * growth.compiledRadius;
  if (wide > growth.compiledRadius) {
    radii.push_back(wide);
  }
  return radii;
}

// Measures one lap's regions, its evaluations bounded over the lap.
class OffsetGrowthMeasure {
public:
  OffsetGrowthMeasure(const Function& function, const Instruction& lap)
      : function_(function), lap_(lap), entry_(function.curves[lap.index]),
        growth_(*entry_.offsetGrowth), compiled_(function) {
    if (lap.operands.size() != entry_.lapOperandCount()) {
      throw CurveLapError(CurveLapError::Kind::DegenerateCurve, entry_.curveSpan,
                          "the lap reads no distance of the tool centre for its offset's counts");
    }
  }

  OffsetRegionGrowth measure(std::size_t region, double from, double to) {
    geom::FunctionCurve drawn = regionAt(region, from, to, 0);
    checkFiniteAlong(entry_, drawn);
    double drawnSteps = fewestDrawnSteps(drawn, from, to);
    int samples =
        std::min(largestGrowthSamples, growthSamplesPerStep * static_cast<int>(drawnSteps));
    double growth = (to - from) * (to - from) * largestCurvatureGrowth(drawn, from, to, samples) /
                    (8 * entry_.amount) * growthMargin;
    for (double radius : checkedRadii(growth_)) {
      geom::FunctionCurve offset = regionAt(region, from, to, growth_.side * radius);
      growth = growthThatFits(offset, from, to, drawnSteps, growth, radius);
    }
    return {drawnSteps, growth / (drawnSteps * drawnSteps)};
  }

private:
  // N0: the fewest uniform steps on the drawn curve.
  double fewestDrawnSteps(const geom::Curve& drawn, double from, double to) {
    return searchedSteps(
        [&] {
          geom::BudgetedCurve budgeted(drawn, remaining());
          geom::EvaluationsCharged charged{evaluated_, budgeted};
          try {
            return fewestUniformSteps(budgeted, from, to, entry_.amount);
          } catch (const geom::EvaluationBudgetExceeded&) {
            tooLarge(evaluationLimitMessage());
          }
        },
        entry_.cutSpan, entry_.curveSpan);
  }

  // Q, raised until ceil(sqrt(N0^2 + Q r)) steps keep the exact offset at
  // `radius` within the entry's amount.
  double growthThatFits(const geom::Curve& offset, double from, double to, double drawnSteps,
                        double growth, double radius) {
    auto stepsAt = [&] { return std::ceil(std::sqrt(drawnSteps * drawnSteps + growth * radius)); };
    geom::BudgetedCurve exact(offset, remaining());
    geom::EvaluationsCharged charged{evaluated_, exact};
    try {
      for (int tries = 0;
           stepsAt() <= maximumStepsPerRegion &&
           !uniformStepsFit(exact, from, to, static_cast<int>(stepsAt()), entry_.amount);
           ++tries) {
        if (tries == growthTries) {
          tooLarge(fmt::format("cannot bound the steps of this curve's offset at radius {:g} "
                               "within its tolerance",
                               radius));
        }
        growth = growth * growthRaise + 1;
      }
    } catch (const geom::EvaluationBudgetExceeded&) {
      tooLarge(evaluationLimitMessage());
    }
    if (radius == growth_.compiledRadius && stepsAt() > maximumStepsPerRegion) {
      tooLarge(fmt::format("the offset of this curve at radius {:g} needs more than {} uniform "
                           "steps on one piece within its tolerance",
                           radius, maximumStepsPerRegion));
    }
    return growth;
  }

  static std::string evaluationLimitMessage() {
    return fmt::format("checking the steps of this curve's offset within its tolerance asks more "
                       "than {} points of it; that is the limit of one cut",
                       maximumOffsetStepEvaluations);
  }

  std::size_t remaining() const {
    return maximumOffsetStepEvaluations - std::min(evaluated_, maximumOffsetStepEvaluations);
  }

  [[noreturn]] void tooLarge(const std::string& message) const {
    throw CurveLapError(CurveLapError::Kind::ProgramTooLarge, entry_.cutSpan, message);
  }

  // The region's points with the tool centre at `distance` from the curve
  // (what the region reads from outside is asked as it is compiled, here).
  geom::FunctionCurve regionAt(std::size_t region, double from, double to, double distance) {
    ValueId distanceValue = lap_.operands.back();
    auto evaluator = std::make_shared<LapRegionEvaluator>(
        function_, lap_, region, [&](ValueId value) -> std::optional<double> {
          if (value == distanceValue) {
            return distance;
          }
          return compiled_(value);
        });
    return geom::FunctionCurve({from, to}, [evaluator](double t) { return (*evaluator)(t); });
  }

  const Function& function_;
  const Instruction& lap_;
  const CurveTableEntry& entry_;
  const OffsetStepGrowth& growth_;
  CompiledValues compiled_;
  std::size_t evaluated_ = 0;
};

} // namespace

std::vector<OffsetRegionGrowth> measureOffsetGrowth(const Function& function,
                                                    const Instruction& lap) {
  const CurveTableEntry& entry = function.curves[lap.index];
  std::vector<OffsetRegionGrowth> regions(entry.regionSteps.size());
  if (!entry.offsetGrowth) {
    return regions;
  }
  OffsetGrowthMeasure measure(function, lap);
  std::vector<CurveTableEntry::RegionPlace> places = entry.regionPlaces();
  for (std::size_t region = 0; region < regions.size() && region < places.size(); ++region) {
    if (entry.regionSteps[region] == stepsChosenByLegalisation) {
      auto [from, to] = entry.regionRange(places[region]);
      regions[region] = measure.measure(region, from, to);
    }
  }
  return regions;
}

double offsetStepsAt(const OffsetRegionGrowth& region, const OffsetStepGrowth& growth,
                     double distance) {
  using geom::MathFunction;
  double radius = growth.side > 0 ? distance : -distance;
  double share = 1 + region.growth * radius;
  double steps = region.drawnSteps * geom::computeMath(MathFunction::Sqrt, share);
  return geom::computeMath(MathFunction::Round, steps + 0.5);
}

} // namespace cncc::ir
