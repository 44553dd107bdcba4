#include "cncc/backends/gcode_writer.h"

#include "cncc/backends/line_spans.h"
#include "cncc/backends/program_format.h"

#include <fmt/format.h>

#include <cctype>
#include <cmath>
#include <optional>
#include <span>
#include <vector>

namespace cncc::backends {

std::string formatGcodeNumber(double value, int decimals) {
  std::string text = fmt::format("{:.{}f}", value, decimals);
  std::size_t point = text.find('.');
  if (point == std::string::npos) {
    text += '.';
  } else {
    std::size_t last = text.find_last_not_of('0');
    text.erase(last + 1); // keeps the point when every decimal was 0
  }
  if (text == "-0.") {
    text = "0.";
  }
  return text;
}

std::string gcodeCommentText(std::string_view text) {
  std::string out;
  for (char c : text) {
    if (c == '(' || c == ')') {
      continue;
    }
    unsigned char u = static_cast<unsigned char>(c);
    out += std::isprint(u) ? c : ' ';
  }
  return out;
}

std::optional<int> programNumberFromFileName(std::string_view path) {
  std::size_t slash = path.find_last_of('/');
  std::string_view name = slash == std::string_view::npos ? path : path.substr(slash + 1);
  std::size_t dot = name.find('.');
  if (dot != std::string_view::npos) {
    name = name.substr(0, dot);
  }
  if (name.size() < 2 || name.size() > 9 || (name[0] != 'O' && name[0] != 'o')) {
    return std::nullopt;
  }
  int number = 0;
  for (char c : name.substr(1)) {
    if (!std::isdigit(static_cast<unsigned char>(c))) {
      return std::nullopt;
    }
    number = number * 10 + (c - '0');
  }
  return number > 0 ? std::optional<int>(number) : std::nullopt;
}

namespace {

// Prints motion blocks, keeping coordinates and the feed modal.
class BlockWriter {
public:
  explicit BlockWriter(int decimals) : decimals_(decimals) {}

  void line(std::string text) {
    lines_.push_back(std::move(text));
    origins_.push_back(origin_);
  }

  // Where the lines that follow come from (plain G-code has no loops).
  void setOrigin(const ir::MachineEvent& event) {
    origin_ = {event.span, event.pass, noControllerLoop};
  }

  void move(bool rapid, double x, double y, double z, double feed) {
    if (rapid) {
      // Up first and down last, so a rapid never moves sideways below the
      // height it starts or ends at.
      bool rising = !known_ || z > z_ + 1e-12;
      if (rising) {
        block(true, std::nullopt, std::nullopt, z, 0);
        block(true, x, y, std::nullopt, 0);
      } else {
        block(true, x, y, std::nullopt, 0);
        block(true, std::nullopt, std::nullopt, z, 0);
      }
      return;
    }
    block(false, x, y, z, feed);
  }

  // A rapid along Z alone (move.climb): X and Y stay, printed or not.
  void climb(double z) { block(true, std::nullopt, std::nullopt, z, 0); }

  // An arc (move.arc, native or fitted): X and Y always (a full turn ends
  // where it starts), Z when it climbs or descends (a helix), I J from the
  // start as printed.
  void arc(const ir::MachineEvent& event) {
    double startX = x_.empty() ? 0.0 : std::stod(x_);
    double startY = y_.empty() ? 0.0 : std::stod(y_);
    x_ = formatGcodeNumber(event.x, decimals_);
    y_ = formatGcodeNumber(event.y, decimals_);
    std::string words = fmt::format("{} X{} Y{}", event.clockwise ? "G02" : "G03", x_, y_);
    std::string z = formatGcodeNumber(event.z, decimals_);
    if (z != zText_) {
      words += " Z" + z;
      zText_ = z;
      z_ = event.z;
    }
    words += fmt::format(" I{} J{}", formatGcodeNumber(event.centreX - startX, decimals_),
                         formatGcodeNumber(event.centreY - startY, decimals_));
    std::string feed = formatGcodeNumber(event.feed, decimals_);
    if (feed != feed_) {
      words += " F" + feed;
      feed_ = feed;
    }
    line(std::move(words));
  }

  std::vector<std::string> takeLines() { return std::move(lines_); }
  const std::vector<LineOrigin>& origins() const { return origins_; }

  // After a move the writer does not follow: every coordinate is printed
  // again.
  void forget() {
    x_.clear();
    y_.clear();
    zText_.clear();
    known_ = false;
  }

  // Words the next block with a Z word carries (the length offset after a
  // tool change).
  void beforeNextZ(std::string words) { beforeZ_ = std::move(words); }
  // Words the next feed move in the plane carries (G41/G42 D.. or G40: the
  // controls switch cutter radius compensation on and off on such a move).
  void beforeNextPlaneMove(std::string words) { beforePlane_ = std::move(words); }

private:
  void block(bool rapid, std::optional<double> x, std::optional<double> y, std::optional<double> z,
             double feed) {
    std::string words;
    auto word = [&](char letter, std::optional<double> value, std::string& current) {
      if (!value) {
        return;
      }
      std::string text = formatGcodeNumber(*value, decimals_);
      if (text != current) {
        words += fmt::format(" {}{}", letter, text);
        current = text;
      }
    };
    word('X', x, x_);
    word('Y', y, y_);
    if (!rapid && !words.empty() && !beforePlane_.empty()) {
      words.insert(0, " " + beforePlane_);
      beforePlane_.clear();
    }
    std::size_t beforeZ = words.size();
    word('Z', z, zText_);
    if (words.size() > beforeZ && !beforeZ_.empty()) {
      words.insert(0, " " + beforeZ_);
      beforeZ_.clear();
    }
    if (z) {
      z_ = *z;
    }
    if (x && y && z) {
      known_ = true;
    }
    if (words.empty()) {
      return; // the machine is already there
    }
    std::string feedWord;
    if (!rapid) {
      std::string text = formatGcodeNumber(feed, decimals_);
      if (text != feed_) {
        feedWord = " F" + text;
        feed_ = text;
      }
    }
    line(fmt::format("{}{}{}", rapid ? "G00" : "G01", words, feedWord));
  }

  int decimals_;
  std::vector<std::string> lines_;
  std::vector<LineOrigin> origins_;
  LineOrigin origin_;
  std::string x_, y_, zText_, feed_, beforeZ_, beforePlane_;
  double z_ = 0;
  bool known_ = false;
};

} // namespace

GcodeProgram writeGcodeProgram(const ir::ToolPath& path, const GcodeOptions& options) {
  BlockWriter writer(options.decimals);
  writer.line("%");
  writer.line(fmt::format("O{}", options.programNumber));
  writer.line(fmt::format("({} - PART {})", gcodeCommentText(options.sourceName),
                          gcodeCommentText(options.partName)));
  for (std::string& block : startBlocks(options.setup, options.inches)) {
    writer.line(std::move(block));
  }
  bool spindleOn = false;
  for (const ir::MachineEvent& event : path.events) {
    writer.setOrigin(event);
    switch (event.kind) {
    case ir::MachineEvent::Kind::Rapid:
    case ir::MachineEvent::Kind::Feed:
      if (event.alongZ) {
        writer.climb(event.z);
        break;
      }
      writer.move(event.kind == ir::MachineEvent::Kind::Rapid, event.x, event.y, event.z,
                  event.feed);
      break;
    case ir::MachineEvent::Kind::Arc:
      writer.arc(event);
      break;
    case ir::MachineEvent::Kind::Spindle:
      writer.line(fmt::format("S{} M03", static_cast<long long>(std::llround(event.number))));
      spindleOn = true;
      break;
    case ir::MachineEvent::Kind::Tool:
      if (spindleOn) {
        writer.line("M05");
        spindleOn = false;
      }
      for (std::string& block : toolChangeBlocks(
               options.setup, std::llround(event.number),
               fmt::format("(DIAMETER {})", formatGcodeNumber(event.diameter, options.decimals)))) {
        writer.line(std::move(block));
      }
      writer.beforeNextZ(lengthOffsetWords(
          options.setup, static_cast<int>(std::llround(event.number)), event.offsetRegister));
      break;
    case ir::MachineEvent::Kind::Home:
      for (const std::string& block : options.setup.endRetract) {
        writer.line(block);
      }
      writer.forget();
      break;
    case ir::MachineEvent::Kind::Origin:
    case ir::MachineEvent::Kind::Coolant:
    case ir::MachineEvent::Kind::Contouring:
      if (std::string text =
              settingBlock(options.setup, event, formatGcodeNumber(event.number, options.decimals));
          !text.empty()) {
        writer.line(std::move(text));
      }
      break;
    case ir::MachineEvent::Kind::Comment:
      writer.line(fmt::format("({})", gcodeCommentText(event.text)));
      break;
    case ir::MachineEvent::Kind::CutBegin: // the cut's own comment already says it
      break;
    case ir::MachineEvent::Kind::Compensation:
      writer.beforeNextPlaneMove(compensationBlock(event.number, event.offsetRegister));
      break;
    case ir::MachineEvent::Kind::CornerArc: // lowered for the Fanuc and Mitsubishi targets only
      break;
    }
  }
  if (spindleOn) {
    writer.line("M05");
  }
  for (const std::string& block : options.setup.end) {
    writer.line(block);
  }
  writer.line("M30");
  writer.line("%");
  std::vector<LineOrigin> origins = writer.origins();
  // Plain G-code has no jumps, so numbering it cannot fail.
  std::vector<std::string> errors;
  FormattedProgram formatted = formatProgram(writer.takeLines(), options.setup, errors);
  GcodeProgram program;
  for (const std::string& line : formatted.lines) {
    program.text += line;
    program.text += '\n';
  }
  program.lineOrigins.lines = LineSpans::kept(origins, formatted.printedLine);
  return program;
}

std::string writeGcode(const ir::ToolPath& path, const GcodeOptions& options) {
  return writeGcodeProgram(path, options).text;
}

} // namespace cncc::backends
