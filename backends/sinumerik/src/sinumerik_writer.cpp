#include "cncc/backends/sinumerik_writer.h"
#include "cncc/backends/program_format.h"

#include "sinumerik_splines.h"

#include "cncc/geom/discretisation.h"
#include "cncc/geom/geometry_error.h"

#include <fmt/format.h>

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
using sinumerik::SplineBlocks;
using sinumerik::SplineKind;

constexpr double kSameZ = 1e-9;
constexpr double kSamePoint = 1e-6;
constexpr std::size_t kMaximumNameLength = 24;

std::optional<SplineKind> splineKindOf(const std::string& method) {
  if (method == "bspline" || method == "nurbs") {
    return SplineKind::BSpline;
  }
  if (method == "cspline") {
    return SplineKind::CSpline;
  }
  if (method == "aspline") {
    return SplineKind::ASpline;
  }
  return std::nullopt;
}

std::string methodName(SplineKind kind) {
  switch (kind) {
  case SplineKind::BSpline:
    return "bspline";
  case SplineKind::CSpline:
    return "cspline";
  case SplineKind::ASpline:
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

// The spline blocks of one cut for one start direction.
struct CachedSpline {
  std::optional<Eigen::Vector3d> startDirection;
  SplineBlocks blocks;
  std::string subprogram; // its name, in the subprogram layout
};

class ProgramWriter {
public:
  ProgramWriter(const ir::ToolPath& path, std::span<const SinumerikCut> cuts,
                const SinumerikOptions& options)
      : path_(path), cuts_(cuts), options_(options), name_(programNameOf(options.programName)) {
    program_.cuts.resize(cuts.size());
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
      span_ = path_.events[i].span;
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
    for (const SinumerikCut& cut : cuts_) {
      if (splineKindOf(cut.method)) {
        return true;
      }
    }
    return false;
  }

  void line(std::string text) {
    lines_.push_back(std::move(text));
    cutOfPrintedLine_.push_back(cut_);
    spanOfPrintedLine_.push_back(span_);
  }

  // The program as the machine writes it (line numbers, comments).
  void formatLines() {
    std::vector<std::string> errors; // Sinumerik jumps to labels, not to N
    FormattedProgram formatted = formatProgram(std::move(lines_), options_.setup, errors);
    for (std::size_t i = 0; i < formatted.lines.size(); ++i) {
      program_.text += formatted.lines[i];
      program_.text += '\n';
      program_.cutOfLine.push_back(cutOfPrintedLine_[formatted.printedLine[i]]);
      program_.lineSpans.push_back(spanOfPrintedLine_[formatted.printedLine[i]]);
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

  // Up first and down last, as the G-code writer does.
  void rapid(const MachineEvent& e) {
    exact_ = Eigen::Vector3d(e.x, e.y, e.z);
    Eigen::Vector3d target = sinumerik::roundPoint({e.x, e.y, e.z}, options_.decimals);
    bool rising = !position_ || target.z() > position_->z() + 1e-12;
    if (rising) {
      move("G0", std::nullopt, std::nullopt, target.z(), std::nullopt);
      move("G0", target.x(), target.y(), std::nullopt, std::nullopt);
    } else {
      move("G0", target.x(), target.y(), std::nullopt, std::nullopt);
      move("G0", std::nullopt, std::nullopt, target.z(), std::nullopt);
    }
    previous_ = position_;
    position_ = target;
    lastWasFeed_ = false;
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
    if (std::optional<Lap> lap = lapAt(i)) {
      std::optional<SplineKind> kind = splineKindOf(cuts_[*cut_].method);
      if (kind && lap->flat) {
        spline(i, lap->end, *kind);
      } else {
        chords(i, *lap);
      }
      return lap->end - 1;
    }
    const MachineEvent& e = path_.events[i];
    linear({e.x, e.y, e.z}, e.feed);
    return i;
  }

  // G2/G3 with X and Y always (a full turn ends where it starts), Z for a
  // helix, I J incremental from the start as printed.
  void arc(const MachineEvent& e) {
    Eigen::Vector3d start = position_.value_or(Eigen::Vector3d::Zero());
    exact_ = Eigen::Vector3d(e.x, e.y, e.z);
    Eigen::Vector3d target = sinumerik::roundPoint(*exact_, options_.decimals);
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
    previous_ = position_;
    position_ = target;
    lastWasFeed_ = false;
  }

  void linear(const Eigen::Vector3d& point, double feed) {
    exact_ = point;
    Eigen::Vector3d target = sinumerik::roundPoint(point, options_.decimals);
    move("G1", target.x(), target.y(), target.z(), feed);
    previous_ = position_;
    position_ = target;
    lastWasFeed_ = true;
  }

  // A run of feeds that traces the cut's whole curve once, from the current
  // position: at one height, or descending (a ramp) in proportion to the
  // chord length done.
  struct Lap {
    std::size_t end = 0; // one past its last feed
    bool flat = true;
  };

  std::optional<Lap> lapAt(std::size_t i) const {
    if (!cut_ || *cut_ >= cuts_.size() || !exact_ || cuts_[*cut_].geometry.curve == nullptr) {
      return std::nullopt;
    }
    const geom::Curve& curve = *cuts_[*cut_].geometry.curve;
    geom::ParameterRange domain = curve.domain();
    auto inPlane = [](const Eigen::Vector3d& point) {
      return Eigen::Vector2d(point.x(), point.y());
    };
    if ((inPlane(*exact_) - inPlane(curve.point(domain.t0))).norm() > kSamePoint) {
      return std::nullopt;
    }
    const MachineEvent& first = path_.events[i];
    if ((Eigen::Vector2d(first.x, first.y) - inPlane(*exact_)).norm() <= kSamePoint) {
      return std::nullopt; // a plunge
    }
    Eigen::Vector2d finish = inPlane(curve.point(domain.t1));
    Lap lap;
    lap.flat = isPlanar(curve);
    for (std::size_t j = i; j < path_.events.size(); ++j) {
      const MachineEvent& e = path_.events[j];
      if (e.kind != MachineEvent::Kind::Feed) {
        return std::nullopt;
      }
      lap.flat = lap.flat && std::abs(e.z - exact_->z()) <= kSameZ + 1e-9 * std::abs(e.z);
      if ((Eigen::Vector2d(e.x, e.y) - finish).norm() <= kSamePoint) {
        lap.end = j + 1;
        return lap;
      }
    }
    return std::nullopt;
  }

  // Whether the curve lies in a plane z = constant (the spline axes are X, Y).
  static bool isPlanar(const geom::Curve& curve) {
    constexpr int kProbes = 16;
    geom::ParameterRange domain = curve.domain();
    double z = curve.point(domain.t0).z();
    for (int k = 1; k <= kProbes; ++k) {
      if (std::abs(curve.point(domain.t0 + domain.length() * k / kProbes).z() - z) > kSameZ) {
        return false;
      }
    }
    return true;
  }

  // A lap that is not a spline: the tool path's chords, which left room for
  // the printed rounding already (LoweringOptions::coordinateIncrement).
  void chords(std::size_t first, const Lap& lap) {
    for (std::size_t j = first; j < lap.end; ++j) {
      const MachineEvent& e = path_.events[j];
      linear({e.x, e.y, e.z}, e.feed);
    }
    SinumerikCutSummary& summary = program_.cuts[*cut_];
    if (summary.method.empty()) {
      summary.method = "linear";
      summary.blocksPerPass = lap.end - first;
    }
  }

  // The XY direction of the feed move that arrived at the current position.
  std::optional<Eigen::Vector3d> arrivalDirection() const {
    if (!lastWasFeed_ || !previous_ || !position_) {
      return std::nullopt;
    }
    Eigen::Vector3d direction = *position_ - *previous_;
    direction.z() = 0;
    if (direction.norm() <= kSamePoint) {
      return std::nullopt;
    }
    return direction.normalized();
  }

  const CachedSpline& splineFor(std::size_t first, std::size_t end, SplineKind kind) {
    std::optional<Eigen::Vector3d> direction =
        kind == SplineKind::BSpline ? std::nullopt : arrivalDirection();
    std::vector<CachedSpline>& cached = cache_[*cut_];
    for (const CachedSpline& entry : cached) {
      bool same = entry.startDirection.has_value() == direction.has_value() &&
                  (!direction || (*entry.startDirection - *direction).norm() <= 1e-12);
      if (same) {
        return entry;
      }
    }
    const SinumerikCut& cut = cuts_[*cut_];
    sinumerik::SplineRequest request;
    request.curve = cut.geometry.curve.get();
    request.kind = kind;
    request.tolerance = cut.geometry.tolerance;
    request.samples.push_back({exact_->x(), exact_->y(), 0.0});
    for (std::size_t j = first; j < end; ++j) {
      request.samples.push_back({path_.events[j].x, path_.events[j].y, 0.0});
    }
    request.startDirection = direction;
    request.transitions = options_.transitions;
    request.decimals = options_.decimals;
    CachedSpline entry;
    entry.startDirection = direction;
    try {
      entry.blocks = sinumerik::chooseSplineBlocks(request);
    } catch (const geom::GeometryError& error) {
      throw SinumerikError(
          *cut_, fmt::format("cannot write cut {} as {}: {}", *cut_ + 1, cut.method, error.what()));
    }
    std::size_t index = cached.size();
    entry.subprogram = index == 0 ? fmt::format("{}_CUT{}", name_, *cut_ + 1)
                                  : fmt::format("{}_CUT{}_{}", name_, *cut_ + 1, index + 1);
    SinumerikCutSummary& summary = program_.cuts[*cut_];
    summary.method = methodName(kind);
    summary.blocksPerPass = entry.blocks.points.size();
    summary.modelledDeviation = std::max(summary.modelledDeviation, entry.blocks.deviation);
    summary.exact = entry.blocks.exact;
    summary.note = entry.blocks.note;
    cached.push_back(std::move(entry));
    if (options_.subprograms) {
      subprogramOrder_.push_back({*cut_, index});
    }
    return cached.back();
  }

  void spline(std::size_t first, std::size_t end, SplineKind kind) {
    const CachedSpline& entry = splineFor(first, end, kind);
    const SplineBlocks& blocks = entry.blocks;
    line(fmt::format(
        "; {} {} {}, deviation {:.2g} mm{}{}", blocks.points.size(),
        kind == SplineKind::BSpline ? "BSPLINE"
                                    : (kind == SplineKind::CSpline ? "CSPLINE" : "ASPLINE"),
        kind == SplineKind::BSpline ? "control points" : "knots", blocks.deviation,
        blocks.exact ? ", the NURBS as it is" : "", blocks.note.empty() ? "" : ", " + blocks.note));
    double lapFeed = path_.events[first].feed;
    std::string feedText = number(lapFeed);
    if (feedText != feed_) {
      line("F" + feedText);
      feed_ = feedText;
    }
    if (options_.subprograms) {
      line(entry.subprogram);
    } else {
      splineBlocks(blocks, [this](std::string text) { line(std::move(text)); });
    }
    // The spline ends where the curve does, at the lap's height.
    const MachineEvent& last = path_.events[end - 1];
    exact_ = Eigen::Vector3d(last.x, last.y, last.z);
    previous_ = std::nullopt;
    position_ = sinumerik::roundPoint({last.x, last.y, last.z}, options_.decimals);
    x_ = number(blocks.points.back().x());
    y_ = number(blocks.points.back().y());
    motion_ = "spline";
    lastWasFeed_ = false;
  }

  template <typename Emit> void splineBlocks(const SplineBlocks& blocks, Emit emit) const {
    for (std::size_t i = 0; i < blocks.points.size(); ++i) {
      std::string words =
          fmt::format("X{} Y{}", number(blocks.points[i].x()), number(blocks.points[i].y()));
      if (blocks.kind == SplineKind::BSpline) {
        words += fmt::format(" PW={} PL={}", formatSinumerikNumber(blocks.weights[i], 4),
                             formatSinumerikNumber(blocks.intervals[i], options_.decimals + 3));
        if (i == 0) {
          words = fmt::format("BSPLINE SD={} {}", blocks.degree, words);
        }
      } else if (i == 0) {
        emit(fmt::format("{} {}", startWord(blocks.start), endWord(blocks.end)));
        words = (blocks.kind == SplineKind::CSpline ? "CSPLINE " : "ASPLINE ") + words;
      }
      emit(words);
    }
  }

  void writeSubprograms() {
    for (const auto& [cut, index] : subprogramOrder_) {
      const CachedSpline& entry = cache_[cut][index];
      cut_ = cut;
      line(fmt::format("%_N_{}_SPF", entry.subprogram));
      line(";$PATH=/_N_SPF_DIR");
      line(fmt::format("; cut {}: the spline of every pass, at the height the caller is at",
                       cut + 1));
      splineBlocks(entry.blocks, [this](std::string text) { line(std::move(text)); });
      line("M17");
    }
  }

  const ir::ToolPath& path_;
  std::span<const SinumerikCut> cuts_;
  const SinumerikOptions& options_;
  std::string name_;
  SinumerikProgram program_;
  std::vector<std::string> lines_;
  std::vector<std::optional<std::size_t>> cutOfPrintedLine_;
  std::vector<frontend::SourceSpan> spanOfPrintedLine_;
  frontend::SourceSpan span_; // of the event being written
  std::optional<std::size_t> cut_;
  std::optional<Eigen::Vector3d> position_, previous_;
  std::optional<Eigen::Vector3d> exact_; // the tool path's position, unrounded
  bool lastWasFeed_ = false;
  bool spindleOn_ = false;
  bool pathModeWritten_ = false;
  std::string motion_, x_, y_, z_, feed_;
  std::map<std::size_t, std::vector<CachedSpline>> cache_;
  std::vector<std::pair<std::size_t, std::size_t>> subprogramOrder_;
};

} // namespace

ir::LoweringOptions sinumerikLoweringOptions(const SinumerikOptions& options) {
  ir::LoweringOptions lowering;
  lowering.splineInterpolation = true;
  lowering.coordinateIncrement = std::pow(10.0, -options.decimals);
  return lowering;
}

SinumerikProgram writeSinumerik(const ir::ToolPath& path, std::span<const SinumerikCut> cuts,
                                const SinumerikOptions& options) {
  return ProgramWriter(path, cuts, options).write();
}

} // namespace cncc::backends
