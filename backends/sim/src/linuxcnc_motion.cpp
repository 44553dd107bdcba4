// A block's words in LinuxCNC's order of execution: F, S, T, M6, spindle,
// coolant, dwell, plane, units, compensation, tool length, coordinate
// system, path mode, distance modes, motion, then the stops (M0, M1, M2,
// M30). Cutter radius compensation runs through sim::RadiusCompensation
// with LinuxCNC's tangent entry and arcs about outside corners. Arc
// tolerances are those LinuxCNC's interpreter applies (measured against
// rs274: an end radius may differ from the start's by 0.0283 mm, 0.00283
// inch, or by 0.1 % of the radius).
#include "linuxcnc_machine.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace cncc::backends::sim::linuxcnc {

namespace {

// The modal groups whose codes exclude each other in a block.
constexpr std::array<std::array<int, 5>, 8> modalGroups{{
    {0, 10, 20, 30, 800},
    {400, 410, 411, 420, 421},
    {170, -1, -1, -1, -1},
    {200, 210, -1, -1, -1},
    {430, 490, -1, -1, -1},
    {610, 611, 640, -1, -1},
    {900, 910, -1, -1, -1},
    {901, 911, -1, -1, -1},
}};

// More turns of one helix are refused: each becomes a circle of the path.
constexpr int maximumTurns = 1000;

constexpr std::array<int, 33> knownGCodes{0,   10,  20,  30,  40,  170, 200, 210, 400, 410, 411,
                                          420, 421, 430, 490, 530, 540, 550, 560, 570, 580, 590,
                                          591, 592, 593, 610, 611, 640, 800, 900, 901, 910, 911};
constexpr std::array<int, 4> acceptedModeCodes{940, 970, 980, 990};

std::string gName(int code) {
  return code % 10 == 0 ? fmt::format("G{}", code / 10)
                        : fmt::format("G{}.{}", code / 10, code % 10);
}

bool contains(const auto& list, int code) {
  return std::find(list.begin(), list.end(), code) != list.end();
}

// Why a G code that LinuxCNC knows is not run here.
std::string refusalOfG(int code) {
  if (code == 180 || code == 190) {
    return fmt::format("{}: only the XY plane (G17) is modelled", gName(code));
  }
  if ((code >= 810 && code <= 890) || code == 730 || code == 760) {
    return fmt::format("{}: canned cycles are not modelled in the LinuxCNC dialect", gName(code));
  }
  return fmt::format("{} is not modelled in the LinuxCNC dialect", gName(code));
}

std::string refusalOfLetter(char letter) {
  switch (letter) {
  case 'r':
    return "R arcs are not modelled in the LinuxCNC dialect: give I and J";
  case 'a':
  case 'b':
  case 'c':
  case 'u':
  case 'v':
  case 'w':
    return fmt::format("the axis {} is not modelled: only X, Y and Z",
                       static_cast<char>(letter - 'a' + 'A'));
  case 'n':
    return "N (a line number) must start the line";
  default:
    return fmt::format("the word {} is not modelled in the LinuxCNC dialect",
                       static_cast<char>(letter - 'a' + 'A'));
  }
}

int wholeNumber(double value, std::string_view what, const LineContext& context) {
  double whole = std::round(value);
  if (std::abs(value - whole) > 1e-6 || whole < 0 || whole > 1e9) {
    failAt(context, fmt::format("{} must be a whole number from 0, not {}", what, value));
  }
  return static_cast<int>(whole);
}

} // namespace

BlockWords collectWords(const std::vector<std::pair<char, double>>& words,
                        const LineContext& context) {
  BlockWords block;
  for (const auto& [letter, value] : words) {
    if (letter == 'g') {
      double tenfold = std::round(value * 10);
      if (std::abs(value * 10 - tenfold) > 1e-6 || tenfold < 0 || tenfold > 9999) {
        failAt(context, fmt::format("G{} is no G code", value));
      }
      int code = static_cast<int>(tenfold);
      if (!contains(knownGCodes, code) && !contains(acceptedModeCodes, code)) {
        failAt(context, refusalOfG(code));
      }
      block.gCodes.insert(code);
    } else if (letter == 'm') {
      int code = wholeNumber(value, "an M code", context);
      if (code > 9 && code != 30) {
        failAt(context, fmt::format("M{} is not modelled in the LinuxCNC dialect", code));
      }
      block.mCodes.insert(code);
    } else if (std::string_view("xyzijkfstpqhd").find(letter) == std::string_view::npos) {
      failAt(context, refusalOfLetter(letter));
    } else if (!block.values.emplace(letter, value).second) {
      failAt(context,
             fmt::format("two {} words in one block", static_cast<char>(letter - 'a' + 'A')));
    }
  }
  for (const auto& group : modalGroups) {
    int found = 0;
    for (int code : group) {
      found += block.hasG(code) ? 1 : 0;
    }
    if (found > 1) {
      failAt(context, "two G codes of the same modal group in one block");
    }
  }
  int spindleCodes = block.hasM(3) + block.hasM(4) + block.hasM(5);
  int stops = block.hasM(0) + block.hasM(1) + block.hasM(2) + block.hasM(30);
  if (spindleCodes > 1 || stops > 1 || block.hasM(7) + block.hasM(8) + block.hasM(9) > 1) {
    failAt(context, "two M codes of the same modal group in one block");
  }
  return block;
}

std::optional<double> Machine::position(char axis) const {
  if (axis == 'z') {
    return zInMachineCoordinates_ ? std::nullopt : std::optional<double>(position_.z);
  }
  return axis == 'x' ? position_.x : position_.y;
}

namespace {

ExecutedEvent executedEventOf(const LinuxcncMove& move) {
  ExecutedEvent event;
  switch (move.kind) {
  case LinuxcncMove::Kind::Traverse:
    event.kind = ExecutedEvent::Kind::Rapid;
    break;
  case LinuxcncMove::Kind::Feed:
    event.kind = ExecutedEvent::Kind::Feed;
    break;
  case LinuxcncMove::Kind::Arc:
    event.kind = move.turns > 0 ? ExecutedEvent::Kind::CounterclockwiseArc
                                : ExecutedEvent::Kind::ClockwiseArc;
    break;
  case LinuxcncMove::Kind::ToolChange:
    event.kind = ExecutedEvent::Kind::ToolChange;
    break;
  case LinuxcncMove::Kind::Spindle:
    event.kind = ExecutedEvent::Kind::Spindle;
    break;
  }
  event.start = move.start;
  event.end = move.end;
  event.centre = move.centre;
  event.feed = move.feed;
  event.number = move.number;
  event.line = move.line;
  return event;
}

LinuxcncMove linuxcncMoveOf(const ExecutedEvent& event) {
  LinuxcncMove move;
  switch (event.kind) {
  case ExecutedEvent::Kind::Rapid:
    move.kind = LinuxcncMove::Kind::Traverse;
    break;
  case ExecutedEvent::Kind::Feed:
    move.kind = LinuxcncMove::Kind::Feed;
    break;
  case ExecutedEvent::Kind::ClockwiseArc:
  case ExecutedEvent::Kind::CounterclockwiseArc:
    move.kind = LinuxcncMove::Kind::Arc;
    move.turns = event.kind == ExecutedEvent::Kind::CounterclockwiseArc ? 1 : -1;
    break;
  case ExecutedEvent::Kind::ToolChange:
    move.kind = LinuxcncMove::Kind::ToolChange;
    break;
  case ExecutedEvent::Kind::Spindle:
    move.kind = LinuxcncMove::Kind::Spindle;
    break;
  }
  move.start = event.start;
  move.end = event.end;
  move.centre = event.centre;
  move.feed = event.feed;
  move.number = event.number;
  move.line = event.line;
  return move;
}

} // namespace

void Machine::emit(LinuxcncMove move) {
  if (!compensation_.isOn()) {
    run_.moves.push_back(move);
    return;
  }
  if (move.kind == LinuxcncMove::Kind::Arc && std::abs(move.turns) != 1) {
    failAt({block_.line, block_.text},
           "an arc of several turns (P) with cutter compensation on is not modelled");
  }
  compensation_.add(executedEventOf(move), block_);
  drainCompensated();
}

void Machine::drainCompensated() {
  for (const ExecutedEvent& event : compensated_.events) {
    run_.moves.push_back(linuxcncMoveOf(event));
  }
  compensated_.events.clear();
}

void Machine::setCompensation(const BlockWords& words, const LineContext& context) {
  if (words.hasG(400)) {
    compensation_.cancel(block_);
    return;
  }
  int code = 0;
  for (int candidate : {410, 411, 420, 421}) {
    if (words.hasG(candidate)) {
      code = candidate;
    }
  }
  if (code == 0) {
    return;
  }
  if (!words.has('d')) {
    failAt(context, fmt::format("{} without D: {}", gName(code),
                                code % 10 == 1 ? "the tool diameter" : "which tool's radius?"));
  }
  double d = words.values.at('d');
  double radius = 0;
  if (code % 10 == 1) { // G41.1/G42.1: D is the diameter
    if (d < 0) {
      failAt(context, fmt::format("{} D{}: the diameter must not be negative", gName(code), d));
    }
    radius = d / 2;
  } else if (int tool = wholeNumber(d, "D (the tool number)", context); tool != 0) {
    auto found = options_.toolRadii.find(tool);
    if (found == options_.toolRadii.end()) {
      failAt(context, fmt::format("D{}: the radius of tool {} is not known; give it with "
                                  "--tool-radius {}=R",
                                  tool, tool, tool));
    }
    radius = found->second;
  }
  compensation_.start(code == 410 || code == 411, radius, block_);
}

void Machine::setUnits(bool inches, const LineContext& context) {
  if (inches != inches_ && moved_) {
    failAt(context, "a change of units after the first move is not modelled");
  }
  inches_ = inches;
  run_.inches = inches;
}

void Machine::spindle(const BlockWords& words, const LineContext& context) {
  if (words.has('s')) {
    if (words.values.at('s') < 0) {
      failAt(context, "S must not be negative");
    }
    bool changed = words.values.at('s') != speed_;
    speed_ = words.values.at('s');
    if (changed && spindleDirection_ != 0 && !words.hasM(5)) {
      emit({.kind = LinuxcncMove::Kind::Spindle, .number = speed_, .line = context.line});
    }
  }
  if (words.has('t')) {
    selectedTool_ = wholeNumber(words.values.at('t'), "T", context);
  }
  if (words.hasM(6)) {
    if (!selectedTool_) {
      failAt(context, "M6 without a tool selected by T");
    }
    emit({.kind = LinuxcncMove::Kind::ToolChange,
          .number = static_cast<double>(*selectedTool_),
          .line = context.line});
  }
  if ((words.hasM(3) || words.hasM(4)) && spindleDirection_ == 0) {
    emit({.kind = LinuxcncMove::Kind::Spindle, .number = speed_, .line = context.line});
  }
  if (words.hasM(3) || words.hasM(4)) {
    spindleDirection_ = words.hasM(3) ? 3 : 4;
  }
  if (words.hasM(5) && spindleDirection_ != 0) {
    spindleDirection_ = 0;
    emit({.kind = LinuxcncMove::Kind::Spindle, .number = 0, .line = context.line});
  }
}

bool Machine::execute(const BlockWords& words, const LineContext& context) {
  block_.line = context.line;
  block_.text = std::string(context.text);
  bool ends = executeWords(words, context);
  if (ends) {
    compensation_.finish(block_);
  }
  compensation_.endOfBlock(block_);
  drainCompensated();
  return ends;
}

bool Machine::executeWords(const BlockWords& words, const LineContext& context) {
  if (words.has('f')) {
    if (words.values.at('f') < 0) {
      failAt(context, "F must not be negative");
    }
    feed_ = words.values.at('f');
  }
  spindle(words, context);
  bool explicitMotion = false;
  for (int code : {0, 10, 20, 30, 800}) {
    if (words.hasG(code)) {
      motionMode_ = code;
      explicitMotion = true;
    }
  }
  bool axes = words.has('x') || words.has('y') || words.has('z');
  bool arcNow = (explicitMotion || axes) && (motionMode_ == 20 || motionMode_ == 30);
  auto onlyWith = [&](char letter, bool used, std::string_view users) {
    if (words.has(letter) && !used) {
      failAt(context, fmt::format("{} without {}", static_cast<char>(letter - 'a' + 'A'), users));
    }
  };
  onlyWith('p', words.hasG(40) || words.hasG(640) || arcNow, "G4, G64, G2 or G3");
  onlyWith('q', words.hasG(640), "G64");
  onlyWith('h', words.hasG(430), "G43");
  onlyWith('d', words.hasG(410) || words.hasG(411) || words.hasG(420) || words.hasG(421),
           "G41, G42, G41.1 or G42.1");
  onlyWith('i', arcNow, "G2 or G3");
  onlyWith('j', arcNow, "G2 or G3");
  if (words.has('k')) {
    failAt(context, "K is not an arc centre word in the XY plane (G17)");
  }
  if (words.hasG(40) && !words.has('p')) {
    failAt(context, "G4 without P (the dwell in seconds)");
  }
  if (words.hasG(200) || words.hasG(210)) {
    setUnits(words.hasG(200), context);
  }
  setCompensation(words, context);
  if (words.hasG(430) && words.has('h')) {
    wholeNumber(words.values.at('h'), "H", context);
  }
  if (words.hasG(900) || words.hasG(910)) {
    absolute_ = words.hasG(900);
  }
  if (words.hasG(901) || words.hasG(911)) {
    absoluteArcCentres_ = words.hasG(901);
  }
  motion(words, context);
  return words.hasM(2) || words.hasM(30);
}

Point3 Machine::target(const BlockWords& words) const {
  Point3 end = position_;
  auto axis = [&](char letter, double& coordinate) {
    if (words.has(letter)) {
      coordinate = absolute_ ? words.values.at(letter) : coordinate + words.values.at(letter);
    }
  };
  axis('x', end.x);
  axis('y', end.y);
  axis('z', end.z);
  return end;
}

void Machine::motion(const BlockWords& words, const LineContext& context) {
  bool axes = words.has('x') || words.has('y') || words.has('z');
  if (!axes) {
    return;
  }
  if (motionMode_ == 800) {
    failAt(context, "X, Y or Z without a motion mode (G0, G1, G2, G3)");
  }
  if (words.hasG(530)) {
    if (motionMode_ != 0 && motionMode_ != 10) {
      failAt(context, "G53 needs G0 or G1");
    }
    if (!absolute_) {
      failAt(context, "G53 in G91 is not modelled");
    }
    if (words.has('x') || words.has('y')) {
      failAt(context, "G53 X or Y: the machine's X and Y are not modelled in work coordinates");
    }
    zInMachineCoordinates_ = true;
    return;
  }
  if (zInMachineCoordinates_) {
    if (!words.has('z') || !absolute_ || motionMode_ != 0) {
      failAt(context, "after G53 Z the next move is a G0 to an absolute Z (the machine's Z is "
                      "not modelled in work coordinates)");
    }
    position_.z = words.values.at('z');
    zInMachineCoordinates_ = false;
  }
  Point3 end = target(words);
  moved_ = true;
  if (motionMode_ == 20 || motionMode_ == 30) {
    arc(words, end, context);
  } else {
    if (motionMode_ == 10 && feed_ <= 0) {
      failAt(context, "G1 with a zero feed: no F has been commanded");
    }
    bool traverse = motionMode_ == 0;
    emit({.kind = traverse ? LinuxcncMove::Kind::Traverse : LinuxcncMove::Kind::Feed,
          .start = position_,
          .end = end,
          .feed = traverse ? 0 : feed_,
          .line = context.line});
  }
  position_ = end;
}

void Machine::arc(const BlockWords& words, Point3 end, const LineContext& context) {
  std::string name = gName(motionMode_);
  if (feed_ <= 0) {
    failAt(context, fmt::format("{} with a zero feed: no F has been commanded", name));
  }
  if (!words.has('i') && !words.has('j')) {
    failAt(context, fmt::format("{} without I or J", name));
  }
  auto word = [&](char letter) { return words.has(letter) ? words.values.at(letter) : 0.0; };
  Point3 centre{word('i'), word('j'), position_.z};
  if (!absoluteArcCentres_) {
    centre.x += position_.x;
    centre.y += position_.y;
  }
  double startRadius = std::hypot(position_.x - centre.x, position_.y - centre.y);
  double endRadius = std::hypot(end.x - centre.x, end.y - centre.y);
  double smallest = inches_ ? 0.00005 : 0.00127;
  if (startRadius < smallest || endRadius < smallest) {
    failAt(context, fmt::format("{}: a zero-radius arc", name));
  }
  double difference = std::abs(startRadius - endRadius);
  double spiral = (inches_ ? 0.002 : 0.02) * std::sqrt(2.0);
  if (difference > spiral && difference / std::max(startRadius, endRadius) > 0.001) {
    failAt(context, fmt::format("{}: the end is {:.4f} from the centre, the start {:.4f}", name,
                                endRadius, startRadius));
  }
  int turns = 1;
  if (words.has('p')) {
    double p = words.values.at('p');
    if (p < 1 || p != std::floor(p) || p > maximumTurns) {
      failAt(context, fmt::format("{} P{}: the turns are a whole number from 1 to {}", name, p,
                                  maximumTurns));
    }
    turns = static_cast<int>(p);
  }
  emit({.kind = LinuxcncMove::Kind::Arc,
        .start = position_,
        .end = end,
        .centre = centre,
        .turns = motionMode_ == 30 ? turns : -turns,
        .feed = feed_,
        .line = context.line});
}

} // namespace cncc::backends::sim::linuxcnc
