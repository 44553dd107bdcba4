// What controller_cuts.cpp plans for each loop of a cut, and the bounds
// arithmetic it shares with controller_nurbs_spans.cpp (NURBS spans whose
// control points depend on parameters).
#pragma once

#include "part_lowering.h"

#include "cncc/ir/curve_lap_steps.h"

#include <array>
#include <optional>
#include <utility>
#include <vector>

namespace cncc::ir::lowering {

using Polynomial = std::vector<double>; // ascending powers of u

inline constexpr int maximumStepsPerPiece = maximumStepsPerRegion;

Polynomial derivativeOf(const Polynomial& polynomial);
// The coefficients of p in the Bernstein basis of its degree on [0, 1].
Polynomial bernsteinCoefficients(const Polynomial& polynomial);
// An upper bound of |p(u)| on [0, 1] (its largest Bernstein coefficient).
double supremumBound(const Polynomial& polynomial);
// Every coordinate's bound, as one bound of the vector's length.
double vectorSupremumBound(const std::vector<Polynomial>& coordinates);

// constant + sum of coefficient * value: the bounds of a NURBS span, kept
// in this form so that the controller computes each as one flat sum.
struct LinearForm {
  double constant = 0;
  std::vector<std::pair<Scalar, double>> terms;

  void add(Scalar value, double coefficient) {
    if (value.isConstant()) {
      constant += coefficient * value.constant;
      return;
    }
    for (auto& [existing, factor] : terms) {
      if (existing.value == value.value) {
        factor += coefficient;
        return;
      }
    }
    terms.emplace_back(value, coefficient);
  }
  void add(const LinearForm& other, double coefficient) {
    constant += coefficient * other.constant;
    for (const auto& [value, factor] : other.terms) {
      add(value, coefficient * factor);
    }
  }
  bool isConstant() const { return terms.empty(); }
  Scalar scalar(Arithmetic& math) const {
    Scalar sum = Scalar::of(constant);
    for (const auto& [value, factor] : terms) {
      sum = math.add(sum, factor == 1 ? value : math.multiply(value, Scalar::of(factor)));
    }
    return sum;
  }
};

// One loop of the cut: a piece, or a knot span of a NURBS piece.
struct ControllerSegment {
  std::size_t piece = 0;
  std::size_t span = 0;
  // The piece's own parameter range (a NURBS span: its local u, 0 to 1).
  double from = 0;
  double to = 1;
  // Chosen at compile time; 0 when the controller computes stepCount.
  int steps = 0;
  std::optional<Scalar> stepCount;
  bool isNurbs = false;
  // An arc piece: move.arc blocks (native_arcs.cpp), no steps.
  bool isArc = false;
  // A line, arc, polar or param piece that depends on controller values:
  // evaluated from its symbolic form over start .. end.
  const SymbolicPiece* symbolic = nullptr;
  Scalar start, end;
  // A NURBS span of constant shape moved by a transform of controller values.
  const RuntimeTransform* moved = nullptr;
  // A NURBS span whose control points depend on parameters, split as
  //   W(u) = reference + Wc(u) + sum_d (w_d - reference) N_d(u),
  //   X(u) = Xc(u) + sum_d w_d x_d N_d(u)   (likewise y, z),
  // with Xc, Wc the constant control points' share (literals) and, per
  // dependent control point d, its basis function N_d (literals) and its
  // homogeneous point (computed on the controller once).
  bool split = false;
  bool rational = false;
  double referenceWeight = 1;
  std::array<Polynomial, 4> constantPart;
  std::vector<Polynomial> dependentBasis;
  std::vector<std::array<Scalar, 4>> dependentPoints;
  // A rational split span walked with a step computed at each point
  // (rational_span_walk.cpp), with a positive lower bound of its weights,
  // the chord budget and the transform's stretch.
  bool stepPerPoint = false;
  Scalar smallestWeight = Scalar::of(1);
  double budget = 0;
  Scalar stretch = Scalar::of(1);
};

// Whether the segment is the last (first) of its piece: a knot span may not be.
inline bool endsItsPiece(const ControllerSegment& segment, const CurvePiece& piece) {
  return !segment.isNurbs || segment.span + 1 == piece.spans.size();
}
inline bool startsItsPiece(const ControllerSegment& segment) {
  return !segment.isNurbs || segment.span == 0;
}

} // namespace cncc::ir::lowering
