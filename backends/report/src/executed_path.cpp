#include "cncc/backends/executed_path.h"

#include "cncc/backends/gcode_writer.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <numbers>

namespace cncc::backends {

namespace {

using ir::MachineEvent;

// A modal position: an axis is unknown until a block has set it.
using ModalPosition = std::array<std::optional<double>, 3>;

bool isKnown(const ModalPosition& position) {
  return position[0] && position[1] && position[2];
}

Eigen::Vector3d pointOf(const ModalPosition& position) {
  return {*position[0], *position[1], *position[2]};
}

// One G00/G01 block as read, before the cuts are known.
struct GcodeBlock {
  bool rapid = false;
  ModalPosition position; // after the block
  double feed = 0;
  std::optional<std::size_t> cut;
  std::size_t line = 0;
};

// The program without comments: `( ... )` and from `;` to the end of the line.
std::string withoutComment(std::string_view line) {
  std::string text;
  bool inComment = false;
  for (char c : line) {
    if (c == ';' && !inComment) {
      break;
    }
    if (c == '(') {
      inComment = true;
    } else if (c == ')') {
      inComment = false;
    } else if (!inComment) {
      text += c;
    }
  }
  return text;
}

struct Word {
  char letter;
  double value;
};

std::vector<Word> wordsOf(std::string_view text, std::size_t lineNumber) {
  std::vector<Word> words;
  std::size_t i = 0;
  while (i < text.size()) {
    unsigned char c = static_cast<unsigned char>(text[i]);
    if (std::isspace(c)) {
      ++i;
      continue;
    }
    if (!std::isalpha(c)) {
      throw ExecutionMismatch(fmt::format("line {}: unexpected '{}'", lineNumber, text[i]));
    }
    std::size_t begin = i + 1;
    std::size_t end = begin;
    while (end < text.size() && (std::isdigit(static_cast<unsigned char>(text[end])) ||
                                 text[end] == '.' || text[end] == '-' || text[end] == '+')) {
      ++end;
    }
    double value = 0;
    const char* first = text.data() + begin + (begin < end && text[begin] == '+' ? 1 : 0);
    auto [stop, error] = std::from_chars(first, text.data() + end, value);
    if (begin == end || error != std::errc() || stop != text.data() + end) {
      throw ExecutionMismatch(
          fmt::format("line {}: '{}' has no number", lineNumber, text.substr(i, end - i)));
    }
    words.push_back({static_cast<char>(std::toupper(c)), value});
    i = end;
  }
  return words;
}

class GcodeReader {
public:
  std::vector<GcodeBlock> read(std::string_view program) {
    std::size_t lineNumber = 0;
    while (!program.empty()) {
      std::size_t newline = program.find('\n');
      std::string_view line = program.substr(0, newline);
      program =
          newline == std::string_view::npos ? std::string_view() : program.substr(newline + 1);
      ++lineNumber;
      if (line.find('%') == std::string_view::npos) {
        readBlock(wordsOf(withoutComment(line), lineNumber), lineNumber);
      }
    }
    return std::move(blocks_);
  }

private:
  // A block that moves in machine coordinates (the end retract: G28's
  // return to the reference point, G53): not a move of the tool path.
  static bool movesInMachineCoordinates(const std::vector<Word>& words) {
    return std::any_of(words.begin(), words.end(), [](const Word& word) {
      return word.letter == 'G' && (word.value == 28 || word.value == 53);
    });
  }

  void readBlock(const std::vector<Word>& words, std::size_t lineNumber) {
    if (movesInMachineCoordinates(words)) {
      position_[2].reset(); // Z is somewhere up at the reference point
      return;
    }
    bool moves = false;
    std::optional<ArcMotion> arc;
    Eigen::Vector2d centre = Eigen::Vector2d::Zero(); // I J, from the start
    ModalPosition start = position_;
    for (const Word& word : words) {
      if (word.letter == 'G' && (word.value == 0 || word.value == 1)) {
        rapid_ = word.value == 0;
        motionKnown_ = true;
      } else if (word.letter == 'G' && (word.value == 2 || word.value == 3)) {
        arc = word.value == 2 ? ArcMotion::Clockwise : ArcMotion::Counterclockwise;
      } else if (word.letter == 'I' || word.letter == 'J') {
        (word.letter == 'I' ? centre.x() : centre.y()) = word.value;
      } else if (word.letter >= 'X' && word.letter <= 'Z') {
        position_[static_cast<std::size_t>(word.letter - 'X')] = word.value;
        moves = true;
      } else if (word.letter == 'F') {
        feed_ = word.value;
      }
    }
    if (!moves) {
      return;
    }
    if (arc) {
      addArc(*arc, start, centre, lineNumber);
      return;
    }
    if (!motionKnown_) {
      throw ExecutionMismatch(fmt::format("line {}: a move before G00 or G01", lineNumber));
    }
    blocks_.push_back({rapid_, position_, rapid_ ? 0.0 : feed_, std::nullopt, lineNumber});
  }

  enum class ArcMotion { Clockwise, Counterclockwise };

  // A G02/G03 block (XY plane, I J centre, not modal here: the printers
  // write the G word on every arc) as feed moves along it whose sagitta is
  // at most 1e-5 (program units), so that measuring them measures the arc.
  void addArc(ArcMotion motion, const ModalPosition& start, const Eigen::Vector2d& offset,
              std::size_t lineNumber) {
    if (!isKnown(start)) {
      throw ExecutionMismatch(fmt::format("line {}: an arc from an unknown position", lineNumber));
    }
    Eigen::Vector3d from = pointOf(start);
    Eigen::Vector3d to = pointOf(position_);
    Eigen::Vector2d centre = from.head<2>() + offset;
    Eigen::Vector2d a = from.head<2>() - centre;
    Eigen::Vector2d b = to.head<2>() - centre;
    double startRadius = a.norm();
    if (startRadius == 0) {
      throw ExecutionMismatch(fmt::format("line {}: the arc's centre is its start", lineNumber));
    }
    double sweep = std::atan2(a.x() * b.y() - a.y() * b.x(), a.dot(b));
    bool clockwise = motion == ArcMotion::Clockwise;
    if (clockwise && sweep >= 0) {
      sweep -= 2 * std::numbers::pi;
    } else if (!clockwise && sweep <= 0) {
      sweep += 2 * std::numbers::pi;
    }
    double startAngle = std::atan2(a.y(), a.x());
    double endRadius = b.norm();
    // The radius changes linearly from start to end, as controllers do.
    double largest = std::max(startRadius, endRadius);
    double step = 2 * std::acos(1 - std::min(1.0, 1e-5 / largest));
    auto steps = static_cast<std::size_t>(std::min(1e5, std::ceil(std::fabs(sweep) / step)));
    for (std::size_t k = 1; k <= steps; ++k) {
      double share = static_cast<double>(k) / static_cast<double>(steps);
      double radius = startRadius + (endRadius - startRadius) * share;
      double angle = startAngle + sweep * share;
      ModalPosition point = position_;
      if (k < steps) {
        point[0] = centre.x() + radius * std::cos(angle);
        point[1] = centre.y() + radius * std::sin(angle);
        point[2] = from.z() + (to.z() - from.z()) * share;
      }
      blocks_.push_back({false, point, feed_, std::nullopt, lineNumber});
    }
    rapid_ = false;
    motionKnown_ = true;
  }

  std::vector<GcodeBlock> blocks_;
  ModalPosition position_;
  bool rapid_ = true;
  bool motionKnown_ = false;
  double feed_ = 0;
};

// Gives each G01 block the cut of the tool path event that printed it. The
// writer prints a block for every move that changes a printed coordinate, and
// a rapid as up to two blocks (Z and XY), so the walk is in lockstep.
class CutAssignment {
public:
  CutAssignment(std::vector<GcodeBlock>& blocks, int decimals)
      : blocks_(blocks), decimals_(decimals) {}

  void run(const ir::ToolPath& toolPath) {
    std::optional<std::size_t> cut;
    for (const MachineEvent& event : toolPath.events) {
      if (event.kind == MachineEvent::Kind::CutBegin) {
        cut = static_cast<std::size_t>(event.number);
      } else if (event.kind == MachineEvent::Kind::Rapid ||
                 event.kind == MachineEvent::Kind::Feed || event.kind == MachineEvent::Kind::Arc) {
        follow(event, cut); // the reader has an arc's blocks as chords of one line
      }
    }
    if (next_ != blocks_.size()) {
      throw ExecutionMismatch(
          fmt::format("line {}: a move the tool path does not have", blocks_[next_].line));
    }
  }

private:
  // Where the event ends (a climb along Z alone: at its height, X and Y
  // where they were, printed or not).
  bool isAt(const MachineEvent& event) const {
    auto same = [&](const std::optional<double>& axis, double target) {
      return axis && formatGcodeNumber(*axis, decimals_) == formatGcodeNumber(target, decimals_);
    };
    return (event.alongZ || (same(position_[0], event.x) && same(position_[1], event.y))) &&
           same(position_[2], event.z);
  }

  void follow(const MachineEvent& event, std::optional<std::size_t> cut) {
    bool rapid = event.kind == MachineEvent::Kind::Rapid;
    // An arc moves even when it ends where it starts (a full circle).
    bool mustMove = event.kind == MachineEvent::Kind::Arc;
    while (mustMove || !isAt(event)) {
      mustMove = false;
      if (next_ == blocks_.size() || blocks_[next_].rapid != rapid) {
        throw ExecutionMismatch(fmt::format(
            "the program has no {} to ({}, {}, {})", rapid ? "rapid" : "feed move",
            formatGcodeNumber(event.x, decimals_), formatGcodeNumber(event.y, decimals_),
            formatGcodeNumber(event.z, decimals_)));
      }
      GcodeBlock& block = blocks_[next_++];
      block.cut = rapid ? std::nullopt : cut;
      position_ = block.position;
      bool arcGoesOn = next_ < blocks_.size() && blocks_[next_].line == block.line;
      if (!rapid && !isAt(event) && !arcGoesOn) {
        throw ExecutionMismatch(
            fmt::format("line {}: the feed move does not reach the tool path's", block.line));
      }
    }
  }

  std::vector<GcodeBlock>& blocks_;
  int decimals_;
  std::size_t next_ = 0;
  ModalPosition position_;
};

} // namespace

PathTooLargeToMeasure::PathTooLargeToMeasure(double limit, double arcSagitta)
    : std::runtime_error(fmt::format("the executed path has more than {:.0f} points to measure "
                                     "(arcs as chords within {:g}): too large to verify",
                                     limit, arcSagitta)) {}

void checkMeasurablePath(const ir::ToolPath& toolPath, double arcSagitta) {
  if (!(ir::flattenedEventCount(toolPath, arcSagitta) <= maximumMeasuredPoints)) {
    throw PathTooLargeToMeasure(maximumMeasuredPoints, arcSagitta);
  }
}

ExecutedPath executedPathOfToolPath(const ir::ToolPath& toolPath, double arcSagitta) {
  ExecutedPath path;
  bool started = false;
  std::optional<std::size_t> cut;
  for (const MachineEvent& event : ir::flattenArcs(toolPath, arcSagitta).events) {
    if (event.kind == MachineEvent::Kind::CutBegin) {
      cut = static_cast<std::size_t>(event.number);
      continue;
    }
    bool rapid = event.kind == MachineEvent::Kind::Rapid;
    if (!rapid && event.kind != MachineEvent::Kind::Feed) {
      continue;
    }
    Eigen::Vector3d target(event.x, event.y, event.z);
    if (!started && event.alongZ) {
      continue; // a climb from where the tool change left X and Y: not known
    }
    if (!started) {
      path.start = target;
      started = true;
      continue;
    }
    path.moves.push_back({rapid, target, rapid ? 0.0 : event.feed, rapid ? std::nullopt : cut});
  }
  return path;
}

ExecutedPath executeGcode(std::string_view program, const ir::ToolPath& toolPath, int decimals) {
  std::vector<GcodeBlock> blocks = GcodeReader().read(program);
  CutAssignment(blocks, decimals).run(toolPath);
  ExecutedPath path;
  bool started = false;
  for (const GcodeBlock& block : blocks) {
    if (!isKnown(block.position)) {
      continue;
    }
    if (!started) {
      path.start = pointOf(block.position);
      started = true;
      continue;
    }
    path.moves.push_back({block.rapid, pointOf(block.position), block.feed, block.cut});
  }
  return path;
}

std::size_t countProgramBlocks(std::string_view program) {
  std::size_t blocks = 0;
  while (!program.empty()) {
    std::size_t newline = program.find('\n');
    std::string_view line = program.substr(0, newline);
    program = newline == std::string_view::npos ? std::string_view() : program.substr(newline + 1);
    bool blank = line.find_first_not_of(" \t\r") == std::string_view::npos;
    if (!blank && line.find_first_not_of(" \t\r%") != std::string_view::npos) {
      ++blocks;
    }
  }
  return blocks;
}

} // namespace cncc::backends
