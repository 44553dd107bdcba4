// Address words: modal G codes, F S T, G00-G03 motion, G65 calls, M codes.
#include "sim_machine.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string_view>

namespace cncc::backends::sim {

namespace {

// G codes in tenths (G06.2 is 62) with their modal group; 0 is the
// one-shot group.
struct GCode {
  int tenths;
  int group;
};

constexpr GCode supportedGCodes[] = {
    {0, 1},    {10, 1},   {20, 1},   {30, 1},   {40, 0},   {650, 0},  {170, 2},  {900, 3},
    {910, 3},  {940, 5},  {200, 6},  {210, 6},  {400, 7},  {430, 8},  {490, 8},  {800, 9},
    {540, 14}, {550, 14}, {560, 14}, {570, 14}, {580, 14}, {590, 14}, {610, 15}, {640, 15},
    {62, 1},   {50, 0},   {51, 0},   {541, 14}, {280, 0},  {410, 7},  {420, 7},  {730, 9},
    {740, 9},  {810, 9},  {820, 9},  {830, 9},  {840, 9},  {850, 9},  {860, 9},  {890, 9},
    {980, 10}, {990, 10}, {520, 0},  {680, 16}, {690, 16}, {150, 17}, {160, 17}, {660, 12},
    {670, 12}, {390, 0}};
// G06.2 NURBS and G05 P10000 (sim_nurbs.cpp); G05.1 Q1/Q0 (AI contour
// control) and G54.1 P.. (extended work offsets) do not change the path.

constexpr std::string_view axisLetters = "XYZ";
constexpr std::string_view arcLetters = "IJKR";

std::string gName(int tenths) {
  return tenths % 10 == 0 ? fmt::format("G{:02d}", tenths / 10)
                          : fmt::format("G{:02d}.{}", tenths / 10, tenths % 10);
}

std::optional<int> groupOf(int tenths) {
  for (const GCode& code : supportedGCodes) {
    if (code.tenths == tenths) {
      return code.group;
    }
  }
  return std::nullopt;
}

bool isCoordinateLetter(char letter) {
  return axisLetters.find(letter) != std::string_view::npos ||
         arcLetters.find(letter) != std::string_view::npos;
}

} // namespace

double Machine::increment() const {
  // IS-B: 0.001 mm, 0.0001 inch.
  return modal_.inches ? profile_.leastInputIncrement / 10.0 : profile_.leastInputIncrement;
}

double Machine::roundToIncrement(double value) const {
  return std::round(value / increment()) * increment();
}

namespace {

void checkLiteral(const Word& word, const Block& block, int decimals, bool isArgument) {
  if (!word.isLiteral) {
    return;
  }
  // Without a point, 0 is 0 however the controller reads it.
  if (!word.literalHasPoint && word.value.number != 0) {
    failInBlock(block, fmt::format("{} {} without a decimal point: its meaning depends on a "
                                   "parameter; write {}{}.",
                                   isArgument ? "the argument" : "the coordinate", word.letter,
                                   word.letter, word.value.number));
  }
  if (word.literalDecimals > decimals) {
    failInBlock(block, fmt::format("the address {} has {} decimals; the least input increment "
                                   "allows {}",
                                   word.letter, word.literalDecimals, decimals));
  }
}

BlockWords evaluateWords(const Block& block, const VariableReader& variables) {
  BlockWords words;
  for (const Word& word : block.words) {
    if (word.containsRound) {
      failInBlock(block, fmt::format("ROUND in the address {} rounds to the least input "
                                     "increment on some controllers and to a whole number on "
                                     "others; compute it in a variable",
                                     word.letter));
    }
    Value value = evaluate(word.value, variables, block);
    if (value.vacant) {
      continue;
    }
    if (word.letter == 'G' || word.letter == 'M') {
      double tenths = value.number * (word.letter == 'G' ? 10 : 1);
      if (std::abs(tenths - std::round(tenths)) > 1e-6 || std::abs(tenths) > 1e6) {
        failInBlock(block, fmt::format("{}{} is not a code", word.letter, value.number));
      }
      (word.letter == 'G' ? words.gCodes : words.mCodes)
          .push_back(static_cast<int>(std::lround(tenths)));
      continue;
    }
    words.values[word.letter] = value.number;
  }
  return words;
}

void checkGCodes(const Block& block, const BlockWords& words) {
  std::map<int, int> groups;
  for (int tenths : words.gCodes) {
    std::optional<int> group = groupOf(tenths);
    if (!group) {
      failInBlock(block,
                  fmt::format("{} is not simulated (refused rather than guessed)", gName(tenths)));
    }
    if (*group != 0 && groups.count(*group) > 0) {
      failInBlock(block, fmt::format("{} and {} are in the same modal group", gName(groups[*group]),
                                     gName(tenths)));
    }
    groups[*group] = tenths;
  }
  for (int call : {650, 660}) {
    if (words.hasG(call) && words.gCodes.size() > 1) {
      failInBlock(block, fmt::format("{} must be the only G code of its block", gName(call)));
    }
  }
}

// The letters a block of this kind may hold.
void checkLetters(const Block& block, const BlockWords& words, bool cycle) {
  bool dwell = words.hasG(40);
  bool subprogramCall =
      std::find(words.mCodes.begin(), words.mCodes.end(), 98) != words.mCodes.end();
  bool subprogramReturn =
      std::find(words.mCodes.begin(), words.mCodes.end(), 99) != words.mCodes.end();
  for (const auto& [letter, value] : words.values) {
    bool allowed = std::string_view("XYZIJKRFSTD").find(letter) != std::string_view::npos ||
                   (letter == 'P' &&
                    (dwell || words.hasG(541) || subprogramCall || subprogramReturn || cycle)) ||
                   (letter == 'L' && (subprogramCall || cycle)) ||
                   (letter == 'H' && words.hasG(430)) ||
                   (letter == 'Q' && (words.hasG(51) || cycle));
    if (!allowed) {
      failInBlock(block, fmt::format("the address {} is not simulated in this block", letter));
    }
  }
}

} // namespace

Machine::Next Machine::executeWords(const Block& block, std::size_t& next) {
  moveCommanded_ = false;
  Next decision = executeAddressWords(block, next);
  if (decision == Next::Stop) {
    compensation_.finish(block);
  }
  compensation_.endOfBlock(block);
  if (decision == Next::Continue && moveCommanded_ && callAfterMove(block, next)) {
    return Next::Jump;
  }
  return decision;
}

// G41/G42 with the radius of the D register, G40.
void Machine::setCompensation(const Block& block, int tenths) {
  if (tenths == 400) {
    compensation_.cancel(block);
    return;
  }
  if (!modal_.radiusRegister) {
    failInBlock(block, fmt::format("{} without D: which radius register?", gName(tenths)));
  }
  int registerNumber = *modal_.radiusRegister;
  double radius = 0; // D0 is always 0
  if (registerNumber != 0) {
    auto found = options_.toolRadii.find(registerNumber);
    if (found == options_.toolRadii.end()) {
      failInBlock(block, fmt::format("D{}: the radius in offset register {} is not known; give "
                                     "it with --tool-radius {}=R or in the machine file's "
                                     "[radius_offsets]",
                                     registerNumber, registerNumber, registerNumber));
    }
    radius = found->second;
  }
  compensation_.start(tenths == 410, radius, block);
}

Machine::Next Machine::executeAddressWords(const Block& block, std::size_t& next) {
  BlockWords words = evaluateWords(block, *this);
  checkGCodes(block, words);
  if (words.hasG(650) || words.hasG(660)) {
    for (const Word& word : block.words) {
      if (word.letter != 'G' && word.letter != 'P' && word.letter != 'L') {
        checkLiteral(word, block, 8, true);
      }
    }
    if (words.hasG(660)) {
      setModalCall(block);
      return Next::Continue;
    }
    callMacro(block, next);
    return Next::Jump;
  }
  if (compensation_.isOn() && (words.hasG(62) || words.hasG(280))) {
    failInBlock(block, fmt::format("{} while G41/G42 is on is not simulated; cancel with G40 first",
                                   words.hasG(62) ? "G06.2" : "G28"));
  }
  if (words.values.count('D') > 0) {
    double number = words.values['D'];
    if (number < 0 || number != std::round(number) || number > 9999) {
      failInBlock(block, "the offset register D must be a whole number from 0 to 9999");
    }
    modal_.radiusRegister = static_cast<int>(number);
  }
  if (executeNurbsWords(block, words.gCodes, words.mCodes, words.values)) {
    return Next::Continue;
  }
  bool cycle = modal_.cycle.code.has_value() ||
               std::any_of(words.gCodes.begin(), words.gCodes.end(), isCycleCode);
  checkLetters(block, words, cycle);
  int decimals = profile_.coordinateDecimals + (modal_.inches ? 1 : 0);
  for (const Word& word : block.words) {
    if (isCoordinateLetter(word.letter) && !(cycle && word.letter == 'K')) { // K: repeats
      checkLiteral(word, block, decimals, false);
    }
  }
  applyModalCodes(block, words);
  applyFeedSpindleTool(block, words);
  executeAxisWords(block, words);
  return executeMCode(block, words, next);
}

// The block's X Y Z I J K R: a move, a cycle's holes, G52's or G68's data,
// G28's intermediate point.
void Machine::executeAxisWords(const Block& block, const BlockWords& words) {
  std::map<char, double> axes;
  for (const auto& [letter, value] : words.values) {
    if (isCoordinateLetter(letter)) {
      axes[letter] = value;
    }
  }
  if (words.hasG(520) && words.hasG(680)) {
    failInBlock(block, "G52 and G68 in one block: give them in blocks of their own");
  } else if (words.hasG(520)) {
    setLocalShift(block, axes); // the block's words set the local origin: no move
  } else if (words.hasG(680)) {
    setRotation(block, axes); // the centre and angle: no move
  } else if (words.hasG(40)) {
    if (!axes.empty()) {
      failInBlock(block, "G04 takes its time in P, with no axis words");
    }
  } else if (words.hasG(280)) {
    returnToReference(block, axes);
  } else if (words.hasG(390) && !profile_.cornerArcOnMoveBlock) {
    cornerArc(block, axes);
  } else if (words.hasG(390) && axes.empty()) {
    failInBlock(block, "G39 (corner arc) on this control goes on the move whose end is the corner");
  } else if (modal_.cycle.code &&
             (axes.count('X') + axes.count('Y') + axes.count('Z') + axes.count('R') > 0)) {
    runCycleBlock(block, words.values);
    moveCommanded_ = true;
  } else if (!axes.empty()) {
    if (!modal_.motion) {
      failInBlock(block, "a move before any G00, G01, G02 or G03: the power-on motion mode is "
                         "a parameter");
    }
    if (words.hasG(390)) { // Mitsubishi: the corner at this move's end
      if (axes.count('I') + axes.count('J') + axes.count('K') + axes.count('R') > 0 ||
          *modal_.motion != 1) {
        failInBlock(block, "G39 (corner arc) is simulated on a G01 move with X, Y and Z only");
      }
      compensation_.cornerArcAfterThisBlock();
    }
    move(block, *modal_.motion, axes);
    moveCommanded_ = true;
  }
}

// Fanuc's G39 [I.. J..]: a block of its own, the corner arc at the end of
// the move before it, towards I J (incremental from the corner) or the next
// move's start.
void Machine::cornerArc(const Block& block, const std::map<char, double>& axes) {
  for (const auto& [letter, value] : axes) {
    if (letter != 'I' && letter != 'J') {
      failInBlock(block, fmt::format("G39 takes the direction after the corner in I and J, not {} "
                                     "(no move in a G39 block)",
                                     letter));
    }
  }
  if (!modal_.coordinates.isPlain()) {
    failInBlock(block, "G39 while G52, G68 or G16 is on is not simulated");
  }
  std::optional<Vector2> direction;
  if (!axes.empty()) {
    auto word = [&](char letter) {
      auto found = axes.find(letter);
      return found == axes.end() ? 0.0 : roundToIncrement(found->second);
    };
    direction = Vector2{word('I'), word('J')};
  }
  compensation_.cornerArc(direction, block);
}

// G28: a rapid to the intermediate point the axis words give (none for
// `G91 G28 Z0.`), then those axes to the machine's reference position,
// which is not in the work coordinates: the part's path leaves them.
void Machine::returnToReference(const Block& block, const std::map<char, double>& axes) {
  if (axes.empty()) {
    failInBlock(block, "G28 without an axis: which axes return to the reference position?");
  }
  bool moves = false;
  for (const auto& [letter, value] : axes) {
    if (!modal_.coordinates.isPlain() && (modal_.absolute || value != 0)) {
      failInBlock(block, "G28 through a point while G52, G68 or G16 is on is not simulated");
    }
    if (axisLetters.find(letter) == std::string_view::npos) {
      failInBlock(block, fmt::format("G28 takes axis words, not {}", letter));
    }
    double current = letter == 'X'   ? modal_.position.x
                     : letter == 'Y' ? modal_.position.y
                                     : modal_.position.z;
    moves = moves || (modal_.absolute ? roundToIncrement(value) != current : value != 0);
  }
  if (moves) {
    move(block, 0, axes);
  }
  modal_.atReference = true;
}

void Machine::move(const Block& block, int motion, const std::map<char, double>& axes) {
  if (modal_.atReference) {
    // The virtual machine does not know where its reference is in work
    // coordinates: from there Z must be given absolutely, by a rapid.
    if (axes.count('Z') > 0 && (!modal_.absolute || motion != 0)) {
      failInBlock(block, "after G28 the first Z move is a G00 to an absolute Z");
    }
    modal_.atReference = axes.count('Z') == 0;
  }
  if (axes.count('Z') > 0 && modal_.toolChanged && !modal_.lengthOffset &&
      profile_.requiresLengthOffset) {
    failInBlock(block, fmt::format("a Z move with tool {} in the spindle and no tool length "
                                   "offset active: G43 H.. must come first",
                                   modal_.selectedTool.value_or(0)));
  }
  if (modal_.coordinates.polar && motion > 1) {
    failInBlock(block, "arcs in G16 polar coordinates are not simulated");
  }
  Point3 target = programmedTarget(block, axes);
  double limit = modal_.inches ? profile_.maximumCoordinate / 10.0 : profile_.maximumCoordinate;
  for (double coordinate : {target.x, target.y, target.z}) {
    if (std::abs(coordinate) > limit + increment() / 2) {
      failInBlock(block, fmt::format("the coordinate {} is beyond the controller's range +-{}",
                                     coordinate, limit));
    }
  }
  bool arcWords = axes.count('I') + axes.count('J') + axes.count('K') + axes.count('R') > 0;
  if (motion == 0 || motion == 1) {
    if (arcWords) {
      failInBlock(block, "I, J, K or R in a straight move");
    }
    if (motion == 1 && !modal_.feed) {
      failInBlock(block, "G01 without a feed: no F has been commanded");
    }
    ExecutedEvent event{motion == 0 ? ExecutedEvent::Kind::Rapid : ExecutedEvent::Kind::Feed,
                        modal_.position,
                        target,
                        {},
                        motion == 0 ? 0 : *modal_.feed,
                        0,
                        block.line};
    output(event, block);
    modal_.position = target;
    return;
  }
  moveArc(block, motion, target, axes);
}

} // namespace cncc::backends::sim
