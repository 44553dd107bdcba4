#include "cncc/geom/offset_clearance.h"

#include "cncc/geom/geometry_error.h"
#include "cncc/geom/offset_curve.h"

#include "scalar_optimisation.h"

#include <algorithm>
#include <cmath>

namespace cncc::geom {

namespace {

constexpr int kMinimumSamplesPerPiece = 64;
constexpr int kTotalSamples = 4096;
constexpr int kMaximumCrossingChords = 4096;

// Parameters sampling each smooth piece of the curve, ends included.
std::vector<double> sampleParameters(const Curve& curve, int perPiece, int total) {
  std::vector<double> breaks = curve.breakpoints();
  ParameterRange domain = curve.domain();
  std::vector<double> parameters;
  for (std::size_t p = 0; p + 1 < breaks.size(); ++p) {
    double length = breaks[p + 1] - breaks[p];
    int count = std::max(perPiece, static_cast<int>(total * length / domain.length()));
    for (int i = 0; i < count; ++i) {
      parameters.push_back(breaks[p] + length * i / count);
    }
  }
  parameters.push_back(domain.t1);
  return parameters;
}

// The tightest bend where `bend(t)` (a curvature, positive on the side
// looked at) is largest: sampled, each local largest refined.
template <class Bend>
CurvatureExtreme tightest(const Curve& curve, const std::vector<double>& parameters,
                          const Bend& bend) {
  std::vector<double> values;
  values.reserve(parameters.size());
  for (double t : parameters) {
    values.push_back(bend(t));
  }
  CurvatureExtreme found;
  double largest = 0.0;
  for (std::size_t i = 0; i < parameters.size(); ++i) {
    bool peak = values[i] > 0 && (i == 0 || values[i] >= values[i - 1]) &&
                (i + 1 == values.size() || values[i] >= values[i + 1]);
    if (!peak) {
      continue;
    }
    double t = parameters[i];
    double value = values[i];
    double low = parameters[i == 0 ? 0 : i - 1];
    double high = parameters[std::min(i + 1, parameters.size() - 1)];
    if (high > low) {
      detail::ScalarExtremum refined =
          detail::minimiseBrent([&](double s) { return -bend(s); }, low, high);
      if (-refined.value > value) {
        t = refined.t;
        value = -refined.value;
      }
    }
    if (value > largest) {
      largest = value;
      found = {t, curve.point(t), 1.0 / value};
    }
  }
  return found;
}

bool chordsCross(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                 const Eigen::Vector2d& d, Eigen::Vector2d& at) {
  Eigen::Vector2d r = b - a;
  Eigen::Vector2d s = d - c;
  double denominator = r.x() * s.y() - r.y() * s.x();
  if (denominator == 0) {
    return false;
  }
  Eigen::Vector2d q = c - a;
  double u = (q.x() * s.y() - q.y() * s.x()) / denominator;
  double v = (q.x() * r.y() - q.y() * r.x()) / denominator;
  if (u <= 0 || u >= 1 || v <= 0 || v >= 1) {
    return false;
  }
  at = a + u * r;
  return true;
}

} // namespace

OffsetClearance offsetClearance(const Curve& curve, double distance) {
  if (!(distance != 0) || !std::isfinite(distance)) {
    throw GeometryError("an offset needs a finite non-zero distance");
  }
  double side = distance > 0 ? 1.0 : -1.0;
  std::vector<double> parameters = sampleParameters(curve, kMinimumSamplesPerPiece, kTotalSamples);
  auto curvature = [&](double t) { return signedCurvatureOf(curve.derivatives(t)); };
  OffsetClearance clearance;
  clearance.concave = tightest(curve, parameters, [&](double t) { return side * curvature(t); });
  clearance.convex = tightest(curve, parameters, [&](double t) { return -side * curvature(t); });
  return clearance;
}

std::optional<Eigen::Vector3d> offsetSelfCrossing(const Curve& offset, int samplesPerPiece) {
  std::size_t pieces = std::max<std::size_t>(offset.breakpoints().size() - 1, 1);
  std::vector<double> parameters;
  if (pieces * 4 <= kMaximumCrossingChords) {
    int perPiece =
        std::max(4, std::min(samplesPerPiece, kMaximumCrossingChords / static_cast<int>(pieces)));
    parameters = sampleParameters(offset, perPiece, 0);
  } else {
    // Too many pieces for four chords each: equal steps over the whole curve.
    ParameterRange domain = offset.domain();
    for (int i = 0; i <= kMaximumCrossingChords; ++i) {
      parameters.push_back(domain.t0 + domain.length() * i / kMaximumCrossingChords);
    }
  }
  std::vector<Eigen::Vector2d> points;
  for (double t : parameters) {
    points.push_back(offset.point(t).head<2>());
  }
  std::size_t chords = points.size() - 1;
  bool closed = (points.front() - points.back()).norm() < 1e-9;
  for (std::size_t i = 0; i < chords; ++i) {
    for (std::size_t j = i + 2; j < chords; ++j) {
      if (closed && i == 0 && j + 1 == chords) {
        continue; // the closing chord meets the first at the start
      }
      Eigen::Vector2d at;
      if (chordsCross(points[i], points[i + 1], points[j], points[j + 1], at)) {
        return Eigen::Vector3d(at.x(), at.y(), 0.0);
      }
    }
  }
  return std::nullopt;
}

} // namespace cncc::geom
