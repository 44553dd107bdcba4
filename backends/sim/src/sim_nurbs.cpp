// G06.2 NURBS interpolation (Fanuc; Mitsubishi after G05 P10000), as
// TARGETS.md gives the rules: `G06.2 P<order> K X Y Z R F` starts the curve
// at the current position, each further block with K and axis words adds a
// control point with its knot, K-only blocks give the last `order` knots, and
// the first block without K ends the curve, which is then executed exactly:
// the NURBS through the control points as the controller rounds them to its
// increment, recorded as feed moves between curve points whose chords stay
// within 1e-5 (program units) of it.
#include "sim_machine.h"

#include "cncc/geom/nurbs_curve.h"

#include <Eigen/Geometry>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string_view>

namespace cncc::backends::sim {

namespace {

constexpr double chordAccuracy = 1e-5;

bool contains(const std::vector<int>& codes, int code) {
  return std::find(codes.begin(), codes.end(), code) != codes.end();
}

// The literal words of a NURBS block: axis words with the coordinate
// decimals, K and R (Mitsubishi) with at most 4.
void checkNurbsLiterals(const Block& block, int coordinateDecimals, bool mitsubishi) {
  for (const Word& word : block.words) {
    if (!word.isLiteral) {
      continue;
    }
    bool axis = std::string_view("XYZ").find(word.letter) != std::string_view::npos;
    bool parameter = word.letter == 'K' || word.letter == 'R';
    if (axis && word.literalDecimals > coordinateDecimals) {
      failInBlock(block, fmt::format("the address {} has {} decimals; the least input increment "
                                     "allows {}",
                                     word.letter, word.literalDecimals, coordinateDecimals));
    }
    if (parameter && mitsubishi && word.literalDecimals > 4) {
      failInBlock(block, fmt::format("G06.2 on M80: {} has {} decimals; at most 4", word.letter,
                                     word.literalDecimals));
    }
  }
}

void checkLettersIn(const Block& block, const std::map<char, double>& values,
                    std::string_view allowed) {
  for (const auto& [letter, value] : values) {
    if (allowed.find(letter) == std::string_view::npos) {
      failInBlock(block, fmt::format("the address {} is not allowed in a G06.2 block", letter));
    }
  }
}

void checkMitsubishiRange(const Block& block, char letter, double value) {
  if (value < 0.0001 || value > 99.9999) {
    failInBlock(block, fmt::format("G06.2 on M80: {}{} is outside 0.0001..99.9999", letter, value));
  }
}

// Curve points from `from` to `to` (parameters) whose chords stay within
// chordAccuracy of the curve, `to` included.
void sampleSpan(const geom::NurbsCurve& curve, double from, double to, int depth,
                std::vector<Eigen::Vector3d>& points) {
  double middle = 0.5 * (from + to);
  Eigen::Vector3d a = curve.point(from);
  Eigen::Vector3d b = curve.point(to);
  Eigen::Vector3d m = curve.point(middle);
  Eigen::Vector3d chord = b - a;
  double distance = chord.norm() > 0 ? (m - a).cross(chord).norm() / chord.norm() : (m - a).norm();
  // Quarter points too, so that an S-shaped span is not taken for straight.
  Eigen::Vector3d q = curve.point(0.5 * (from + middle));
  double quarter = chord.norm() > 0 ? (q - a).cross(chord).norm() / chord.norm() : (q - a).norm();
  if (depth < 30 && (depth < 3 || std::max(distance, quarter) > chordAccuracy)) {
    sampleSpan(curve, from, middle, depth + 1, points);
    sampleSpan(curve, middle, to, depth + 1, points);
    return;
  }
  points.push_back(b);
}

} // namespace

bool Machine::executeNurbsWords(const Block& block, const std::vector<int>& gCodes,
                                const std::vector<int>& mCodes,
                                const std::map<char, double>& values) {
  bool mitsubishi = profile_.name == "m80";
  int decimals = profile_.coordinateDecimals + (modal_.inches ? 1 : 0);
  if (contains(gCodes, 50)) {
    checkLettersIn(block, values, "P");
    double mode = values.count('P') > 0 ? values.at('P') : -1;
    if (mode != 10000 && mode != 0) {
      failInBlock(block, "G05 takes P10000 (high-speed machining, needed for NURBS) or P0");
    }
    if (nurbs_.active) {
      finishNurbs(block);
    }
    nurbs_.highSpeedMode = mode == 10000;
    return true;
  }
  bool starts = contains(gCodes, 62);
  if (!starts && !nurbs_.active) {
    return false;
  }
  if (!starts && values.count('K') == 0) {
    finishNurbs(block); // this block runs as usual
    return false;
  }
  if (!mCodes.empty() || gCodes.size() > (starts ? 1u : 0u)) {
    failInBlock(block, "no other G code and no auxiliary function inside NURBS interpolation");
  }
  if (values.count('K') == 0) {
    failInBlock(block, "every G06.2 block needs a knot K");
  }
  checkNurbsLiterals(block, decimals, mitsubishi);
  double knot = values.at('K');
  if (mitsubishi) {
    checkMitsubishiRange(block, 'K', knot);
  }
  if (starts) {
    if (mitsubishi && !nurbs_.highSpeedMode) {
      failInBlock(block, "G06.2 on M80 needs G05 P10000 first");
    }
    if (nurbs_.active) {
      finishNurbs(block);
    }
    checkLettersIn(block, values, "PKXYZRF");
    if (!modal_.absolute) {
      failInBlock(block, "G06.2 is simulated in absolute coordinates (G90) only");
    }
    double order = values.count('P') > 0 ? values.at('P') : 4;
    if (order != 2 && order != 3 && order != 4) {
      failInBlock(block, fmt::format("G06.2 P{}: the order must be 2, 3 or 4", order));
    }
    if (values.count('F') > 0) {
      if (values.at('F') <= 0) {
        failInBlock(block, "the feed F must be positive");
      }
      modal_.feed = values.at('F');
    }
    if (!modal_.feed) {
      failInBlock(block, "G06.2 without a feed: no F has been commanded");
    }
    nurbs_ = NurbsInProgress{
        true, nurbs_.highSpeedMode, static_cast<int>(order), block.line, {}, {}, {}, false};
  } else {
    checkLettersIn(block, values, "KXYZR");
  }
  bool point =
      starts || values.count('X') + values.count('Y') + values.count('Z') + values.count('R') > 0;
  nurbs_.knots.push_back(knot);
  if (!point) {
    nurbs_.knotsOnly = true;
    return true;
  }
  if (nurbs_.knotsOnly) {
    failInBlock(block, "a control point after the K-only blocks of the last knots");
  }
  Point3 last = nurbs_.points.empty() ? modal_.position
                                      : Point3{nurbs_.points.back().x(), nurbs_.points.back().y(),
                                               nurbs_.points.back().z()};
  auto axis = [&](char letter, double previous) {
    auto found = values.find(letter);
    return found == values.end() ? previous : roundToIncrement(found->second);
  };
  Eigen::Vector3d controlPoint(axis('X', last.x), axis('Y', last.y), axis('Z', last.z));
  double weight = values.count('R') > 0 ? values.at('R') : 1.0;
  if (!(weight > 0)) {
    failInBlock(block, fmt::format("G06.2 weight R{} must be positive", weight));
  }
  if (mitsubishi) {
    checkMitsubishiRange(block, 'R', weight);
  }
  if (starts) {
    Eigen::Vector3d here(modal_.position.x, modal_.position.y, modal_.position.z);
    if ((controlPoint - here).norm() > increment() / 2) {
      failInBlock(block, fmt::format("G06.2: the first control point ({}, {}, {}) is not the "
                                     "current position ({}, {}, {})",
                                     controlPoint.x(), controlPoint.y(), controlPoint.z(), here.x(),
                                     here.y(), here.z()));
    }
  }
  nurbs_.points.push_back(controlPoint);
  nurbs_.weights.push_back(weight);
  return true;
}

void Machine::finishNurbs(const Block& block) {
  NurbsInProgress nurbs = std::move(nurbs_);
  nurbs_ = NurbsInProgress{};
  nurbs_.highSpeedMode = nurbs.highSpeedMode;
  std::size_t order = static_cast<std::size_t>(nurbs.order);
  std::string where = fmt::format("the NURBS from line {}", nurbs.firstLine);
  if (nurbs.knots.size() != nurbs.points.size() + order) {
    failInBlock(block, fmt::format("{} has {} knots; {} control points of order {} need {}", where,
                                   nurbs.knots.size(), nurbs.points.size(), order,
                                   nurbs.points.size() + order));
  }
  for (std::size_t i = 1; i < order; ++i) {
    if (nurbs.knots[i] != nurbs.knots[0] ||
        nurbs.knots[nurbs.knots.size() - 1 - i] != nurbs.knots.back()) {
      failInBlock(block,
                  fmt::format("{}: the first and last {} knots must be equal", where, order));
    }
  }
  if (std::optional<std::string> problem = geom::NurbsCurve::findProblem(
          nurbs.knots, nurbs.order - 1, nurbs.points, nurbs.weights)) {
    failInBlock(block, fmt::format("{}: {}", where, *problem));
  }
  geom::NurbsCurve curve(geom::KnotVector(nurbs.knots, nurbs.order - 1), nurbs.points,
                         nurbs.weights);
  std::vector<Eigen::Vector3d> points;
  const std::vector<double>& knots = nurbs.knots;
  for (std::size_t i = 1; i < knots.size(); ++i) {
    if (knots[i] > knots[i - 1]) {
      sampleSpan(curve, knots[i - 1], knots[i], 0, points);
    }
  }
  for (const Eigen::Vector3d& point : points) {
    Point3 target{point.x(), point.y(), point.z()};
    path_.events.push_back(
        {ExecutedEvent::Kind::Feed, modal_.position, target, {}, *modal_.feed, 0, nurbs.firstLine});
    modal_.position = target;
  }
}

} // namespace cncc::backends::sim
