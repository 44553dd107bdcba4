// Drilling canned cycles in the G17 plane: G73, G74, G81-G86, G89 with
// G98 (return to the initial level) or G99 (return to the R point), G80 to
// cancel. Every hole: rapid to X Y, rapid to R, the cycle's moves down to Z,
// back up. The cycle's data (R, Z, Q, P) stay modal until G80 or a G00-G03.
// G91: R is the distance from the initial level, Z from the R point.
#include "sim_machine.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace cncc::backends::sim {

namespace {

bool isFeedingOut(int cycle) {
  return cycle == 74 || cycle == 84 || cycle == 85 || cycle == 89;
}

} // namespace

bool Machine::isCycleCode(int tenths) {
  switch (tenths) {
  case 730:
  case 740:
  case 810:
  case 820:
  case 830:
  case 840:
  case 850:
  case 860:
  case 890:
    return true;
  default:
    return false;
  }
}

void Machine::setCycleMode(const Block& block, int tenths) {
  if (tenths == 980 || tenths == 990) {
    modal_.cycle.returnToInitial = tenths == 980;
    return;
  }
  if (tenths == 800 || tenths < 40) { // G80, or G00-G03: the cycle ends, with its data
    CannedCycle cancelled;
    cancelled.returnToInitial = modal_.cycle.returnToInitial;
    modal_.cycle = cancelled;
    return;
  }
  if (compensation_.isOn()) {
    failInBlock(block, "a drilling cycle while G41/G42 is on is not simulated; cancel with G40 "
                       "first");
  }
  if (!modal_.cycle.code) {
    if (modal_.atReference) {
      failInBlock(block, "a drilling cycle right after G28: its initial level is not in the work "
                         "coordinates; give Z with G00 first");
    }
    modal_.cycle.initialZ = modal_.position.z;
  }
  modal_.cycle.code = tenths / 10;
}

// One block of cycle mode that holds X, Y, Z or R: the data it changes,
// then its holes.
void Machine::runCycleBlock(const Block& block, const std::map<char, double>& values) {
  CannedCycle& cycle = modal_.cycle;
  if (!cycle.returnToInitial) {
    failInBlock(block, "G98 or G99 has not been commanded: the return level at power-on is a "
                       "parameter");
  }
  for (const Word& word : block.words) {
    if (word.letter == 'Q' && word.isLiteral && !word.literalHasPoint && word.value.number != 0) {
      failInBlock(block, "Q without a decimal point counts least input increments; write Q with "
                         "a point");
    }
  }
  auto given = [&](char letter) -> std::optional<double> {
    auto found = values.find(letter);
    return found == values.end() ? std::nullopt : std::optional<double>(found->second);
  };
  if (std::optional<double> r = given('R')) {
    cycle.rPoint = roundToIncrement(*r);
  }
  if (std::optional<double> z = given('Z')) {
    cycle.bottom = roundToIncrement(*z);
  }
  if (std::optional<double> q = given('Q')) {
    cycle.peck = roundToIncrement(std::abs(*q));
  }
  char repeatLetter = options_.reading.family == ControllerFamily::Fanuc ? 'K' : 'L';
  char otherLetter = repeatLetter == 'K' ? 'L' : 'K';
  if (values.count(otherLetter) > 0) {
    failInBlock(block, fmt::format("the repeat count of a drilling cycle is {} on this control, "
                                   "not {}",
                                   repeatLetter, otherLetter));
  }
  int repeats = 1;
  if (std::optional<double> count = given(repeatLetter)) {
    if (*count < 0 || *count != std::floor(*count) || *count > 9999) {
      failInBlock(block, fmt::format("{}{:g}: the repeat count is a whole number from 0 to 9999",
                                     repeatLetter, *count));
    }
    repeats = static_cast<int>(*count);
  }
  if (!cycle.rPoint || !cycle.bottom) {
    failInBlock(block, fmt::format("G{} without {}: the cycle needs its R point and its Z",
                                   *cycle.code, cycle.rPoint ? "Z" : "R"));
  }
  for (int hole = 0; hole < repeats; ++hole) {
    drillHole(block, values);
  }
}

void Machine::drillHole(const Block& block, const std::map<char, double>& values) {
  CannedCycle& cycle = modal_.cycle;
  double shiftZ = modal_.coordinates.shift.z; // G52
  double rLevel = modal_.absolute ? *cycle.rPoint + shiftZ : cycle.initialZ + *cycle.rPoint;
  double bottom = modal_.absolute ? *cycle.bottom + shiftZ : rLevel + *cycle.bottom;
  if (bottom >= rLevel) {
    failInBlock(block, fmt::format("the hole's bottom Z{:g} is not below its R point {:g}", bottom,
                                   rLevel));
  }
  if (modal_.toolChanged && !modal_.lengthOffset && profile_.requiresLengthOffset) {
    failInBlock(block, "a drilling cycle with no tool length offset active: G43 H.. must come "
                       "first");
  }
  std::map<char, double> position;
  for (char letter : {'X', 'Y'}) {
    if (values.count(letter) > 0) {
      position[letter] = values.at(letter);
    }
  }
  Point3 above = programmedTarget(block, position);
  cycleMove(block, false, above);
  Point3 at = above;
  at.z = rLevel;
  cycleMove(block, false, at);
  drillDown(block, rLevel, bottom);
  at.z = rLevel;
  if (isFeedingOut(*cycle.code)) {
    cycleMove(block, true, at);
  } else if (*cycle.code == 86) {
    output({ExecutedEvent::Kind::Spindle, {}, {}, {}, 0, 0, block.line}, block);
  }
  at.z = *cycle.returnToInitial ? cycle.initialZ : rLevel;
  cycleMove(block, false, at);
  if (*cycle.code == 86) {
    output({ExecutedEvent::Kind::Spindle, {}, {}, {}, 0, modal_.spindleSpeed, block.line}, block);
  }
}

// From the R point down to the bottom, with the pecks of G73 and G83.
void Machine::drillDown(const Block& block, double rLevel, double bottom) {
  int code = *modal_.cycle.code;
  if ((code == 74 || code == 84) && !modal_.spindleRunning) {
    failInBlock(block, fmt::format("G{} taps with the spindle stopped", code));
  }
  Point3 at = modal_.position;
  if (code != 73 && code != 83) {
    at.z = bottom;
    cycleMove(block, true, at);
    return;
  }
  double peck = modal_.cycle.peck.value_or(0);
  if (peck <= 0) {
    failInBlock(block, fmt::format("G{} without Q: how deep is each peck?", code));
  }
  const std::optional<double>& clearance =
      code == 73 ? options_.peckRetract : options_.peckClearance;
  if (!clearance) {
    failInBlock(block,
                fmt::format("G{}'s {} is a parameter of the control ({}); give it with {}", code,
                            code == 73 ? "retract" : "clearance", peckParameterName(code),
                            code == 73 ? "--peck-retract D" : "--peck-clearance D"));
  }
  double depth = rLevel;
  while (true) {
    double next = std::max(roundToIncrement(depth - peck), bottom);
    if (code == 83 && depth != rLevel) {
      at.z = roundToIncrement(depth + *clearance); // back down, short of the last depth
      cycleMove(block, false, at);
    }
    at.z = next;
    cycleMove(block, true, at);
    if (next <= bottom) {
      return;
    }
    at.z = code == 73 ? roundToIncrement(next + *clearance) : rLevel;
    cycleMove(block, false, at);
    depth = next;
  }
}

std::string Machine::peckParameterName(int code) const {
  bool fanuc = options_.reading.family == ControllerFamily::Fanuc;
  if (code == 73) {
    return fanuc ? "Fanuc parameter 5114" : "a machine parameter";
  }
  return fanuc ? "Fanuc parameter 5115" : "a machine parameter";
}

void Machine::cycleMove(const Block& block, bool feed, Point3 target) {
  if (feed && !modal_.feed) {
    failInBlock(block,
                fmt::format("G{} without a feed: no F has been commanded", *modal_.cycle.code));
  }
  const Point3& from = modal_.position;
  if (from.x == target.x && from.y == target.y && from.z == target.z) {
    return;
  }
  ExecutedEvent event{feed ? ExecutedEvent::Kind::Feed : ExecutedEvent::Kind::Rapid,
                      from,
                      target,
                      {},
                      feed ? *modal_.feed : 0,
                      0,
                      block.line};
  output(event, block);
  modal_.position = target;
}

} // namespace cncc::backends::sim
