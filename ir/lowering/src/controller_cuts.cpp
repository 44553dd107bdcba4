// A `curve` statement whose curve reads part parameters (on every target),
// or any curve on a controller that runs the curve loop itself
// (LoweringOptions::controllerLoops, the macro targets): no constant
// tables. Each smooth piece (each knot span of a NURBS) is cut in uniform
// parameter steps by a loop the controller runs, and the sweep's passes are
// a loop too, so part parameters stay editable at the machine. Where the
// host computes the program, bound-controller-steps chooses chords on the
// same laps at the compiled values instead (the lowering is the same).
//
// The tolerance promise holds for the values the program runs with. The
// controller rounds every coordinate to its least input increment, so the
// chord error may use the tolerance less half an increment per moving axis
// (the budget). Then:
// - Constant geometry: the step count of each piece is the fewest uniform
//   steps whose chords all stay within the budget, measured exactly on the
//   curve (geom::chordDeviation) by the legalisation (curve_lap_steps.h;
//   an offset's too, curve_lap_offset_steps.h); here only whether one
//   chord is enough (a lap of single steps is no loop). A NURBS span is
//   evaluated by Horner's rule in the loop index, its power-basis
//   coefficients rescaled to the index and written as literals; a rational
//   span adds its denominator and one division per coordinate.
// - Geometry that depends on parameters: the controller computes the step
//   count of the piece, once per cut, from a bound M >= |C''| over the
//   piece: a chord over a parameter step h deviates at most h^2 M / 8, so
//   N = (length of the domain) * sqrt(M / (8 budget)) steps, rounded up,
//   suffice. The bounds are derived with the functions that compute them
//   (curvature_bounds.cpp); a NURBS span whose control points depend on
//   parameters bounds its chords more tightly from its Bezier control
//   points (cncc/lowering/rational_span_steps.h, used by
//   controller_nurbs_spans.cpp). The pieces' symbolic forms come from
//   symbolic_curves.cpp.
// samples=N gives N - 1 equal steps of a single piece's parameter, and
// entry=ramp a first lap descending along each segment (RampSegment). A cut
// this mode cannot treat (spacing=, samples= over several pieces, a curve
// whose dependence on parameters the bounds do not follow, a ramp whose
// shares would change with the parameters) is lowered by the table-driven
// lowering of cuts.cpp, and what it reads is fixed. A count the program
// would compute past a piece's limit at the compiled values is the
// legalisation's (bound-controller-steps: points chosen when compiling).
#include "controller_segment.h"

#include "cncc/geom/deviation.h"
#include "cncc/geom/discretisation.h"
#include "cncc/geom/evaluation_budget.h"
#include "cncc/geom/geometry_error.h"
#include "cncc/geom/nurbs_curve.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>

namespace cncc::ir::lowering {

using namespace frontend;

Polynomial derivativeOf(const Polynomial& polynomial) {
  Polynomial derivative;
  for (std::size_t k = 1; k < polynomial.size(); ++k) {
    derivative.push_back(static_cast<double>(k) * polynomial[k]);
  }
  return derivative;
}

// The coefficients of p in the Bernstein basis of its degree on [0, 1].
Polynomial bernsteinCoefficients(const Polynomial& polynomial) {
  std::size_t n = polynomial.size();
  auto choose = [](std::size_t a, std::size_t b) {
    double value = 1;
    for (std::size_t i = 1; i <= b; ++i) {
      value = value * static_cast<double>(a - b + i) / static_cast<double>(i);
    }
    return value;
  };
  Polynomial coefficients(n, 0.0);
  std::size_t degree = n == 0 ? 0 : n - 1;
  for (std::size_t j = 0; j < n; ++j) {
    for (std::size_t k = 0; k <= j; ++k) {
      coefficients[j] += choose(j, k) / choose(degree, k) * polynomial[k];
    }
  }
  return coefficients;
}

// An upper bound of |p(u)| on [0, 1]: the largest Bernstein coefficient of
// p (the curve of a polynomial lies in the hull of its Bezier coefficients).
double supremumBound(const Polynomial& polynomial) {
  double largest = 0;
  for (double coefficient : bernsteinCoefficients(polynomial)) {
    largest = std::max(largest, std::abs(coefficient));
  }
  // A few ulp for the rounding of the conversion.
  return largest * (1 + 1e-12);
}

// Every coordinate's bound, as one bound of the vector's length.
double vectorSupremumBound(const std::vector<Polynomial>& coordinates) {
  double sum = 0;
  for (const Polynomial& coordinate : coordinates) {
    double bound = supremumBound(coordinate);
    sum += bound * bound;
  }
  return std::sqrt(sum);
}

const Expr* PartLowering::curveArgument(const CutStmt& cut, std::string_view name) {
  if (cut.curve->kind != ExprKind::Call) {
    return nullptr;
  }
  const auto& call = as<CallExpr>(*cut.curve);
  if (call.callee != "nurbs" && call.callee != "bspline" && call.callee != "bezier") {
    return nullptr;
  }
  return builtinArgument(call, name);
}

// The elements of a list literal (or of the let it names) lowered one by
// one; nullopt where the list is not written out.
std::optional<std::vector<std::optional<Lowered>>>
PartLowering::symbolicList(const Expr& expression) {
  return symbolicList(expression, bindings_, environment_);
}

std::optional<std::vector<std::optional<Lowered>>>
PartLowering::symbolicList(const Expr& expression, const Bindings& bindings,
                           const Environment& environment) {
  if (expression.kind == ExprKind::Name) {
    auto found = letValues_.find(as<NameExpr>(expression).declaration);
    return found == letValues_.end() ? std::nullopt
                                     : symbolicList(*found->second, bindings, environment);
  }
  if (expression.kind != ExprKind::List) {
    return std::nullopt;
  }
  std::vector<std::optional<Lowered>> elements;
  for (const ExprPtr& element : as<ListExpr>(expression).elements) {
    elements.push_back(tryLower(*element, bindings, environment));
  }
  return elements;
}

bool PartLowering::lowerControllerCut(const CutStmt& cut, const CutCurve& curve) {
  // A curve that reads parameters is planned so on every target: the
  // host's split-arc-laps and bound-controller-steps cut it in whole turns
  // of its arcs and chords of its other pieces at the compiled values.
  bool hostPlans = !parametersOf(*cut.curve).empty() || runtimeOffset_;
  if ((!options_.controllerLoops && !hostPlans) || modifierValue(cut, "spacing") != nullptr) {
    return false;
  }
  bool ramp = rampEntry(cut);
  if (!safe_) {
    fail(cut.span, "this cut has no safe height; write 'safe z=Z' before it",
         DiagnosticKind::NoSafeHeight);
  }
  // samples=N: N - 1 equal steps of the parameter, whatever the tolerance.
  std::optional<int> uniformSteps;
  if (modifierValue(cut, "samples") != nullptr) {
    uniformSteps = static_cast<int>(sampleCount(cut)) - 1;
  }
  ToleranceBudget tolerances = toleranceBudget(cut);
  double tolerance = tolerances.tolerance;
  bool planar = liesInThePlaneZero(*curve.geometry);
  double rounding = tolerances.pointRounding(planar ? 2 : 3);
  double budget = tolerances.forPoints(planar ? 2 : 3);
  // Arcs are exact: a curve of arcs alone spends no tolerance on its points.
  bool arcsAlone =
      std::all_of(curve.pieces.begin(), curve.pieces.end(),
                  [](const CurvePiece& piece) { return piece.value->kind == CurveKind::Arc; });
  if (!uniformSteps && !arcsAlone && !(budget > 0)) {
    fail(modifierValue(cut, "tolerance") ? modifierValue(cut, "tolerance")->span : cut.span,
         fmt::format("tolerance={:g} is not larger than the controller's rounding of the "
                     "coordinates ({:.6g}, half its increment {:g} on each axis)",
                     tolerance, rounding, options_.coordinateIncrement),
         DiagnosticKind::InvalidTolerance);
  }
  if (chordsTheLegalisationSteps(cut, curve, uniformSteps.has_value(), tolerances)) {
    stepsLeftToTheLegalisation_ = true;
    singleStepsLeftToTheLegalisation_ =
        uniformSteps ? *uniformSteps == 1 : cutInSingleSteps(curve, budget);
    return false; // chords, cut in steps by choose-controller-steps
  }
  if (ramp) {
    checkRampCloses(curve, cut);
  }
  // The pieces as the controller computes them; without them (a curve
  // built in a way the walk does not follow) the pieces are planned at the
  // defaults and what they read is fixed.
  std::optional<std::vector<SymbolicPiece>> symbolic = symbolicPieces(*cut.curve);
  if (symbolic && !symbolicPiecesUsable(*symbolic, curve)) {
    symbolic.reset();
  }
  if (!symbolic && !parametersOf(*cut.curve).empty()) {
    return false; // the tables, with what the curve reads fixed
  }
  std::optional<std::vector<ControllerSegment>> planned =
      planControllerSegments(curve, cut, budget, symbolic ? &*symbolic : nullptr, uniformSteps);
  if (!planned) {
    return false;
  }
  if (runtimeOffset_ && !planOffsetSteps(curve, *planned, budget)) {
    return false;
  }
  if (ramp && planned->size() > 1) {
    // The shares of the descent are lengths at the defaults: with pieces
    // that change with parameters, they would not match the pieces cut.
    for (const ControllerSegment& segment : *planned) {
      if (segment.symbolic != nullptr || segment.split) {
        return false;
      }
    }
  }
  if (runtimeOffset_ && !runtimeOffset_->radius.isConstant()) {
    guardRuntimeRadius(*runtimeOffset_);
  }
  checkMethod(cut, blocksAskedBy(cut));
  Scalar feed = cutFeed(cut);
  ValueId feedValue = arithmetic_.value(feed);
  ValueId safeValue = arithmetic_.value(*safe_);
  bool arcs = hasArcPiece(curve) && !uniformSteps;
  if (runtimeOffset_) {
    for (const PieceJoin& join : runtimeOffset_->joins) {
      arcs = arcs || join.kind == PieceJoin::CornerArc;
    }
  }
  bool activatesLengthOffset =
      beginCutMoves({runtimeOffset_ ? runtimeOffset_->compiled : curve.geometry, tolerance,
                     cut.span, methodOf(cut), arcs ? CutArcs::Native : CutArcs::None});
  noteMethodSpan(cut);
  if (runtimeOffset_) {
    markCutBeside(curve.geometry, std::fabs(runtimeOffset_->compiledDistance));
  }
  for (const ControllerSegment& segment : *planned) {
    if (segment.isArc && segment.symbolic != nullptr) {
      guardArc(symbolicArcPath(*segment.symbolic, *curve.pieces[segment.piece].value));
    }
  }

  const ControllerSegment& first = planned->front();
  const ControllerSegment& last = planned->back();
  auto endPoint = [&](const ControllerSegment& segment, bool atEnd) {
    CurvePoint point = segmentEndPoint(curve, segment, atEnd, cut);
    return runtimeOffset_ ? offsetSegmentEnd(curve, segment, atEnd, point) : point;
  };

  // The passes, computed on the controller (sweeps.cpp). Each lap a
  // curve.lap, which expand-controller-loops writes out; beside the curve,
  // never a ramp (controller_offset_laps.cpp).
  CurvePoint start = endPoint(first, false);
  CurvePoint finish = endPoint(last, true);
  if (runtimeOffset_ && runtimeOffset_->closed &&
      runtimeOffset_->joins.back().kind == PieceJoin::CornerArc) {
    finish = start; // after the arc about the corner where the path closes
  }
  SteppedLap lap = runtimeOffset_ ? besideSteppedLap(cut, curve, *planned, budget)
                                  : steppedLap(cut, curve, *planned, uniformSteps ? 0.0 : budget);
  ValueId startX = arithmetic_.value(start.x);
  ValueId startY = arithmetic_.value(start.y);
  ValueId finishY = arithmetic_.value(finish.y);
  ValueId finishX = arithmetic_.value(finish.x);
  emitSweep(cut, ramp, {startX, startY, safeValue, activatesLengthOffset, start.z},
            {finishX, finishY}, feedValue, [&](ValueId zFrom, ValueId zTo) {
              emitSteppedLap(curve, lap, *planned, zFrom, zTo, feedValue, cut);
            });
  return true;
}

// A curve of constants (no parameter or loop variable read, on its own
// curve) cut within a tolerance whose chords keep within it after the
// rounding of three axes, or in samples= over one piece that is no NURBS
// (whose knot spans the samples would cross) and no arc: its laps are the
// chords or the samples every target's lowering gives it (a knot span's
// region its polynomial in u, as a stepped span's; with arc pieces, the
// host's arc cut: move.arc blocks between a lap for each other piece),
// which choose-controller-steps cuts in steps the controller counts.
bool PartLowering::chordsTheLegalisationSteps(const CutStmt& cut, const CutCurve& curve,
                                              bool uniformSteps,
                                              const ToleranceBudget& tolerances) {
  if (runtimeOffset_ || curve.beside || !parametersOf(*cut.curve).empty()) {
    return false;
  }
  if (uniformSteps) {
    return curve.pieces.size() == 1 && curve.pieces.front().value->kind != CurveKind::Nurbs &&
           curve.pieces.front().value->kind != CurveKind::Arc;
  }
  return tolerances.forPoints() > 0;
}

// Whether one uniform step over [from, to] keeps the curve within the
// budget less the literals' share (8 significant digits of coefficients
// and the step move its points a few micrometres at most), its points
// charged to `evaluated` (bounded by maximumStepSearchEvaluations over a
// cut). Throws as geom's budget and uniformStepsFit do.
bool PartLowering::oneStepKeeps(const geom::Curve& geometry, double from, double to, double budget,
                                std::size_t& evaluated) {
  geom::BudgetedCurve counted(geometry, maximumStepSearchEvaluations - evaluated);
  EvaluationsCharged charged{evaluated, counted};
  return uniformStepsFit(counted, from, to, 1, measuredBudget(budget));
}

// Whether one step keeps every piece (every knot span) but the arcs of a
// curve of constants within the budget, as expand-controller-loops will
// measure it: its laps then print no loop, which the nesting of the
// program's loops does not count (runtime_control.cpp).
bool PartLowering::cutInSingleSteps(const CutCurve& curve, double budget) {
  std::size_t evaluated = 0; // over the pieces, as the step searches
  auto fits = [&](const geom::Curve& geometry, double from, double to) {
    try {
      return oneStepKeeps(geometry, from, to, budget, evaluated);
    } catch (const std::exception&) {
      return false; // counted as a loop; the legalisation reports it
    }
  };
  for (const CurvePiece& piece : curve.pieces) {
    if (piece.value->kind == CurveKind::Arc) {
      continue; // move.arc blocks, no lap (lowerHostArcCut)
    }
    if (piece.spans.empty()) {
      geom::ParameterRange domain = piece.geometry->domain();
      if (!fits(TransformedCurve(piece.geometry, piece.transform), domain.t0, domain.t1)) {
        return false;
      }
      continue;
    }
    for (const geom::PolynomialSpan& span : piece.spans) {
      auto own =
          std::make_shared<geom::PiecewisePolynomialCurve>(std::vector<geom::PolynomialSpan>{span});
      if (!fits(TransformedCurve(own, piece.transform), span.t0, span.t1)) {
        return false;
      }
    }
  }
  return true;
}

// The drawn curve's point where the segment starts or ends.
CurvePoint PartLowering::segmentEndPoint(const CutCurve& curve, const ControllerSegment& segment,
                                         bool atEnd, const CutStmt& cut) {
  if (segment.symbolic != nullptr) {
    return symbolicPointAt(*segment.symbolic, *curve.pieces[segment.piece].value,
                           atEnd ? segment.end : segment.start);
  }
  Scalar local = Scalar::of(atEnd ? segment.to : segment.from);
  if (segment.split) {
    return movedSplitSpanPoint(segment, local);
  }
  if (segment.isNurbs) {
    return nurbsSegmentPoint(curve, segment, local, cut);
  }
  return pointAt(curve, segment.piece, segment.span, local, cut);
}

Scalar PartLowering::stepsOf(const ControllerSegment& segment) {
  return segment.steps > 0 ? Scalar::of(segment.steps) : *segment.stepCount;
}

// Every piece found, in the compile-time curve's order and of the same kind.
bool PartLowering::symbolicPiecesUsable(const std::vector<SymbolicPiece>& pieces,
                                        const CutCurve& curve) {
  if (pieces.size() != curve.pieces.size()) {
    return false;
  }
  for (std::size_t p = 0; p < pieces.size(); ++p) {
    CurveKind kind = curve.pieces[p].value->kind;
    std::string_view callee = pieces[p].call->callee;
    bool nurbs = callee == "nurbs" || callee == "bspline" || callee == "bezier";
    bool same = nurbs ? kind == CurveKind::Nurbs : callee == curve.pieces[p].value->constructor;
    if (!same) {
      return false;
    }
  }
  return true;
}

std::optional<std::vector<ControllerSegment>>
PartLowering::planControllerSegments(const CutCurve& curve, const CutStmt& cut, double budget,
                                     const std::vector<SymbolicPiece>* symbolic,
                                     std::optional<int> uniformSteps) {
  std::vector<ControllerSegment> segments;
  // The points the step searches ask of the curve, over the cut: each
  // search is bounded by maximumStepsPerPiece, their sum by
  // maximumStepSearchEvaluations.
  std::size_t evaluated = 0;
  // For the legalisation to choose: whether one step is enough, as the
  // lowering asks (a lap of single steps is no loop); beside the curve,
  // the offset's (planOffsetSteps).
  auto constantSteps = [&](const geom::Curve& geometry, double from, double to) {
    if (runtimeOffset_) {
      return stepsChosenByLegalisation; // the offset's (planOffsetSteps)
    }
    auto search = [&] {
      return oneStepKeeps(geometry, from, to, budget, evaluated) ? 1 : stepsChosenByLegalisation;
    };
    try {
      return searchedSteps(search, cut.span, cut.curve->span);
    } catch (const CurveLapError& error) {
      reportCurveLapError(error, *diagnostics_);
      throw LoweringFailed{};
    }
  };
  if (uniformSteps &&
      (curve.pieces.size() != 1 || curve.pieces.front().value->kind == CurveKind::Nurbs)) {
    return std::nullopt; // samples= over several pieces: the tables
  }
  for (std::size_t p = 0; p < curve.pieces.size(); ++p) {
    const CurvePiece& piece = curve.pieces[p];
    const CurveValue& value = *piece.value;
    if (value.kind == CurveKind::Nurbs) {
      const SymbolicPiece* own = symbolic != nullptr ? &(*symbolic)[p] : nullptr;
      for (std::size_t s = 0; s < piece.spans.size(); ++s) {
        ControllerSegment segment;
        segment.piece = p;
        segment.span = s;
        segment.isNurbs = true;
        if (own != nullptr && own->dependent && !own->shapeDependent) {
          segment.moved = &own->transform;
          if (!segment.moved->norm.isConstant()) {
            // A size the controller computes: the span's |C''| bound (its
            // control points' hull) times the scale, over u in [0, 1].
            geom::PolynomialSpan span = cleanedSpan(piece.spans[s]);
            if (span.isRational()) {
              return std::nullopt;
            }
            std::vector<Polynomial> curvature;
            for (int c = 0; c < 3; ++c) {
              Polynomial coordinate;
              for (const geom::HomogeneousPoint& coefficient : span.coefficients) {
                coordinate.push_back(coefficient[c]);
              }
              curvature.push_back(derivativeOf(derivativeOf(coordinate)));
            }
            Scalar bound = arithmetic_.multiply(
                segment.moved->norm, Scalar::of(vectorSupremumBound(curvature) / (8 * budget)));
            segment.stepCount = roundedUpSteps(arithmetic_.unary(Opcode::Sqrt, bound));
          }
        }
        segments.push_back(segment);
      }
      continue;
    }
    ControllerSegment segment;
    segment.piece = p;
    geom::ParameterRange domain = piece.geometry->domain();
    segment.from = domain.t0;
    segment.to = domain.t1;
    if (value.kind == CurveKind::Arc && !uniformSteps) {
      segment.isArc = true;
      segment.steps = 1;
      if (symbolic != nullptr && (*symbolic)[p].dependent) {
        segment.symbolic = &(*symbolic)[p];
        std::tie(segment.start, segment.end) = symbolicRange(*segment.symbolic);
      }
    } else if (symbolic != nullptr && (*symbolic)[p].dependent) {
      segment.symbolic = &(*symbolic)[p];
      std::tie(segment.start, segment.end) = symbolicRange(*segment.symbolic);
      if (uniformSteps) {
        segment.steps = *uniformSteps;
      } else {
        segment.stepCount = symbolicStepCount(*segment.symbolic, value, budget);
        if (!segment.stepCount) {
          return std::nullopt;
        }
        if (segment.stepCount->isConstant()) {
          segment.steps = static_cast<int>(segment.stepCount->constant);
          segment.stepCount.reset();
        }
      }
    } else if (value.kind == CurveKind::Line) {
      segment.steps = 1;
    } else if (uniformSteps) {
      segment.steps = *uniformSteps;
    }
    segments.push_back(segment);
  }
  // NURBS spans whose control points depend on parameters are split (see
  // ControllerSegment); constant pieces and spans take the fewest uniform
  // steps, measured on the true curve.
  std::map<std::size_t, NurbsLists> lists;
  for (ControllerSegment& segment : segments) {
    const CurvePiece& piece = curve.pieces[segment.piece];
    if (segment.steps != 0 || segment.stepCount) {
      continue;
    }
    if (!segment.isNurbs) {
      auto moved = std::make_shared<TransformedCurve>(piece.geometry, piece.transform);
      segment.steps = constantSteps(*moved, segment.from, segment.to);
      continue;
    }
    if (symbolic != nullptr && (*symbolic)[segment.piece].shapeDependent) {
      const SymbolicPiece& own = (*symbolic)[segment.piece];
      auto found = lists.find(segment.piece);
      if (found == lists.end()) {
        std::optional<NurbsLists> pointsAndWeights = nurbsLists(own);
        if (!pointsAndWeights) {
          return std::nullopt;
        }
        found = lists.emplace(segment.piece, std::move(*pointsAndWeights)).first;
        if (found->second.weights) {
          guardWeights(*found->second.weights);
        }
      }
      const std::optional<SymbolicList>& points = found->second.points;
      const std::optional<SymbolicList>& weights = found->second.weights;
      segment.moved = &own.transform;
      planSplitSpan(piece, weights ? &*weights : nullptr, points ? &*points : nullptr, segment,
                    budget, own.transform.norm);
      if (segment.split) {
        continue;
      }
      if (!own.transform.norm.isConstant()) {
        return std::nullopt; // a constant span of a scaled piece
      }
    }
    geom::PolynomialSpan span = piece.spans[segment.span];
    double stretch = segment.moved != nullptr ? std::abs(segment.moved->norm.constant)
                                              : piece.transform.stretch();
    if (!spanLiteralsFit(cleanedSpan(span), cut, stretch)) {
      return std::nullopt; // the tables, with the span's points computed on the host
    }
    auto own =
        std::make_shared<geom::PiecewisePolynomialCurve>(std::vector<geom::PolynomialSpan>{span});
    TransformedCurve moved(own, piece.transform);
    segment.steps = constantSteps(moved, span.t0, span.t1);
  }
  return segments;
}

} // namespace cncc::ir::lowering
