#include "cncc/ir/polynomial_move.h"

#include "cncc/geom/geometry_error.h"
#include "cncc/geom/polynomial_span.h"
#include "cncc/ir/interpreter.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace cncc::ir {

namespace {

// The TNC's limit on how far a spline may start from the previous end (mm).
constexpr double startTolerance = 1e-3;
// The largest deviation of the recorded chords from the cubic, and their
// largest number per span (a bound on the work a huge span makes).
constexpr double chordTolerance = 1e-5;
constexpr int maximumChords = 100000;

// The span over u in [0, 1] (ascending powers c0..c3) as the TNC writes it,
// in t = 1 - u: K1 = -P'(1), K2 = P''(1) / 2, K3 = -P'''(1) / 6.
PolynomialMove fromPowerBasis(const geom::PolynomialSpan& span) {
  std::array<Eigen::Vector3d, 4> c{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(),
                                   Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  for (std::size_t k = 0; k < span.coefficients.size(); ++k) {
    c[k] = span.coefficients[k].head<3>();
  }
  PolynomialMove move;
  move.end = c[0] + c[1] + c[2] + c[3];
  move.coefficients[0] = -c[3];
  move.coefficients[1] = c[2] + 3 * c[3];
  move.coefficients[2] = -(c[1] + 2 * c[2] + 3 * c[3]);
  return move;
}

} // namespace

Eigen::Vector3d PolynomialMove::pointAt(double t) const {
  return ((coefficients[0] * t + coefficients[1]) * t + coefficients[2]) * t + end;
}

Eigen::Vector3d PolynomialMove::startDirection() const {
  return -(3 * coefficients[0] + 2 * coefficients[1] + coefficients[2]);
}

Eigen::Vector3d PolynomialMove::endDirection() const {
  return -coefficients[2];
}

void PolynomialMove::startAt(const Eigen::Vector3d& start) {
  Eigen::Vector3d shift = start - this->start();
  coefficients[0] -= 2 * shift;
  coefficients[1] += 3 * shift;
}

std::vector<PolynomialMove> polynomialMoves(const geom::NurbsCurve& curve) {
  if (curve.degree() > 3) {
    throw geom::GeometryError(
        fmt::format("a curve of degree {} has no exact cubic spans", curve.degree()));
  }
  std::vector<PolynomialMove> moves;
  for (const geom::PolynomialSpan& span : geom::toPowerBasis(curve)) {
    if (span.isRational()) {
      throw geom::GeometryError("a rational curve has no exact polynomial spans");
    }
    moves.push_back(fromPowerBasis(span));
  }
  return moves;
}

double polynomialTransitionDegrees(const PolynomialMove& before, const PolynomialMove& after) {
  Eigen::Vector3d a = before.endDirection();
  Eigen::Vector3d b = after.startDirection();
  if (a.norm() == 0 || b.norm() == 0) {
    return 0;
  }
  double cosine = std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0);
  return std::acos(cosine) * 180 / 3.14159265358979323846;
}

PolynomialMove polynomialMoveOf(std::span<const double, 12> values) {
  PolynomialMove move;
  move.end = {values[0], values[1], values[2]};
  for (int k = 0; k < 3; ++k) {
    for (int axis = 0; axis < 3; ++axis) {
      move.coefficients[k][axis] = values[3 + 3 * axis + k];
    }
  }
  return move;
}

std::vector<double> polynomialMoveTable(const std::vector<PolynomialMove>& spans) {
  std::vector<double> table;
  for (const PolynomialMove& span : spans) {
    table.insert(table.end(), {span.end.x(), span.end.y(), span.end.z()});
    for (int axis = 0; axis < 3; ++axis) {
      for (const Eigen::Vector3d& coefficient : span.coefficients) {
        table.push_back(coefficient[axis]);
      }
    }
  }
  return table;
}

std::optional<std::vector<PolynomialMove>> readPolynomialMoveTable(std::span<const double> table,
                                                                   std::string* problem) {
  if (table.empty() || table.size() % 12 != 0) {
    if (problem != nullptr) {
      *problem = fmt::format("a table of {} numbers holds no cubic spans of 12 numbers each",
                             table.size());
    }
    return std::nullopt;
  }
  std::vector<PolynomialMove> spans;
  for (std::size_t at = 0; at < table.size(); at += 12) {
    spans.push_back(polynomialMoveOf(table.subspan(at).first<12>()));
  }
  return spans;
}

void polynomialMove(const std::array<double, 3>& start, const PolynomialMove& move, double feed,
                    std::vector<MachineEvent>& events) {
  for (const Eigen::Vector3d& vector :
       {move.end, move.coefficients[0], move.coefficients[1], move.coefficients[2]}) {
    if (!vector.allFinite()) {
      throw InterpreterError("a polynomial move with a value that is not finite");
    }
  }
  Eigen::Vector3d from = move.start();
  if ((from - Eigen::Vector3d(start[0], start[1], start[2])).norm() > startTolerance) {
    throw InterpreterError(fmt::format(
        "a polynomial move starts at ({:g}, {:g}, {:g}), {:g} "
        "from where the machine is ({:g}, {:g}, {:g})",
        from.x(), from.y(), from.z(), (from - Eigen::Vector3d(start[0], start[1], start[2])).norm(),
        start[0], start[1], start[2]));
  }
  // A chord over a parameter step h is within |P''| h^2 / 8 of the cubic.
  double curvature =
      (6 * move.coefficients[0].cwiseAbs() + 2 * move.coefficients[1].cwiseAbs()).norm();
  double steps = std::ceil(std::sqrt(curvature / (8 * chordTolerance)));
  int count = static_cast<int>(std::clamp(steps, 1.0, double(maximumChords)));
  for (int i = 1; i <= count; ++i) {
    double t = i == count ? 0.0 : 1.0 - double(i) / count;
    Eigen::Vector3d point = i == count ? move.end : move.pointAt(t);
    MachineEvent event;
    event.kind = MachineEvent::Kind::Feed;
    event.x = point.x();
    event.y = point.y();
    event.z = point.z();
    event.feed = feed;
    events.push_back(event);
  }
}

} // namespace cncc::ir
