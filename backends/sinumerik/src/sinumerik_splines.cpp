#include "sinumerik_splines.h"

#include "cncc/backends/sinumerik_controller.h"
#include "cncc/geom/bspline_fitting.h"
#include "cncc/geom/curve_deviation.h"
#include "cncc/geom/geometry_error.h"
#include "cncc/geom/nurbs_curve.h"
#include "cncc/geom/polynomial_span.h"
#include "cncc/geom/spline_knot_placement.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>

namespace cncc::backends::sinumerik {

namespace {

using geom::SplineEndCondition;

constexpr double kMaximumWeight = 3.0;    // PW range 0..3
constexpr double kWeightStep = 1e-4;      // PW increment
constexpr int kIntervalExtraDecimals = 3; // PL gets more decimals than coordinates
// Each retry with the printed numbers over the tolerance aims this much lower.
constexpr double kRetryFactor = 0.9;
constexpr int kRetries = 4;
// The share of the tolerance an analytic curve's stand-in may be off by.
constexpr double kStandInShare = 1e-4;

// The measurement's accuracy, a share of the tolerance: the fits aim this
// much lower.
constexpr double kMeasureAccuracy = 1e-3;

double measure(const geom::Curve& spline, const geom::Curve& curve, double tolerance) {
  double accuracy = std::isnan(tolerance) ? 1e-6 : tolerance * kMeasureAccuracy;
  return geom::measureCurveDeviation(spline, curve, {accuracy}).maxDeviation();
}

int intervalDecimals(int decimals) {
  return decimals + kIntervalExtraDecimals;
}

// The blocks of a clamped spline: its points after the first, PW and PL.
SplineBlocks blocksOfSpline(const geom::NurbsCurve& spline, double weightScale, int decimals) {
  SplineBlocks blocks;
  blocks.kind = SplineKind::BSpline;
  blocks.degree = spline.degree();
  const std::vector<double>& knots = spline.knots().values();
  std::size_t n = spline.controlPoints().size() - 1;
  for (std::size_t i = 1; i <= n; ++i) {
    blocks.points.push_back(roundPoint(spline.controlPoints()[i], decimals));
    double weight = spline.weights()[i] * weightScale;
    blocks.weights.push_back(std::round(weight / kWeightStep) * kWeightStep);
    blocks.intervals.push_back(roundTo(knots[i + 1] - knots[i], intervalDecimals(decimals)));
  }
  return blocks;
}

// What the controller builds from the blocks.
geom::NurbsCurve modelOf(const SplineBlocks& blocks, const Eigen::Vector3d& start) {
  return bsplineOfBlocks(start, blocks.degree, blocks.points, blocks.weights, blocks.intervals);
}

// A NURBS of degree 2 or 3 whose weights fit PW once scaled: its own blocks.
// Nothing (and `note` says why) when it cannot be written as it is.
std::optional<SplineBlocks> exactBlocks(const geom::NurbsCurve& nurbs, const SplineRequest& request,
                                        std::string& note) {
  int degree = nurbs.degree();
  if (degree != 2 && degree != 3) {
    note = fmt::format("degree {} (SD is 2 or 3)", degree);
    return std::nullopt;
  }
  if (!nurbs.knots().isClamped()) {
    note = "its knots are not clamped";
    return std::nullopt;
  }
  // The start point's weight cannot be programmed and is 1: scale every
  // weight by the same factor, which leaves a NURBS unchanged.
  double scale = 1.0 / nurbs.weights().front();
  auto [lowest, highest] = std::minmax_element(nurbs.weights().begin(), nurbs.weights().end());
  double top = *highest * scale;
  double bottom = *lowest * scale;
  if (top > kMaximumWeight + 1e-12 || bottom < kWeightStep) {
    note = fmt::format("its weights relative to the first run from {:g} to {:g}, outside PW's "
                       "range 0..3",
                       bottom, top);
    return std::nullopt;
  }
  SplineBlocks blocks = blocksOfSpline(nurbs, scale, request.decimals);
  Eigen::Vector3d start = roundPoint(nurbs.controlPoints().front(), request.decimals);
  blocks.deviation = measure(modelOf(blocks, start), *request.curve, request.tolerance);
  if (!(blocks.deviation <= request.tolerance) && !std::isnan(request.tolerance)) {
    note = fmt::format("its printed numbers (weights in steps of 0.0001) move it by {:.3g} mm",
                       blocks.deviation);
    return std::nullopt;
  }
  blocks.exact = true;
  return blocks;
}

// The curve's own points as control points (samples= or spacing=, as the
// published programs did), PL the chord lengths.
SplineBlocks samplesAsControlPoints(const SplineRequest& request) {
  SplineBlocks blocks;
  blocks.kind = SplineKind::BSpline;
  const std::vector<Eigen::Vector3d>& samples = request.samples;
  blocks.degree = samples.size() >= 4 ? 3 : 2;
  if (samples.size() < 3) {
    throw geom::GeometryError("a B spline needs at least three points");
  }
  std::vector<double> knots(std::size_t(blocks.degree) + 1, 0.0);
  std::vector<Eigen::Vector3d> points;
  for (const Eigen::Vector3d& sample : samples) {
    points.push_back(roundPoint(sample, request.decimals));
  }
  geom::NurbsCurve spline = geom::NurbsCurve::bspline(blocks.degree, points);
  double length = 0;
  for (std::size_t i = 1; i < points.size(); ++i) {
    length += (points[i] - points[i - 1]).norm();
  }
  blocks = blocksOfSpline(spline, 1.0, request.decimals);
  for (double& interval : blocks.intervals) {
    interval = roundTo(interval * length, intervalDecimals(request.decimals));
  }
  blocks.deviation = measure(modelOf(blocks, points.front()), *request.curve, request.tolerance);
  return blocks;
}

SplineBlocks fittedBlocks(const SplineRequest& request) {
  double target = request.tolerance * (1 - kMeasureAccuracy) - roundingBound(request.decimals);
  for (int attempt = 0; attempt < kRetries && target > 0; ++attempt, target *= kRetryFactor) {
    geom::BSplineFitOptions options;
    options.tolerance = target;
    geom::BSplineFit fit = geom::fitBSpline(*request.curve, options);
    SplineBlocks blocks = blocksOfSpline(fit.spline, 1.0, request.decimals);
    Eigen::Vector3d start = roundPoint(fit.spline.controlPoints().front(), request.decimals);
    blocks.deviation = measure(modelOf(blocks, start), *request.curve, request.tolerance);
    if (blocks.deviation <= request.tolerance) {
      return blocks;
    }
  }
  throw geom::GeometryError(
      fmt::format("no B spline with coordinates of {} decimals stays within {:g} mm of this curve",
                  request.decimals, request.tolerance));
}

SplineBlocks bsplineBlocks(const SplineRequest& request) {
  if (std::isnan(request.tolerance)) {
    return samplesAsControlPoints(request);
  }
  std::string note;
  if (const auto* nurbs = dynamic_cast<const geom::NurbsCurve*>(request.curve)) {
    if (std::optional<SplineBlocks> blocks = exactBlocks(*nurbs, request, note)) {
      return *blocks;
    }
  }
  SplineBlocks blocks = fittedBlocks(request);
  blocks.note = note.empty() ? "" : "re-fitted: " + note;
  return blocks;
}

geom::SplineTransitions transitionsFor(const SplineRequest& request) {
  geom::SplineTransitions transitions;
  switch (request.transitions) {
  case SinumerikTransitions::Automatic:
    transitions.start =
        request.startDirection ? SplineEndCondition::Tangent : SplineEndCondition::Natural;
    transitions.startDirection = request.startDirection;
    transitions.end = SplineEndCondition::Natural;
    break;
  case SinumerikTransitions::Natural:
    transitions.start = transitions.end = SplineEndCondition::Natural;
    break;
  case SinumerikTransitions::Auto:
    transitions.start = transitions.end = SplineEndCondition::Auto;
    break;
  }
  return transitions;
}

geom::InterpolatingSplineKind modelKind(SplineKind kind) {
  return kind == SplineKind::CSpline ? geom::InterpolatingSplineKind::CSpline
                                     : geom::InterpolatingSplineKind::ASpline;
}

// Points on the curve through which the modelled spline, built from the
// printed numbers, stays within the tolerance.
SplineBlocks interpolatingBlocks(const SplineRequest& request) {
  geom::SplineTransitions transitions = transitionsFor(request);
  SplineBlocks blocks;
  blocks.kind = request.kind;
  blocks.start = transitions.start;
  blocks.end = transitions.end;
  auto finish = [&](const std::vector<Eigen::Vector3d>& points) {
    std::vector<Eigen::Vector3d> printed;
    for (const Eigen::Vector3d& point : points) {
      // Knots closer than the printed resolution become one.
      Eigen::Vector3d rounded = roundPoint(point, request.decimals);
      if (printed.empty() || rounded != printed.back()) {
        printed.push_back(rounded);
      }
    }
    geom::PiecewisePolynomialCurve model =
        geom::modelSpline(modelKind(request.kind), printed, transitions);
    blocks.points.assign(printed.begin() + 1, printed.end());
    blocks.deviation = measure(model, *request.curve, request.tolerance);
  };
  if (std::isnan(request.tolerance)) {
    finish(request.samples);
    return blocks;
  }
  // Rounding a knot moves the spline by about as much, its neighbours'
  // tangents a little more.
  double target = request.tolerance * (1 - kMeasureAccuracy) - 3 * roundingBound(request.decimals);
  for (int attempt = 0; attempt < kRetries && target > 0; ++attempt, target *= kRetryFactor) {
    geom::SplineKnotPlacementOptions options;
    options.kind = modelKind(request.kind);
    options.tolerance = target;
    options.transitions = transitions;
    geom::SplineKnots knots = geom::placeSplineKnots(*request.curve, options);
    finish(knots.points);
    if (blocks.deviation <= request.tolerance) {
      return blocks;
    }
  }
  throw geom::GeometryError(fmt::format("no {} knots with coordinates of {} decimals keep the "
                                        "spline within {:g} mm of this curve",
                                        request.kind == SplineKind::CSpline ? "CSPLINE" : "ASPLINE",
                                        request.decimals, request.tolerance));
}

// A stand-in for an analytic curve, whose every evaluation runs the part's
// expressions: quintic Hermite spans through its points, first and second
// derivatives at equal parameter steps on each smooth piece, the steps
// halved until the spans' midpoints and quarter points are within `error`
// of the curve (the error falls like h^6). The searches run on it, the
// deviations they find get `error` added.
// Its joins are not the curve's breakpoints (it is C2 there, and within
// `error`), so it reports the curve's own: the fits place knots by the
// curve, not by the stand-in's spans.
class StandInCurve : public geom::PiecewisePolynomialCurve {
public:
  StandInCurve(std::vector<geom::PolynomialSpan> spans, std::vector<double> breakpoints)
      : PiecewisePolynomialCurve(std::move(spans)), breakpoints_(std::move(breakpoints)) {}
  std::vector<double> breakpoints() const override { return breakpoints_; }

private:
  std::vector<double> breakpoints_;
};

struct CurveStandIn {
  std::unique_ptr<StandInCurve> curve;
  double error = 0;
};

geom::PolynomialSpan quinticSpan(const geom::Curve& curve, double t0, double t1) {
  geom::CurveDerivatives a = curve.derivatives(t0);
  geom::CurveDerivatives b = curve.derivatives(t1);
  double h = t1 - t0;
  Eigen::Vector3d p = b.point - a.point;
  Eigen::Vector3d v0 = a.first * h, v1 = b.first * h;
  Eigen::Vector3d s0 = a.second * h * h, s1 = b.second * h * h;
  std::array<Eigen::Vector3d, 6> c = {
      a.point,
      v0,
      0.5 * s0,
      10 * p - 6 * v0 - 4 * v1 - 1.5 * s0 + 0.5 * s1,
      -15 * p + 8 * v0 + 7 * v1 + 1.5 * s0 - s1,
      6 * p - 3 * v0 - 3 * v1 - 0.5 * s0 + 0.5 * s1,
  };
  geom::PolynomialSpan span;
  span.t0 = t0;
  span.t1 = t1;
  for (std::size_t k = 0; k < c.size(); ++k) {
    span.coefficients.push_back({c[k].x(), c[k].y(), c[k].z(), k == 0 ? 1.0 : 0.0});
  }
  return span;
}

std::optional<CurveStandIn> standInFor(const geom::Curve& curve, double error) {
  constexpr int kInitialSteps = 32;
  constexpr int kMaximumSteps = 1 << 14;
  std::vector<double> breakpoints = curve.breakpoints();
  std::vector<geom::PolynomialSpan> spans;
  for (std::size_t piece = 0; piece + 1 < breakpoints.size(); ++piece) {
    double a = breakpoints[piece];
    double b = breakpoints[piece + 1];
    for (int steps = kInitialSteps;; steps *= 2) {
      if (steps > kMaximumSteps) {
        return std::nullopt;
      }
      std::vector<geom::PolynomialSpan> pieceSpans;
      bool close = true;
      for (int i = 0; i < steps && close; ++i) {
        double t0 = a + (b - a) * i / steps;
        double t1 = i + 1 == steps ? b : a + (b - a) * (i + 1) / steps;
        pieceSpans.push_back(quinticSpan(curve, t0, t1));
        for (double u : {0.25, 0.5, 0.75}) {
          double t = t0 + (t1 - t0) * u;
          close = close && (pieceSpans.back().pointAt(u) - curve.point(t)).norm() <= error;
        }
      }
      if (close) {
        spans.insert(spans.end(), pieceSpans.begin(), pieceSpans.end());
        break;
      }
    }
  }
  return CurveStandIn{std::make_unique<StandInCurve>(std::move(spans), std::move(breakpoints)),
                      error};
}

// The request on a stand-in of its curve when that is analytic.
struct CheapRequest {
  SplineRequest request;
  std::optional<CurveStandIn> standIn;
};

CheapRequest cheaper(const SplineRequest& request) {
  CheapRequest cheap{request, std::nullopt};
  bool analytic = dynamic_cast<const geom::NurbsCurve*>(request.curve) == nullptr &&
                  dynamic_cast<const geom::PiecewisePolynomialCurve*>(request.curve) == nullptr;
  if (analytic && !std::isnan(request.tolerance)) {
    cheap.standIn = standInFor(*request.curve, request.tolerance * kStandInShare);
    if (cheap.standIn) {
      cheap.request.curve = cheap.standIn->curve.get();
      cheap.request.tolerance = request.tolerance - cheap.standIn->error;
    }
  }
  return cheap;
}

} // namespace

double roundingBound(int decimals) {
  return 0.5 * std::pow(10.0, -decimals) * std::sqrt(3.0);
}

double roundTo(double value, int decimals) {
  double scale = std::pow(10.0, decimals);
  double rounded = std::round(value * scale) / scale;
  return rounded == 0.0 ? 0.0 : rounded; // never -0
}

Eigen::Vector3d roundPoint(const Eigen::Vector3d& point, int decimals) {
  return {roundTo(point.x(), decimals), roundTo(point.y(), decimals), roundTo(point.z(), decimals)};
}

SplineBlocks chooseSplineBlocks(const SplineRequest& request) {
  CheapRequest cheap = cheaper(request);
  SplineBlocks blocks = request.kind == SplineKind::BSpline ? bsplineBlocks(cheap.request)
                                                            : interpolatingBlocks(cheap.request);
  if (cheap.standIn) {
    blocks.deviation += cheap.standIn->error;
  }
  return blocks;
}

} // namespace cncc::backends::sinumerik
