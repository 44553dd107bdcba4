#include "cncc/backends/sinumerik_writer.h"
#include "cncc/backends/program_format.h"

#include "cncc/ir/spline_move.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <utility>

namespace cncc::backends {

std::string formatSinumerikNumber(double value, int decimals) {
  std::string text = fmt::format("{:.{}f}", value, decimals);
  if (text.find('.') != std::string::npos) {
    text.erase(text.find_last_not_of('0') + 1);
    if (text.back() == '.') {
      text.pop_back();
    }
  }
  return text == "-0" ? "0" : text;
}

namespace {

using ir::MachineEvent;
constexpr std::size_t kMaximumNameLength = 24;

std::string methodName(ir::SplineKind kind) {
  switch (kind) {
  case ir::SplineKind::BSpline:
    return "bspline";
  case ir::SplineKind::CSpline:
    return "cspline";
  case ir::SplineKind::ASpline:
    return "aspline";
  }
  return "";
}

// Upper case letters, digits and underscores, the first two letters or
// underscores, as program names must be.
std::string programNameOf(const std::string& name) {
  std::string out;
  for (char c : name) {
    unsigned char u = static_cast<unsigned char>(c);
    out += std::isalnum(u) ? static_cast<char>(std::toupper(u)) : '_';
  }
  auto letterOrUnderscore = [](char c) {
    return std::isalpha(static_cast<unsigned char>(c)) || c == '_';
  };
  if (out.size() < 2 || !letterOrUnderscore(out[0]) || !letterOrUnderscore(out[1])) {
    out = "CN" + out;
  }
  // Room for the subprograms' _CUTnn_k.
  return out.substr(0, kMaximumNameLength - 10);
}

std::string commentText(std::string_view text) {
  std::string out;
  for (char c : text) {
    out += std::isprint(static_cast<unsigned char>(c)) ? c : ' ';
  }
  return out;
}

const char* startWord(geom::SplineEndCondition condition) {
  switch (condition) {
  case geom::SplineEndCondition::Auto:
    return "BAUTO";
  case geom::SplineEndCondition::Natural:
    return "BNAT";
  case geom::SplineEndCondition::Tangent:
    return "BTAN";
  }
  return "";
}

const char* endWord(geom::SplineEndCondition condition) {
  switch (condition) {
  case geom::SplineEndCondition::Auto:
    return "EAUTO";
  case geom::SplineEndCondition::Natural:
    return "ENAT";
  case geom::SplineEndCondition::Tangent:
    return "ETAN";
  }
  return "";
}

// A spline move's subprogram (the subprogram layout).
struct SplineSubprogram {
  std::uint32_t table = 0;
  std::string name;
  std::optional<std::size_t> cut;
  frontend::SourceSpan span; // of the cut statement that calls it first
};

class ProgramWriter {
public:
  ProgramWriter(const ir::ToolPath& path, std::span<const std::vector<double>> tables,
                std::size_t cutCount, const SinumerikOptions& options)
      : path_(path), tables_(tables), options_(options), name_(programNameOf(options.programName)) {
    program_.cuts.resize(cutCount);
  }

  SinumerikProgram write() {
    if (options_.subprograms) {
      line(fmt::format("%_N_{}_MPF", name_));
      line(";$PATH=/_N_MPF_DIR");
    }
    line(fmt::format("; {} - part {}", commentText(options_.sourceName),
                     commentText(options_.partName)));
    for (std::string& block : startBlocks(options_.setup, options_.inches)) {
      line(std::move(block));
    }
    if (usesSplines()) {
      line("SPLINEPATH(1,X,Y)");
    }
    for (std::size_t i = 0; i < path_.events.size(); ++i) {
      origin_ = {path_.events[i].span, path_.events[i].pass, noControllerLoop};
      i = event(i);
    }
    if (spindleOn_) {
      line("M5");
    }
    for (const std::string& block : options_.setup.end) {
      line(block);
    }
    line("M30");
    writeSubprograms();
    formatLines();
    return std::move(program_);
  }

private:
  bool usesSplines() const {
    return std::any_of(path_.events.begin(), path_.events.end(),
                       [](const MachineEvent& e) { return e.splineTable != 0; });
  }

  void line(std::string text) {
    lines_.push_back(std::move(text));
    cutOfPrintedLine_.push_back(cut_);
    originOfPrintedLine_.push_back(origin_);
  }

  // The program as the machine writes it (line numbers, comments).
  void formatLines() {
    std::vector<std::string> errors; // Sinumerik jumps to labels, not to N
    FormattedProgram formatted = formatProgram(std::move(lines_), options_.setup, errors);
    for (std::size_t i = 0; i < formatted.lines.size(); ++i) {
      program_.text += formatted.lines[i];
      program_.text += '\n';
      program_.cutOfLine.push_back(cutOfPrintedLine_[formatted.printedLine[i]]);
      program_.lineOrigins.lines.push_back(originOfPrintedLine_[formatted.printedLine[i]]);
    }
  }

  std::string number(double value) const { return formatSinumerikNumber(value, options_.decimals); }

  // Handles event i (and, for a lap cut as a spline, the feeds after it);
  // returns the last event used.
  std::size_t event(std::size_t i) {
    const MachineEvent& e = path_.events[i];
    switch (e.kind) {
    case MachineEvent::Kind::Rapid:
      rapid(e);
      break;
    case MachineEvent::Kind::Feed:
      return feed(i);
    case MachineEvent::Kind::Arc:
      arc(e);
      break;
    case MachineEvent::Kind::Spindle:
      line(fmt::format("M3 S{}", static_cast<long long>(std::llround(e.number))));
      spindleOn_ = true;
      break;
    case MachineEvent::Kind::Tool:
      tool(e);
      break;
    case MachineEvent::Kind::Home:
      for (const std::string& block : options_.setup.endRetract) {
        line(block);
      }
      break;
    case MachineEvent::Kind::Origin:
    case MachineEvent::Kind::Coolant:
    case MachineEvent::Kind::Contouring:
      if (std::string text = settingBlock(options_.setup, e, number(e.number)); !text.empty()) {
        line(std::move(text));
      }
      break;
    case MachineEvent::Kind::Comment:
      line("; " + commentText(e.text));
      break;
    case MachineEvent::Kind::CutBegin:
      cut_ = static_cast<std::size_t>(e.number);
      line(fmt::format("; cut {}", *cut_ + 1));
      break;
    case MachineEvent::Kind::Compensation:
      compensation(e);
      break;
    case MachineEvent::Kind::CornerArc: // lowered for the Fanuc and Mitsubishi targets only
      break;
    }
    return i;
  }

  void tool(const MachineEvent& e) {
    if (spindleOn_) {
      line("M5");
      spindleOn_ = false;
    }
    long long number = std::llround(e.number);
    std::string edge = toolEdgeWords(options_.setup, e.offsetRegister);
    std::string additions = fmt::format("{}{}; tool {}, diameter {}", edge, edge.empty() ? "" : " ",
                                        number, number_(e.diameter));
    for (std::string& block : toolChangeBlocks(options_.setup, number, additions)) {
      line(std::move(block));
    }
    // CYCLE832 sets the path mode itself where the machine has it.
    if (!pathModeWritten_ && options_.setup.contouringOn.empty()) {
      line("G64");
      if (options_.soft) {
        line("SOFT");
      }
      pathModeWritten_ = true;
    }
  }

  std::string number_(double value) const { return number(value); }

  // G41/G42 (left/right) with the radius of the active cutting edge, the D
  // of the tool change, or G40, on the next G1 in the plane. G450 (a
  // transition arc round an outside corner, as the compiler's offset and
  // verify's reference run it) is said once rather than left to the
  // machine's reset state, which may be G451.
  void compensation(const MachineEvent& e) {
    if (e.number == 0) {
      beforePlane_ = "G40";
      return;
    }
    beforePlane_ = e.number > 0 ? "G41" : "G42";
    if (!cornerModeWritten_) {
      beforePlane_ += " G450";
      cornerModeWritten_ = true;
    }
  }

  // Up first and down last, as the G-code writer does.
  void rapid(const MachineEvent& e) {
    // The G1 blocks of a pass of a cut without splines: its chords after the plunge.
    if (cut_ && *cut_ < program_.cuts.size() && feedsInPass_ > 0 &&
        program_.cuts[*cut_].method.empty()) {
      program_.cuts[*cut_].method = "linear";
      program_.cuts[*cut_].blocksPerPass = feedsInPass_ - 1;
    }
    feedsInPass_ = 0;
    Eigen::Vector3d target = roundPoint({e.x, e.y, e.z});
    if (e.alongZ) { // X and Y stay, printed or not
      move("G0", std::nullopt, std::nullopt, target.z(), std::nullopt);
      position_ = target;
      return;
    }
    bool rising = !position_ || target.z() > position_->z() + 1e-12;
    if (rising) {
      move("G0", std::nullopt, std::nullopt, target.z(), std::nullopt);
      move("G0", target.x(), target.y(), std::nullopt, std::nullopt);
    } else {
      move("G0", target.x(), target.y(), std::nullopt, std::nullopt);
      move("G0", std::nullopt, std::nullopt, target.z(), std::nullopt);
    }
    position_ = target;
  }

  void move(const char* code, std::optional<double> x, std::optional<double> y,
            std::optional<double> z, std::optional<double> feed) {
    std::string words;
    auto word = [&](char letter, std::optional<double> value, std::string& current) {
      if (value) {
        std::string text = number(*value);
        if (text != current) {
          words += fmt::format(" {}{}", letter, text);
          current = text;
        }
      }
    };
    word('X', x, x_);
    word('Y', y, y_);
    if (!words.empty() && !beforePlane_.empty() && std::string_view(code) == "G1") {
      words.insert(0, " " + beforePlane_);
      beforePlane_.clear();
    }
    word('Z', z, z_);
    if (words.empty()) {
      return;
    }
    std::string motion = code == motion_ ? "" : code;
    motion_ = code;
    std::string feedWord;
    if (feed) {
      std::string text = number(*feed);
      if (text != feed_) {
        feedWord = " F" + text;
        feed_ = text;
      }
    }
    std::string text = motion + words + feedWord;
    line(text.front() == ' ' ? text.substr(1) : text);
  }

  std::size_t feed(std::size_t i) {
    const MachineEvent& e = path_.events[i];
    if (e.splineTable != 0) {
      return spline(i);
    }
    linear({e.x, e.y, e.z}, e.feed);
    ++feedsInPass_;
    return i;
  }

  // G2/G3 with X and Y always (a full turn ends where it starts), Z for a
  // helix, I J incremental from the start as printed.
  void arc(const MachineEvent& e) {
    Eigen::Vector3d start = position_.value_or(Eigen::Vector3d::Zero());
    Eigen::Vector3d target = roundPoint({e.x, e.y, e.z});
    const char* code = e.clockwise ? "G2" : "G3";
    std::string words = code == motion_ ? "" : code;
    motion_ = code;
    x_ = number(target.x());
    y_ = number(target.y());
    words += fmt::format(" X{} Y{}", x_, y_);
    if (std::string z = number(target.z()); z != z_) {
      words += " Z" + z;
      z_ = z;
    }
    words += fmt::format(" I{} J{}", number(e.centreX - start.x()), number(e.centreY - start.y()));
    if (std::string feed = number(e.feed); feed != feed_) {
      words += " F" + feed;
      feed_ = feed;
    }
    line(words.front() == ' ' ? words.substr(1) : words);
    position_ = target;
  }

  void linear(const Eigen::Vector3d& point, double feed) {
    Eigen::Vector3d target = roundPoint(point);
    move("G1", target.x(), target.y(), target.z(), feed);
    position_ = target;
  }

  // The blocks of the move.spline whose first chord is event `first`;
  // returns its last chord.
  std::size_t spline(std::size_t first) {
    std::uint32_t table = path_.events[first].splineTable - 1;
    std::string problem;
    std::optional<ir::SplineBlockData> blocks =
        table < tables_.size() ? ir::readSplineMoveTable(tables_[table], &problem) : std::nullopt;
    if (!blocks) {
      throw std::logic_error("a spline move without its blocks: " + problem);
    }
    std::size_t last = first;
    while (last + 1 < path_.events.size() && path_.events[last + 1].splineTable == table + 1 &&
           !path_.events[last + 1].splineStart) {
      ++last;
    }
    std::string feedText = number(path_.events[first].feed);
    if (feedText != feed_) {
      line("F" + feedText);
      feed_ = feedText;
    }
    if (options_.subprograms) {
      line(subprogramOf(table));
    } else {
      splineBlocks(*blocks, [this](std::string text) { line(std::move(text)); });
    }
    if (cut_ && *cut_ < program_.cuts.size()) {
      SinumerikCutSummary& summary = program_.cuts[*cut_];
      summary.method = methodName(blocks->kind);
      summary.blocksPerPass = blocks->points.size();
    }
    // The spline ends at its last point, at the pass height.
    const MachineEvent& end = path_.events[last];
    position_ = roundPoint({end.x, end.y, end.z});
    x_ = number(blocks->points.back().x());
    y_ = number(blocks->points.back().y());
    motion_ = "spline";
    return last;
  }

  const std::string& subprogramOf(std::uint32_t table) {
    for (const SplineSubprogram& subprogram : subprograms_) {
      if (subprogram.table == table) {
        return subprogram.name;
      }
    }
    std::size_t cut = cut_.value_or(0);
    std::size_t index = subprogramsOfCut_[cut]++;
    subprograms_.push_back({table,
                            index == 0 ? fmt::format("{}_CUT{}", name_, cut + 1)
                                       : fmt::format("{}_CUT{}_{}", name_, cut + 1, index + 1),
                            cut_, origin_.span});
    return subprograms_.back().name;
  }

  template <typename Emit> void splineBlocks(const ir::SplineBlockData& blocks, Emit emit) const {
    bool bspline = blocks.kind == ir::SplineKind::BSpline;
    for (std::size_t i = 0; i < blocks.points.size(); ++i) {
      std::string words =
          fmt::format("X{} Y{}", number(blocks.points[i].x()), number(blocks.points[i].y()));
      if (bspline) {
        words += fmt::format(" PW={} PL={}", formatSinumerikNumber(blocks.weights[i], 4),
                             formatSinumerikNumber(blocks.intervals[i], options_.decimals + 3));
        if (i == 0) {
          words = fmt::format("BSPLINE SD={} {}", blocks.degree, words);
        }
      } else if (i == 0) {
        emit(fmt::format("{} {}", startWord(blocks.start), endWord(blocks.end)));
        words = (blocks.kind == ir::SplineKind::CSpline ? "CSPLINE " : "ASPLINE ") + words;
      }
      emit(words);
    }
  }

  // Each subprogram's lines, its header too, come from the cut that made it.
  void writeSubprograms() {
    for (const SplineSubprogram& subprogram : subprograms_) {
      cut_ = subprogram.cut;
      origin_ = LineOrigin{}; // called by every pass: none of its own
      origin_.span = subprogram.span;
      std::optional<ir::SplineBlockData> blocks =
          ir::readSplineMoveTable(tables_[subprogram.table]);
      line(fmt::format("%_N_{}_SPF", subprogram.name));
      line(";$PATH=/_N_SPF_DIR");
      line(fmt::format("; cut {}: the spline of every pass, at the height the caller is at",
                       cut_.value_or(0) + 1));
      splineBlocks(*blocks, [this](std::string text) { line(std::move(text)); });
      line("M17");
    }
  }

  Eigen::Vector3d roundPoint(const Eigen::Vector3d& point) const {
    auto rounded = [this](double value) { return std::stod(number(value)); };
    return {rounded(point.x()), rounded(point.y()), rounded(point.z())};
  }

  const ir::ToolPath& path_;
  std::span<const std::vector<double>> tables_;
  const SinumerikOptions& options_;
  std::string name_;
  SinumerikProgram program_;
  std::vector<std::string> lines_;
  std::vector<std::optional<std::size_t>> cutOfPrintedLine_;
  std::vector<LineOrigin> originOfPrintedLine_;
  LineOrigin origin_; // of the event being written
  std::optional<std::size_t> cut_;
  std::optional<Eigen::Vector3d> position_;
  std::size_t feedsInPass_ = 0; // G1 blocks since the last rapid
  bool spindleOn_ = false;
  bool pathModeWritten_ = false;
  bool cornerModeWritten_ = false; // G450
  std::string beforePlane_;        // G41/G42/G40 for the next G1 in the plane
  std::string motion_, x_, y_, z_, feed_;
  std::vector<SplineSubprogram> subprograms_;
  std::map<std::size_t, std::size_t> subprogramsOfCut_;
};

} // namespace

ir::LoweringOptions sinumerikLoweringOptions(const SinumerikOptions& options) {
  ir::LoweringOptions lowering;
  lowering.splineInterpolation = true;
  lowering.splineBlocks = true;
  lowering.splineEnds = options.transitions;
  lowering.coordinateIncrement = std::pow(10.0, -options.decimals);
  return lowering;
}

SinumerikProgram writeSinumerik(const ir::ToolPath& path,
                                std::span<const std::vector<double>> tables, std::size_t cutCount,
                                const SinumerikOptions& options) {
  return ProgramWriter(path, tables, cutCount, options).write();
}

} // namespace cncc::backends
