// The modal G codes, F, S, T and the M codes of a block of address words.
#include "sim_machine.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace cncc::backends::sim {

namespace {

// The words M99 takes: P, the sequence number to return to.
std::map<char, double> returnWords(const std::map<char, double>& values) {
  std::map<char, double> words;
  if (values.count('P') > 0) {
    words['P'] = values.at('P');
  }
  return words;
}

} // namespace

bool BlockWords::hasG(int tenths) const {
  return std::find(gCodes.begin(), gCodes.end(), tenths) != gCodes.end();
}

void Machine::applyModalCodes(const Block& block, const BlockWords& words) {
  for (int tenths : words.gCodes) {
    switch (tenths) {
    case 0:
    case 10:
    case 20:
    case 30:
      modal_.motion = tenths / 10;
      setCycleMode(block, tenths);
      break;
    case 800: // G80 cancels, G98/G99 choose the return level
    case 980:
    case 990:
      setCycleMode(block, tenths);
      break;
    case 900:
    case 910:
      modal_.absolute = tenths == 900;
      break;
    case 200:
    case 210:
      modal_.inches = tenths == 200;
      path_.inches = modal_.inches;
      break;
    case 430:
      if (words.values.count('H') == 0) {
        failInBlock(block, "G43 without H: which length offset?");
      }
      modal_.lengthOffset = static_cast<int>(words.values.at('H'));
      break;
    case 490:
      modal_.lengthOffset.reset();
      break;
    case 400:
    case 410:
    case 420:
      setCompensation(block, tenths);
      break;
    case 690:
      if (compensation_.isOn()) {
        failInBlock(block, "G69 while G41/G42 is on is not simulated; cancel with G40 first");
      }
      modal_.coordinates.rotated = false;
      break;
    case 150:
    case 160:
      modal_.coordinates.polar = tenths == 160;
      break;
    case 670:
      modal_.modalCall.reset();
      break;
    case 541:
      checkExtendedWorkOffset(block, words);
      break;
    default:
      if (isCycleCode(tenths)) {
        setCycleMode(block, tenths);
      }
      break; // else G04, G17, G54-G59, G61, G64, G94: no effect on the path
    }
  }
}

// G54.1 Pn: a work offset the machine has.
void Machine::checkExtendedWorkOffset(const Block& block, const BlockWords& words) const {
  auto p = words.values.find('P');
  if (p == words.values.end()) {
    failInBlock(block, "G54.1 without P: which extended work offset?");
  }
  if (profile_.maximumExtendedWorkOffset == 0) {
    failInBlock(block, "this machine has no extended work offsets (G54.1)");
  }
  if (p->second < 1 || p->second > profile_.maximumExtendedWorkOffset ||
      p->second != std::floor(p->second)) {
    failInBlock(block,
                fmt::format("G54.1 P{:g}: this machine's extended work offsets are P1 to P{}",
                            p->second, profile_.maximumExtendedWorkOffset));
  }
}

void Machine::applyFeedSpindleTool(const Block& block, const BlockWords& words) {
  if (words.values.count('F') > 0) {
    if (words.values.at('F') <= 0) {
      failInBlock(block, "the feed F must be positive");
    }
    modal_.feed = words.values.at('F');
    double perMinute = *modal_.feed * (modal_.inches ? 25.4 : 1.0);
    if (profile_.maximumFeed > 0 && perMinute > profile_.maximumFeed * (1 + 1e-9)) {
      failInBlock(block, fmt::format("the feed F{:g} is over the machine's maximum of {:g} mm/min",
                                     *modal_.feed, profile_.maximumFeed));
    }
  }
  if (words.values.count('S') > 0) {
    double speed = words.values.at('S');
    if (speed < 0 || speed != std::round(speed)) {
      failInBlock(block, "the spindle speed S must be a whole number from 0");
    }
    if (profile_.maximumSpindleSpeed > 0 && speed > profile_.maximumSpindleSpeed) {
      failInBlock(block, fmt::format("the spindle speed S{:g} is over the machine's maximum of "
                                     "{:g} rpm",
                                     speed, profile_.maximumSpindleSpeed));
    }
    modal_.spindleSpeed = speed;
    if (modal_.spindleRunning) {
      output({ExecutedEvent::Kind::Spindle, {}, {}, {}, 0, speed, block.line}, block);
    }
  }
  if (words.values.count('T') > 0) {
    double tool = words.values.at('T');
    if (tool < 0 || tool != std::round(tool) || tool > 99999999) {
      failInBlock(block, "the tool number T must be a whole number from 0");
    }
    modal_.selectedTool = static_cast<int>(tool);
  }
}

Machine::Next Machine::executeMCode(const Block& block, const BlockWords& words,
                                    std::size_t& next) {
  if (words.mCodes.size() > 1) {
    failInBlock(block, "one M code per block");
  }
  if (words.mCodes.empty()) {
    return Next::Continue;
  }
  switch (words.mCodes.front()) {
  case 0:
  case 1:
  case 7:
  case 8:
  case 9:
    return Next::Continue;
  case 2:
  case 30:
    return Next::Stop;
  case 3:
  case 4:
    modal_.spindleRunning = true;
    output({ExecutedEvent::Kind::Spindle, {}, {}, {}, 0, modal_.spindleSpeed, block.line}, block);
    return Next::Continue;
  case 5:
    modal_.spindleRunning = false;
    output({ExecutedEvent::Kind::Spindle, {}, {}, {}, 0, 0, block.line}, block);
    return Next::Continue;
  case 6:
    if (!modal_.selectedTool) {
      failInBlock(block, "M06 before any T: which tool?");
    }
    output(
        {ExecutedEvent::Kind::ToolChange, {}, {}, {}, 0, double(*modal_.selectedTool), block.line},
        block);
    modal_.toolChanged = true;
    modal_.lengthOffset.reset();
    return Next::Continue;
  case 98:
    callSubprogram(block, words.values, next);
    return Next::Jump;
  case 99:
    return returnFromMacro(block, returnWords(words.values), next);
  default:
    failInBlock(block, fmt::format("M{:02d} is not simulated", words.mCodes.front()));
  }
}

} // namespace cncc::backends::sim
