#include "cncc/ir/spline_move.h"

#include "cncc/geom/controller_bspline.h"
#include "cncc/geom/discretisation.h"
#include "cncc/geom/geometry_error.h"
#include "cncc/geom/nurbs_curve.h"
#include "cncc/geom/polynomial_span.h"
#include "cncc/ir/interpreter.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace cncc::ir {

namespace {

constexpr std::size_t kHeader = 5;
constexpr std::size_t kMaximumPoints = 1'000'000;
// An XY move shorter than this gives no direction (as the controller model).
constexpr double kNoDirection = 1e-9;

// Points along a non-rational piecewise polynomial (a C or A spline) whose
// chords stay within `tolerance`: on each span, |C''(u)| <= sum k (k - 1)
// |c_k| for u in [0, 1], and a chord of parameter length h sags at most
// h^2 / 8 of it. Nothing for a rational span.
std::optional<std::vector<Eigen::Vector3d>> polynomialChords(const geom::Curve& curve,
                                                             double tolerance) {
  const auto* pieces = dynamic_cast<const geom::PiecewisePolynomialCurve*>(&curve);
  if (pieces == nullptr) {
    return std::nullopt;
  }
  std::vector<Eigen::Vector3d> points{pieces->spans().front().pointAt(0)};
  for (const geom::PolynomialSpan& span : pieces->spans()) {
    if (span.isRational()) {
      return std::nullopt;
    }
    double bend = 0;
    for (std::size_t k = 2; k < span.coefficients.size(); ++k) {
      bend += double(k * (k - 1)) * span.coefficients[k].head<3>().norm();
    }
    double steps = std::clamp(std::ceil(std::sqrt(bend / (8 * tolerance))), 1.0, 1e6);
    for (double i = 1; i <= steps; ++i) {
      points.push_back(span.pointAt(i == steps ? 1.0 : i / steps));
    }
  }
  return points;
}

} // namespace

std::vector<double> splineMoveTable(const SplineBlockData& data) {
  std::vector<double> table{static_cast<double>(data.kind), static_cast<double>(data.degree),
                            static_cast<double>(data.start), static_cast<double>(data.end),
                            static_cast<double>(data.points.size())};
  for (const Eigen::Vector3d& point : data.points) {
    table.insert(table.end(), {point.x(), point.y(), point.z()});
  }
  if (data.kind == SplineKind::BSpline) {
    table.insert(table.end(), data.weights.begin(), data.weights.end());
    table.insert(table.end(), data.intervals.begin(), data.intervals.end());
  }
  return table;
}

std::optional<SplineBlockData> readSplineMoveTable(std::span<const double> table,
                                                   std::string* problem) {
  auto fail = [&](std::string message) -> std::optional<SplineBlockData> {
    if (problem != nullptr) {
      *problem = std::move(message);
    }
    return std::nullopt;
  };
  auto whole = [](double value, double low, double high) {
    return value >= low && value <= high && value == std::floor(value);
  };
  if (table.size() < kHeader || !whole(table[0], 0, 2) || !whole(table[2], 0, 2) ||
      !whole(table[3], 0, 2) || !whole(table[4], 1, double(kMaximumPoints))) {
    return fail("its table does not start with a kind (0 to 2), a degree, two transitions (0 to "
                "2) and a point count (1 or more)");
  }
  SplineBlockData data;
  data.kind = static_cast<SplineKind>(table[0]);
  bool bspline = data.kind == SplineKind::BSpline;
  if (bspline ? !whole(table[1], 2, 3) : table[1] != 3) {
    return fail(bspline ? "its B spline's degree is not 2 or 3"
                        : "its interpolating spline's degree is not 3");
  }
  data.degree = static_cast<int>(table[1]);
  data.start = static_cast<geom::SplineEndCondition>(table[2]);
  data.end = static_cast<geom::SplineEndCondition>(table[3]);
  auto n = static_cast<std::size_t>(table[4]);
  std::size_t expected = kHeader + 3 * n + (bspline ? 2 * n : 0);
  if (table.size() != expected || (bspline && n < std::size_t(data.degree))) {
    return fail(fmt::format(
        "its table of {} entries does not hold {} points{}", table.size(), n,
        bspline ? fmt::format(" with weights and intervals (at least {})", data.degree) : ""));
  }
  for (double value : table) {
    if (!std::isfinite(value)) {
      return fail("its table holds a number that is not finite");
    }
  }
  for (std::size_t i = 0; i < n; ++i) {
    const double* point = &table[kHeader + 3 * i];
    data.points.emplace_back(point[0], point[1], point[2]);
  }
  if (bspline) {
    std::span<const double> rest = table.subspan(kHeader + 3 * n);
    data.weights.assign(rest.begin(), rest.begin() + static_cast<long>(n));
    data.intervals.assign(rest.begin() + static_cast<long>(n), rest.end());
    if (std::any_of(data.weights.begin(), data.weights.end(), [](double w) { return w <= 0; }) ||
        std::any_of(data.intervals.begin(), data.intervals.end(), [](double l) { return l < 0; })) {
      return fail("its B spline has a weight that is not positive or a negative interval");
    }
  }
  return data;
}

std::shared_ptr<const geom::Curve> splineMoveCurve(const SplineBlockData& data,
                                                   const Eigen::Vector3d& start, double z,
                                                   const std::optional<Eigen::Vector3d>& arrival) {
  std::vector<Eigen::Vector3d> points = data.points;
  for (Eigen::Vector3d& point : points) {
    point.z() += z;
  }
  try {
    if (data.kind == SplineKind::BSpline) {
      return std::make_shared<geom::NurbsCurve>(
          geom::bsplineOfBlocks(start, data.degree, points, data.weights, data.intervals));
    }
    points.insert(points.begin(), start);
    geom::SplineTransitions transitions;
    transitions.start = data.start;
    transitions.end = data.end;
    transitions.startDirection = arrival;
    if (data.kind == SplineKind::CSpline) {
      return std::make_shared<geom::PiecewisePolynomialCurve>(geom::cSpline(points, transitions));
    }
    return std::make_shared<geom::PiecewisePolynomialCurve>(geom::aSpline(points, transitions));
  } catch (const geom::GeometryError& error) {
    throw InterpreterError(fmt::format("a spline move has no curve: {}", error.what()));
  }
}

void splineMove(std::uint32_t table, std::span<const double> data, double z, double feed,
                std::vector<MachineEvent>& events) {
  std::string problem;
  std::optional<SplineBlockData> blocks = readSplineMoveTable(data, &problem);
  if (!blocks) {
    throw InterpreterError("a spline move whose " + problem);
  }
  // Where the machine is, and the XY direction of the feed move that got it there.
  Eigen::Vector3d start = Eigen::Vector3d::Zero();
  std::optional<Eigen::Vector3d> arrival;
  auto last = std::find_if(events.rbegin(), events.rend(), isMove);
  if (last != events.rend()) {
    start = {last->x, last->y, last->z};
    auto before = std::find_if(last + 1, events.rend(), isMove);
    if (last->kind == MachineEvent::Kind::Feed && before != events.rend()) {
      Eigen::Vector3d direction(last->x - before->x, last->y - before->y, 0);
      if (direction.norm() > kNoDirection) {
        arrival = direction;
      }
    }
  }
  std::shared_ptr<const geom::Curve> curve = splineMoveCurve(*blocks, start, z, arrival);
  double size = 0;
  for (const Eigen::Vector3d& point : blocks->points) {
    size = std::max(size, (point - start).norm());
  }
  double tolerance = std::max(1e-5, 1e-7 * size);
  std::optional<std::vector<Eigen::Vector3d>> points = polynomialChords(*curve, tolerance);
  if (!points) {
    points = geom::discretiseByChordTolerance(*curve, tolerance).points;
  }
  for (std::size_t i = 1; i < points->size(); ++i) {
    MachineEvent event;
    event.kind = MachineEvent::Kind::Feed;
    event.x = (*points)[i].x();
    event.y = (*points)[i].y();
    event.z = (*points)[i].z();
    event.feed = feed;
    event.splineTable = table + 1;
    event.splineStart = i == 1;
    events.push_back(event);
  }
}

} // namespace cncc::ir
