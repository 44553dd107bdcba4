#include "cncc/backends/linuxcnc_canon.h"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

namespace cncc::backends {

namespace {

struct CanonCall {
  std::string_view name;
  std::vector<double> arguments;
};

std::string_view trimmed(std::string_view text) {
  std::size_t first = text.find_first_not_of(" \t\r");
  if (first == std::string_view::npos) {
    return {};
  }
  std::size_t last = text.find_last_not_of(" \t\r");
  return text.substr(first, last - first + 1);
}

// `NAME(1.0, -2, 3)` after the line number and `N.....`; nullopt for a line
// that is no call, and for calls whose arguments are not all numbers.
std::optional<CanonCall> callOf(std::string_view line) {
  std::size_t open = line.find('(');
  std::size_t close = line.rfind(')');
  if (open == std::string_view::npos || close == std::string_view::npos || close < open) {
    return std::nullopt;
  }
  std::string_view head = line.substr(0, open);
  std::size_t space = head.find_last_of(' ');
  CanonCall call;
  call.name = space == std::string_view::npos ? head : head.substr(space + 1);
  std::string_view list = line.substr(open + 1, close - open - 1);
  while (!trimmed(list).empty()) {
    std::size_t comma = list.find(',');
    std::string_view item = trimmed(list.substr(0, comma));
    double value = 0;
    auto [end, error] = std::from_chars(item.data(), item.data() + item.size(), value);
    if (error != std::errc() || end != item.data() + item.size()) {
      return CanonCall{call.name, {}};
    }
    call.arguments.push_back(value);
    list = comma == std::string_view::npos ? std::string_view() : list.substr(comma + 1);
  }
  return call;
}

class CanonReader {
public:
  CanonReader(double arcChordError, double maximumMoves)
      : arcChordError_(arcChordError), maximumMoves_(maximumMoves) {}

  void read(const CanonCall& call, std::size_t lineNumber) {
    auto need = [&](std::size_t count) {
      if (call.arguments.size() < count) {
        throw ExecutionMismatch(fmt::format("rs274 line {}: {} has {} numbers, {} expected",
                                            lineNumber, call.name, call.arguments.size(), count));
      }
    };
    if (call.name == "STRAIGHT_TRAVERSE" || call.name == "STRAIGHT_FEED") {
      need(3);
      bool rapid = call.name == "STRAIGHT_TRAVERSE";
      Eigen::Vector3d end(call.arguments[0], call.arguments[1], call.arguments[2]);
      if (!(rapid && isMachineZero(end))) { // G53 G0 Z0: the part's path leaves the work
        moveTo(end, rapid);
      }
    } else if (call.name == "SET_G5X_OFFSET") {
      need(4);
      workOffsetZ_ = call.arguments[3];
    } else if (call.name == "SET_FEED_RATE") {
      need(1);
      feed_ = call.arguments[0];
    } else if (call.name == "ARC_FEED") {
      need(6);
      arc(call.arguments);
    } else if (call.name == "NURBS_FEED") {
      throw ExecutionMismatch(fmt::format(
          "rs274 line {}: NURBS_FEED is printed without its control points", lineNumber));
    }
  }

  ExecutedPath path() && { return std::move(path_); }

private:
  // A traverse in Z alone to the machine's Z0, where the work offset puts it
  // (rs274ReferenceHeight above the work; it is not part of the work).
  bool isMachineZero(const Eigen::Vector3d& end) const {
    return workOffsetZ_ != 0 && std::abs(end.z() + workOffsetZ_) < 1e-6 &&
           (end.head<2>() - position_.head<2>()).norm() < 1e-9;
  }

  void moveTo(const Eigen::Vector3d& end, bool rapid) {
    if (!(static_cast<double>(path_.moves.size()) < maximumMoves_)) {
      throw PathTooLargeToMeasure(maximumMoves_, arcChordError_);
    }
    path_.moves.push_back({rapid, end, rapid ? 0.0 : feed_, std::nullopt});
    position_ = end;
  }

  void arc(const std::vector<double>& a) {
    Eigen::Vector2d end(a[0], a[1]), centre(a[2], a[3]);
    int turns = static_cast<int>(std::lround(a[4]));
    Eigen::Vector2d from = position_.head<2>() - centre;
    Eigen::Vector2d to = end - centre;
    double radius = from.norm();
    double start = std::atan2(from.y(), from.x());
    double sweep = std::atan2(to.y(), to.x()) - start;
    double turn = 2 * std::numbers::pi;
    if (turns > 0) { // counterclockwise: 0 < sweep <= 2 pi, and full turns more
      while (sweep <= 1e-12) {
        sweep += turn;
      }
      sweep += turn * (turns - 1);
    } else {
      while (sweep >= -1e-12) {
        sweep -= turn;
      }
      sweep -= turn * (-turns - 1);
    }
    double step = radius > arcChordError_ ? 2 * std::acos(1 - arcChordError_ / radius) : turn;
    double chords = std::max(1.0, std::ceil(std::abs(sweep) / step));
    if (!(static_cast<double>(path_.moves.size()) + chords <= maximumMoves_)) {
      throw PathTooLargeToMeasure(maximumMoves_, arcChordError_);
    }
    int pieces = static_cast<int>(chords);
    double z0 = position_.z();
    for (int i = 1; i <= pieces; ++i) {
      double f = static_cast<double>(i) / pieces;
      double angle = start + sweep * f;
      Eigen::Vector3d point(centre.x() + radius * std::cos(angle),
                            centre.y() + radius * std::sin(angle), z0 + (a[5] - z0) * f);
      if (i == pieces) {
        point.head<2>() = end;
      }
      moveTo(point, false);
    }
  }

  double arcChordError_;
  double maximumMoves_;
  ExecutedPath path_;
  Eigen::Vector3d position_ = Eigen::Vector3d::Zero();
  double feed_ = 0;
  double workOffsetZ_ = 0; // of the work offset in use (SET_G5X_OFFSET)
};

} // namespace

ExecutedPath readLinuxcncCanon(std::string_view canon, double arcChordError, double maximumMoves) {
  CanonReader reader(arcChordError, maximumMoves);
  std::size_t lineNumber = 0;
  while (!canon.empty()) {
    std::size_t newline = canon.find('\n');
    std::string_view line = canon.substr(0, newline);
    canon = newline == std::string_view::npos ? std::string_view() : canon.substr(newline + 1);
    ++lineNumber;
    if (std::optional<CanonCall> call = callOf(line)) {
      reader.read(*call, lineNumber);
    }
  }
  return std::move(reader).path();
}

} // namespace cncc::backends
