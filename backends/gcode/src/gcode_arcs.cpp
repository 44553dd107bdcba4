#include "cncc/backends/gcode_arcs.h"

#include "cncc/backends/gcode_writer.h"
#include "cncc/geom/geometry_error.h"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

namespace cncc::backends {

using ir::MachineEvent;

double arcRoundingAllowance(int decimals) {
  // Half an increment on each axis of the start, the end and the centre: the
  // circle the controller cuts moves by at most that much in each.
  double halfIncrement = 0.5 * std::pow(10.0, -decimals);
  return 3.0 * std::sqrt(2.0) * halfIncrement;
}

OneCutArcFit fitCutArc(const ir::CutGeometry& cut, int decimals) {
  if (std::isnan(cut.tolerance)) {
    return {std::nullopt,
            "samples= or spacing= chose its points; arcs are fitted within a tolerance="};
  }
  if (std::optional<std::string> problem = geom::findArcFittingProblem(*cut.curve)) {
    return {std::nullopt, *problem};
  }
  double allowance = arcRoundingAllowance(decimals);
  if (!(cut.tolerance > 2.0 * allowance)) {
    return {std::nullopt,
            fmt::format("its tolerance {:g} leaves no room for rounding the arcs' centres to "
                        "{} decimals",
                        cut.tolerance, decimals)};
  }
  try {
    return {geom::fitArcs(*cut.curve, {cut.tolerance - allowance}), ""};
  } catch (const geom::GeometryError& error) {
    return {std::nullopt, error.what()};
  }
}

CutArcFitting fitCutArcs(std::span<const ir::CutGeometry> cuts, bool allCuts, int decimals) {
  CutArcFitting fitting;
  fitting.fits.resize(cuts.size());
  for (std::size_t i = 0; i < cuts.size(); ++i) {
    const ir::CutGeometry& cut = cuts[i];
    // A cut with arc pieces has its circles already (move.arc).
    if (!cut.arcs.value_or(allCuts) || cut.curve == nullptr || cut.nativeArcs) {
      continue;
    }
    OneCutArcFit fit = fitCutArc(cut, decimals);
    if (fit.fit) {
      fitting.fits[i] = std::move(fit.fit);
    } else {
      fitting.problems.push_back({i, std::move(fit.problem)});
    }
  }
  return fitting;
}

namespace {

bool sameInPlane(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return (a - b).norm() <= 1e-7 * (1.0 + a.norm());
}

Eigen::Vector2d planar(const MachineEvent& event) {
  return {event.x, event.y};
}

// The lap inside the run of feed moves events[begin, end) of a fitted cut,
// `before` being where the machine was before the run; nullopt for a lone
// plunge (a ramp lap follows in the next run).
std::optional<ArcLap> lapOfRun(const std::vector<MachineEvent>& events, std::size_t begin,
                               std::size_t end, const Eigen::Vector3d& before, std::size_t cut,
                               const geom::ArcFit& fit) {
  std::size_t length = end - begin;
  std::size_t first = 0;
  if (sameInPlane(planar(events[begin]), before.head<2>())) {
    if (length == 1) {
      return std::nullopt; // the plunge of a ramped pass
    }
    first = begin + 1; // a plunge, then the lap
  } else if (length % 2 == 0) {
    first = begin + length / 2; // a ramp lap, then the lap
  } else {
    throw std::logic_error(fmt::format("cut {}: a pass of {} feed moves is neither a plunge and a "
                                       "lap nor a ramp lap and a lap",
                                       cut + 1, length));
  }
  const MachineEvent& from = events[first - 1];
  const MachineEvent& last = events[end - 1];
  bool shaped = sameInPlane(planar(from), fit.segments.front().start.head<2>()) &&
                sameInPlane(planar(last), fit.segments.back().end.head<2>());
  for (std::size_t i = first - 1; i < end && shaped; ++i) {
    shaped = std::fabs(events[i].z - last.z) <= 1e-9 * (1.0 + std::fabs(last.z)) &&
             (i < first || events[i].feed == last.feed);
  }
  if (!shaped) {
    throw std::logic_error(fmt::format(
        "cut {}: a lap does not start and end where the curve does at one height", cut + 1));
  }
  return ArcLap{first, end - 1, cut, last.z, last.feed};
}

} // namespace

std::vector<ArcLap> findArcLaps(const ir::ToolPath& path, const CutArcFits& fits) {
  std::vector<ArcLap> laps;
  const std::vector<MachineEvent>& events = path.events;
  std::optional<std::size_t> cut;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  std::size_t i = 0;
  while (i < events.size()) {
    const MachineEvent& event = events[i];
    if (event.kind == MachineEvent::Kind::CutBegin) {
      cut = static_cast<std::size_t>(event.number);
    } else if (event.kind == MachineEvent::Kind::Rapid) {
      position = {event.x, event.y, event.z};
    }
    if (event.kind != MachineEvent::Kind::Feed) {
      ++i;
      continue;
    }
    std::size_t begin = i;
    while (i < events.size() && events[i].kind == MachineEvent::Kind::Feed) {
      ++i;
    }
    if (cut && *cut < fits.size() && fits[*cut]) {
      if (std::optional<ArcLap> lap = lapOfRun(events, begin, i, position, *cut, *fits[*cut])) {
        laps.push_back(*lap);
      }
    }
    const MachineEvent& last = events[i - 1];
    position = {last.x, last.y, last.z};
  }
  return laps;
}

ir::ToolPath arcEndPoints(const ir::ToolPath& path, const CutArcFits& fits) {
  std::vector<ArcLap> laps = findArcLaps(path, fits);
  ir::ToolPath result;
  std::size_t next = 0;
  for (std::size_t i = 0; i < path.events.size(); ++i) {
    if (next < laps.size() && laps[next].first == i) {
      const ArcLap& lap = laps[next++];
      for (const geom::ArcSegment& segment : fits[lap.cut]->segments) {
        MachineEvent feed;
        feed.kind = MachineEvent::Kind::Feed;
        feed.x = segment.end.x();
        feed.y = segment.end.y();
        feed.z = lap.z;
        feed.feed = lap.feed;
        result.events.push_back(feed);
      }
      i = lap.last;
      continue;
    }
    result.events.push_back(path.events[i]);
  }
  return result;
}

namespace {

// The value the controller reads from the printed number.
double printed(double value, int decimals) {
  return std::stod(formatGcodeNumber(value, decimals));
}

// An arc too flat or too short to print as one: its sagitta is below half
// an increment, or its chord is under two increments (I J would be mostly
// rounding).
bool printsAsLine(const geom::ArcSegment& segment, int decimals) {
  double increment = std::pow(10.0, -decimals);
  double sagitta = segment.radius * (1.0 - std::cos(0.5 * std::fabs(segment.sweep)));
  double chord = (segment.end - segment.start).head<2>().norm();
  return sagitta < 0.5 * increment || chord < 2.0 * increment;
}

} // namespace

std::vector<ArcMotion> arcMotions(std::span<const geom::ArcSegment> segments,
                                  const ArcBlockFormat& format) {
  std::vector<ArcMotion> blocks;
  Eigen::Vector2d at = format.start;
  auto number = [&](double value) { return formatGcodeNumber(value, format.decimals); };
  std::string zero = format.leadingZero ? "0" : "";
  for (const geom::ArcSegment& segment : segments) {
    Eigen::Vector2d end(printed(segment.end.x(), format.decimals),
                        printed(segment.end.y(), format.decimals));
    if (end == at) {
      continue; // rounds to no movement
    }
    ArcMotion block;
    if (segment.kind == geom::ArcSegmentKind::Line || printsAsLine(segment, format.decimals)) {
      block = {"G" + zero + "1", fmt::format(" X{} Y{}", number(end.x()), number(end.y()))};
    } else {
      bool clockwise = segment.direction == geom::ArcDirection::Clockwise;
      block = {"G" + zero + (clockwise ? "2" : "3"),
               fmt::format(" X{} Y{} I{} J{}", number(end.x()), number(end.y()),
                           number(segment.centre.x() - at.x()),
                           number(segment.centre.y() - at.y()))};
    }
    if (blocks.empty()) {
      block.words += format.feedWord;
    }
    blocks.push_back(std::move(block));
    at = end;
  }
  return blocks;
}

std::vector<std::string> arcBlocks(std::span<const geom::ArcSegment> segments,
                                   const ArcBlockFormat& format) {
  std::vector<std::string> blocks;
  for (ArcMotion& block : arcMotions(segments, format)) {
    blocks.push_back(block.motion + block.words);
  }
  return blocks;
}

} // namespace cncc::backends
