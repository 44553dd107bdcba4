#include "cncc/backends/contour_left.h"

#include "cncc/geom/arc_length.h"
#include "cncc/geom/deviation.h"
#include "cncc/geom/segment_tree.h"
#include "plane_projection.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>

namespace cncc::backends {

namespace {

// Refinements of the largest gouge or undercut between samples, at most:
// local maxima of the sampled values within a sample spacing of the best.
constexpr std::size_t kRefinedCandidates = 16;

geom::SegmentTree pathTree(const std::vector<std::vector<Eigen::Vector3d>>& polylines) {
  std::vector<geom::LineSegment> segments;
  for (const std::vector<Eigen::Vector3d>& polyline : polylines) {
    if (polyline.size() == 1) {
      segments.push_back({polyline.front(), polyline.front()});
    }
    for (std::size_t i = 1; i < polyline.size(); ++i) {
      segments.push_back({polyline[i - 1], polyline[i]});
    }
  }
  return geom::SegmentTree(std::move(segments));
}

// Parameters of the drawn curve about `spacing` apart along it (its
// breakpoints, where a corner may be, among them); the spacing grows when
// that would be more than maximumContourSamples.
std::vector<double> sampleParameters(const geom::Curve& plan, double spacing) {
  std::vector<double> breaks = plan.breakpoints();
  std::vector<double> lengths;
  double total = 0;
  for (std::size_t i = 1; i < breaks.size(); ++i) {
    lengths.push_back(geom::arcLength(plan, breaks[i - 1], breaks[i], 1e-6));
    total += lengths.back();
  }
  if (!(spacing > 0)) {
    spacing = total / 20000;
  }
  spacing = std::max(spacing, total / static_cast<double>(maximumContourSamples));
  std::vector<double> parameters{breaks.front()};
  for (std::size_t i = 1; i < breaks.size(); ++i) {
    double count = spacing > 0 ? std::ceil(lengths[i - 1] / spacing) : 1;
    auto steps = static_cast<std::size_t>(std::max(1.0, count));
    for (std::size_t k = 1; k <= steps; ++k) {
      double fraction = static_cast<double>(k) / static_cast<double>(steps);
      parameters.push_back(breaks[i - 1] + (breaks[i] - breaks[i - 1]) * fraction);
    }
  }
  return parameters;
}

// The largest of `value` over the samples, refined between the neighbours of
// the best few sampled maxima by golden-section search.
struct Largest {
  double value = -std::numeric_limits<double>::infinity();
  double parameter = 0;
};
Largest largestOf(const std::vector<double>& parameters, const std::vector<double>& sampled,
                  double spacing, const std::function<double(double)>& value) {
  Largest best;
  std::vector<std::size_t> maxima;
  for (std::size_t i = 0; i < sampled.size(); ++i) {
    bool aboveLeft = i == 0 || sampled[i] >= sampled[i - 1];
    bool aboveRight = i + 1 == sampled.size() || sampled[i] >= sampled[i + 1];
    if (aboveLeft && aboveRight) {
      maxima.push_back(i);
    }
    if (sampled[i] > best.value) {
      best = {sampled[i], parameters[i]};
    }
  }
  std::sort(maxima.begin(), maxima.end(),
            [&](std::size_t a, std::size_t b) { return sampled[a] > sampled[b]; });
  double bar = best.value - spacing;
  const double golden = (std::sqrt(5.0) - 1) / 2;
  for (std::size_t k = 0; k < std::min(maxima.size(), kRefinedCandidates); ++k) {
    std::size_t i = maxima[k];
    if (sampled[i] < bar) {
      break;
    }
    double a = parameters[i == 0 ? 0 : i - 1];
    double b = parameters[std::min(i + 1, parameters.size() - 1)];
    double c = b - golden * (b - a);
    double d = a + golden * (b - a);
    double fc = value(c);
    double fd = value(d);
    for (int step = 0; step < 60 && b - a > 1e-14 * (1 + std::fabs(a)); ++step) {
      if (fc >= fd) {
        b = d, d = c, fd = fc;
        c = b - golden * (b - a);
        fc = value(c);
      } else {
        a = c, c = d, fc = fd;
        d = a + golden * (b - a);
        fd = value(d);
      }
    }
    for (auto [t, f] : {std::pair{c, fc}, std::pair{d, fd}}) {
      if (f > best.value) {
        best = {f, t};
      }
    }
  }
  return best;
}

} // namespace

ContourLeft measureContourLeft(std::size_t cutIndex, const ir::CutGeometry& cut,
                               const std::vector<std::vector<Eigen::Vector3d>>& polylines,
                               double accuracy) {
  ContourLeft left;
  left.cut = cutIndex;
  left.tolerance = cut.tolerance;
  left.toolRadius = cut.toolRadius;
  if (cut.drawnCurve == nullptr || cut.curve == nullptr || polylines.empty()) {
    return left;
  }
  PlaneProjection drawn(*cut.drawnCurve);
  PlaneProjection ideal(*cut.curve);
  geom::SegmentTree path = pathTree(polylines);
  // Where the exact offset stays farther than r from the curve (the inside
  // of a corner), the tool leaves that much however well the path keeps it.
  geom::CurveProximity exact(ideal, accuracy);
  double r = cut.toolRadius;
  auto executed = [&](double t) { return path.nearest(drawn.point(t)).distance; };
  // The material left at a point of the drawn curve `distance` from the path.
  auto leftAt = [&](const Eigen::Vector3d& point, double distance) {
    return distance > r ? distance - std::max(r, exact.sampledDistance(point)) : distance - r;
  };
  auto undercut = [&](double t) {
    Eigen::Vector3d point = drawn.point(t);
    return leftAt(point, path.nearest(point).distance);
  };
  double spacing = std::isfinite(cut.tolerance) ? cut.tolerance / 4 : 0;
  std::vector<double> parameters = sampleParameters(drawn, spacing);
  left.samples = parameters.size();
  std::vector<double> gouges, undercuts;
  double step = 0; // the largest gap between samples: how much a value may rise between two
  Eigen::Vector3d previous = drawn.point(parameters.front());
  for (double t : parameters) {
    Eigen::Vector3d point = drawn.point(t);
    step = std::max(step, (point - previous).norm());
    previous = point;
    double distance = path.nearest(point).distance;
    gouges.push_back(r - distance);
    undercuts.push_back(leftAt(point, distance));
  }
  Largest gouge = largestOf(parameters, gouges, step, [&](double t) { return r - executed(t); });
  Largest material = largestOf(parameters, undercuts, step, undercut);
  if (gouge.value > 0) {
    left.largestGouge = gouge.value;
    left.gougeAt = drawn.point(gouge.parameter);
  }
  if (material.value > 0) {
    left.largestUndercut = material.value;
    left.undercutAt = drawn.point(material.parameter);
  }
  return left;
}

} // namespace cncc::backends
