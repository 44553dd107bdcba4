#include "cncc/ir/nurbs_move.h"

#include "cncc/geom/discretisation.h"
#include "cncc/geom/geometry_error.h"
#include "cncc/ir/interpreter.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace cncc::ir {

namespace {

// How far the first control point may lie from where the machine is (the
// controllers compare the printed numbers; the IR's are on the grid).
constexpr double startTolerance = 1e-6;

} // namespace

std::vector<double> nurbsMoveTable(const geom::NurbsCurve& curve) {
  std::vector<double> table{static_cast<double>(curve.degree() + 1)};
  const std::vector<double>& knots = curve.knots().values();
  table.insert(table.end(), knots.begin(), knots.end());
  for (const Eigen::Vector3d& point : curve.controlPoints()) {
    table.insert(table.end(), {point.x(), point.y(), point.z()});
  }
  return table;
}

std::optional<NurbsBlockData> readNurbsMoveTable(std::span<const double> table, std::size_t weights,
                                                 std::string* problem) {
  auto fail = [&](std::string message) -> std::optional<NurbsBlockData> {
    if (problem != nullptr) {
      *problem = std::move(message);
    }
    return std::nullopt;
  };
  if (table.empty() || !(table[0] >= 2 && table[0] <= 16) || table[0] != std::floor(table[0])) {
    return fail("its table does not start with an order of 2 to 16");
  }
  auto order = static_cast<std::size_t>(table[0]);
  if (weights < order || table.size() != 1 + weights + order + 3 * weights) {
    return fail(fmt::format("its table of {} entries does not hold order {}, {} knots and {} "
                            "control points",
                            table.size(), order, weights + order, weights));
  }
  NurbsBlockData data;
  data.order = static_cast<int>(order);
  data.knots.assign(table.begin() + 1, table.begin() + 1 + static_cast<long>(weights + order));
  std::span<const double> coordinates = table.subspan(1 + weights + order);
  for (std::size_t i = 0; i < weights; ++i) {
    data.points.emplace_back(coordinates[3 * i], coordinates[3 * i + 1], coordinates[3 * i + 2]);
  }
  return data;
}

geom::NurbsCurve nurbsMoveCurve(const NurbsBlockData& data, double z,
                                std::span<const double> weights) {
  std::vector<Eigen::Vector3d> points = data.points;
  for (Eigen::Vector3d& point : points) {
    point.z() += z;
  }
  std::vector<double> weightValues(weights.begin(), weights.end());
  try {
    return geom::NurbsCurve(geom::KnotVector(data.knots, data.order - 1), std::move(points),
                            std::move(weightValues));
  } catch (const geom::GeometryError& error) {
    throw InterpreterError(fmt::format("a NURBS move has no curve: {}", error.what()));
  }
}

void nurbsMove(const std::array<double, 3>& start, std::span<const double> table, double z,
               double feed, std::span<const double> weights, std::vector<MachineEvent>& events) {
  std::string problem;
  std::optional<NurbsBlockData> data = readNurbsMoveTable(table, weights.size(), &problem);
  if (!data) {
    throw InterpreterError("a NURBS move whose " + problem);
  }
  geom::NurbsCurve curve = nurbsMoveCurve(*data, z, weights);
  const Eigen::Vector3d& first = curve.controlPoints().front();
  if ((first - Eigen::Vector3d(start[0], start[1], start[2])).norm() > startTolerance) {
    throw InterpreterError(fmt::format("a NURBS move starts at ({:g}, {:g}, {:g}), not at its "
                                       "first control point ({:g}, {:g}, {:g})",
                                       start[0], start[1], start[2], first.x(), first.y(),
                                       first.z()));
  }
  double size = 0;
  for (const Eigen::Vector3d& point : curve.controlPoints()) {
    size = std::max(size, (point - first).norm());
  }
  geom::CurveSamples samples = geom::discretiseByChordTolerance(curve, std::max(1e-5, 1e-7 * size));
  for (std::size_t i = 1; i < samples.points.size(); ++i) {
    MachineEvent event;
    event.kind = MachineEvent::Kind::Feed;
    event.x = samples.points[i].x();
    event.y = samples.points[i].y();
    event.z = samples.points[i].z();
    event.feed = feed;
    events.push_back(event);
  }
}

} // namespace cncc::ir
