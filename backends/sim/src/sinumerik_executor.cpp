#include "cncc/backends/sinumerik_controller.h"

#include "sinumerik_arc.h"
#include "sinumerik_blocks.h"
#include "sinumerik_compensation.h"
#include "sinumerik_expression.h"
#include "sinumerik_program_state.h"
#include "sinumerik_sampling.h"

#include "cncc/geom/discretisation.h"
#include "cncc/geom/geometry_error.h"
#include "cncc/geom/knot_vector.h"
#include "cncc/ir/tool_path.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <map>

namespace cncc::backends::sinumerik {

namespace {

constexpr double kNoDirection = 1e-9;

using Vector = Eigen::Vector3d;

enum class Motion { Rapid, Linear, ClockwiseArc, CounterClockwiseArc, BSpline, CSpline, ASpline };

// The points of a spline group, gathered until the motion changes.
struct PendingSpline {
  Motion motion = Motion::BSpline;
  Vector start = Vector::Zero();
  std::optional<Vector> startDirection;
  geom::SplineEndCondition startCondition = geom::SplineEndCondition::Tangent;
  geom::SplineEndCondition endCondition = geom::SplineEndCondition::Tangent;
  int degree = 3;
  std::vector<Vector> points;
  std::vector<double> weights;
  std::vector<double> intervals;
  std::vector<int> lines, mainLines;
  double feed = 0;
};

MotionKind kindOf(Motion motion) {
  switch (motion) {
  case Motion::Rapid:
    return MotionKind::Rapid;
  case Motion::Linear:
  case Motion::ClockwiseArc: // recorded as its chords
  case Motion::CounterClockwiseArc:
    return MotionKind::Linear;
  case Motion::BSpline:
    return MotionKind::BSpline;
  case Motion::CSpline:
    return MotionKind::CSpline;
  case Motion::ASpline:
    return MotionKind::ASpline;
  }
  return MotionKind::Linear;
}

bool isSpline(Motion motion) {
  return motion == Motion::BSpline || motion == Motion::CSpline || motion == Motion::ASpline;
}

class Controller {
public:
  Controller(std::vector<SinumerikProgramUnit> units, const SinumerikRunOptions& options,
             SinumerikRun& run)
      : units_(std::move(units)), options_(options), run_(run) {}

  void execute() {
    runUnit(0, 0);
    finishSpline(std::nullopt);
  }

private:
  // Runs program `index`; `callLine` is the main-program line calling it.
  void runUnit(std::size_t index, int callLine) {
    const SinumerikProgramUnit& unit = units_[index];
    if (++depth_ > 8) {
      throw ProgramError(unit.name, unit.blocks.empty() ? 1 : unit.blocks.front().line,
                         "subprograms nest deeper than this model allows (8)");
    }
    std::size_t at = 0;
    while (at < unit.blocks.size()) {
      const SinumerikBlock& block = unit.blocks[at];
      if (++run_.blocksExecuted > options_.stepLimit) {
        throw ProgramError(unit.name, block.line, "the step limit was reached");
      }
      program_ = unit.name;
      line_ = block.line;
      mainLine_ = index == 0 ? block.line : callLine;
      if (block.control != Control::None) {
        at = withState([&] { return state_.next(unit, at); });
        continue;
      }
      if (!executeBlock(block)) {
        --depth_;
        return;
      }
      ++at;
    }
    if (index == 0) {
      fail("the main program ends without M30");
    }
    fail("the subprogram ends without M17 or RET");
  }

  [[noreturn]] void fail(const std::string& message) const {
    throw ProgramError(program_, line_, message);
  }

  // A problem ProgramState found, at the current line.
  template <typename Action> auto withState(Action action) const -> decltype(action()) {
    try {
      return action();
    } catch (const ExpressionError& error) {
      fail(error.what());
    }
  }

  std::optional<std::size_t> findUnit(const std::string& name) const {
    for (std::size_t i = 1; i < units_.size(); ++i) {
      if (units_[i].subprogram && units_[i].name == name) {
        return i;
      }
    }
    return std::nullopt;
  }

  // False when the block ends the program.
  bool executeBlock(const SinumerikBlock& block) {
    std::array<std::optional<double>, 3> axes;
    ArcWords arcWords; // I J, CR=, TURN=
    std::optional<double> weight, interval;
    bool motionWord = false;
    bool ends = false;
    bool machineCoordinates = false; // SUPA: this block's axes are the machine's
    for (const SinumerikWord& word : block.words) {
      const std::string& a = word.address;
      if (a == "R" && word.parameter >= 0) {
        withState([&] { state_.setParameter(word.parameter, state_.valueOf(word)); });
      } else if (a == "X" || a == "Y" || a == "Z") {
        axes[std::size_t(a[0] - 'X')] = needNumber(word);
      } else if (a == "I" || a == "J") {
        arcWords.centre[std::size_t(a[0] - 'I')] = needNumber(word);
      } else if (a == "CR") {
        arcWords.radius = needNumber(word);
      } else if (a == "TURN") {
        double turns = needNumber(word);
        if (turns != std::floor(turns)) {
          fail(fmt::format("TURN={:g}: the turns are a whole number", turns));
        }
        arcWords.turns = turns;
      } else if (a == "G") {
        motionWord |= gCode(needNumber(word));
      } else if (a == "M") {
        ends |= mCode(needNumber(word));
      } else if (a == "F") {
        feed_ = needNumber(word);
      } else if (a == "S" || a == "N") {
        needNumber(word);
      } else if (a == "D") {
        toolEdge(word);
      } else if (a == "SUPA") {
        machineCoordinates = true;
      } else if (a == "CYCLE832") {
        highSpeedCycle(word);
      } else if (a == "T") {
        selectTool(word);
      } else if (a == "PW") {
        weight = needNumber(word);
        if (!(*weight >= 0 && *weight <= 3)) {
          fail(fmt::format("PW={:g} is outside 0..3", *weight));
        }
      } else if (a == "PL") {
        interval = needNumber(word);
        if (!(*interval >= 0)) {
          fail(fmt::format("PL={:g} is negative", *interval));
        }
      } else if (a == "SD") {
        double degree = needNumber(word);
        if (degree != 2 && degree != 3) {
          fail(fmt::format("SD={:g}: the degree is 2 or 3", degree));
        }
        degree_ = int(degree);
      } else if (a == "BSPLINE" || a == "CSPLINE" || a == "ASPLINE") {
        setMotion(a == "BSPLINE" ? Motion::BSpline
                                 : (a == "CSPLINE" ? Motion::CSpline : Motion::ASpline));
        motionWord = true;
      } else if (a == "BAUTO" || a == "BNAT" || a == "BTAN") {
        startCondition_ = a == "BAUTO" ? geom::SplineEndCondition::Auto
                                       : (a == "BNAT" ? geom::SplineEndCondition::Natural
                                                      : geom::SplineEndCondition::Tangent);
      } else if (a == "EAUTO" || a == "ENAT" || a == "ETAN") {
        endCondition_ = a == "EAUTO" ? geom::SplineEndCondition::Auto
                                     : (a == "ENAT" ? geom::SplineEndCondition::Natural
                                                    : geom::SplineEndCondition::Tangent);
      } else if (a == "SPLINEPATH") {
        splinePath(word);
      } else if (a == "SOFT" || a == "BRISK") {
      } else if (a == "M17" || a == "RET") {
        ends = true;
      } else if (std::optional<std::size_t> unit = findUnit(a)) {
        finishSpline(std::nullopt);
        runUnit(*unit, mainLine_);
      } else {
        fail(fmt::format("'{}' is not known to this model", a));
      }
    }
    bool hasAxis = axes[0] || axes[1] || axes[2];
    if ((weight || interval) && (motion_ != Motion::BSpline || !hasAxis)) {
      fail("PW and PL belong in a BSPLINE block with a point");
    }
    bool arc = motion_ == Motion::ClockwiseArc || motion_ == Motion::CounterClockwiseArc;
    if ((arcWords.centre[0] || arcWords.centre[1] || arcWords.radius || arcWords.turns) && !arc) {
      fail("I, J, CR= and TURN= belong in a G2 or G3 block");
    }
    if (machineCoordinates) {
      // `SUPA G0 Z0`: the machine's own position, off the work coordinates
      // (the program's end); the part's path ends there.
      if (motion_ != Motion::Rapid || axes[0] || axes[1]) {
        fail("SUPA is modelled for a G0 in Z only (the retract at the end)");
      }
    } else if (arc && hasAxis) {
      arcTo(axes, arcWords);
    } else if (hasAxis) {
      moveTo(axes, weight, interval);
    } else if (motionWord && !isSpline(motion_)) {
      finishSpline(std::nullopt);
    }
    return !ends;
  }

  double needNumber(const SinumerikWord& word) const {
    return withState([&] { return state_.valueOf(word); });
  }

  // True for a motion code.
  bool gCode(double value) {
    if (!(value >= 0 && value <= 1000) || double(int(value)) != value) {
      fail(fmt::format("G{:g} is not known to this model", value));
    }
    int code = int(value);
    if (double(code) != value) {
      fail(fmt::format("G{:g} is not known to this model", value));
    }
    switch (code) {
    case 0:
      setMotion(Motion::Rapid);
      return true;
    case 1:
      setMotion(Motion::Linear);
      return true;
    case 2:
    case 3:
      setMotion(code == 2 ? Motion::ClockwiseArc : Motion::CounterClockwiseArc);
      return true;
    case 40:
      compensation_.cancel();
      return false;
    case 41:
    case 42:
      selectCompensation(code == 41);
      return false;
    case 451:
      fail("G451 (outside corners to the offsets' intersection) is not modelled; G450 is");
    case 450:
    case 17:
    case 90:
    case 54:
    case 55:
    case 56:
    case 57:
    case 64:
      return false;
    case 70:
    case 71:
      run_.inches = code == 70;
      return false;
    default:
      fail(fmt::format("G{} is not known to this model", code));
    }
  }

  // True when the program ends.
  bool mCode(double value) {
    if (!(value >= 0 && value <= 1000) || double(int(value)) != value) {
      fail(fmt::format("M{:g} is not known to this model", value));
    }
    int code = int(value);
    switch (code) {
    case 0: // program stop and optional stop: the path goes on
    case 1:
    case 3:
    case 5:
    case 6:
    case 7:
    case 8:
    case 9:
      return false;
    case 30:
      if (depth_ != 1) {
        fail("M30 inside a subprogram");
      }
      withCompensation([&] { compensation_.finish(line_); });
      return true;
    case 17:
      if (depth_ == 1) {
        fail("M17 in the main program");
      }
      return true;
    default:
      fail(fmt::format("M{:g} is not known to this model", value));
    }
  }

  // D1 .. D32000: the cutting edge whose offsets are active (D0: none).
  void toolEdge(const SinumerikWord& word) {
    double edge = needNumber(word);
    if (!(edge >= 0 && edge <= 32000) || edge != std::floor(edge)) {
      fail(fmt::format("D{:g}: a cutting edge is a whole number 0 .. 32000", edge));
    }
    if (compensation_.engaged()) {
      fail("changing the cutting edge with G41/G42 on is not modelled");
    }
    edge_ = int(edge);
  }

  // T="T5", T5 or T=5: the tool whose edges the D words select; a tool
  // change activates its first edge (the default $MC_CUTTING_EDGE_DEFAULT).
  void selectTool(const SinumerikWord& word) {
    if (word.text.empty() && !word.value) {
      fail("T needs a tool name or number");
    }
    if (compensation_.engaged()) {
      fail("a tool change with G41/G42 on");
    }
    tool_.reset();
    if (word.value) {
      tool_ = *word.value;
    } else {
      std::size_t digits = word.text.find_last_not_of("0123456789");
      digits = digits == std::string::npos ? 0 : digits + 1;
      if (digits < word.text.size()) {
        tool_ = std::stod(word.text.substr(digits));
      }
    }
    toolName_ = word.text.empty() ? fmt::format("{:g}", *word.value) : word.text;
    edge_ = 1;
  }

  // G41/G42 with the radius of the active tool's active edge.
  void selectCompensation(bool left) {
    if (toolName_.empty() || edge_ == 0) {
      fail(fmt::format("G{} without an active cutting edge (T and D)", left ? 41 : 42));
    }
    auto radius = tool_ ? options_.toolRadii.find(int(*tool_)) : options_.toolRadii.end();
    if (radius == options_.toolRadii.end()) {
      fail(fmt::format("G{}: the model is given no radius for tool {}'s cutting edges",
                       left ? 41 : 42, toolName_));
    }
    withCompensation([&] { compensation_.select(left, radius->second, line_); });
  }

  // A CompensationError as the line's ProgramError.
  template <typename Action> void withCompensation(Action action) const {
    try {
      action();
    } catch (const CompensationError& error) {
      throw ProgramError(program_, error.line(), error.what());
    }
  }

  // A programmed line or arc in the plane, while compensation is engaged.
  void compensate(const Vector& start, const Vector& end, const sim::PlaneElement& element,
                  bool rapid) {
    if (end.z() != start.z()) {
      fail("a move in Z with G41/G42 on is not modelled");
    }
    if (!element.arc && end.x() == start.x() && end.y() == start.y()) {
      fail("a block without X or Y motion with G41/G42 on is not modelled");
    }
    PlaneMove move;
    move.element = element;
    move.z = end.z();
    move.feed = feed_.value_or(0.0);
    move.rapid = rapid;
    move.line = line_;
    move.mainLine = mainLine_;
    withCompensation([&] { compensation_.add(move); });
  }

  // A move of the tool's centre that compensation worked out.
  void recordCompensated(const PlaneMove& move) {
    const sim::PlaneElement& element = move.element;
    Vector end(element.end.x, element.end.y, move.z);
    if (!element.arc) {
      run_.moves.push_back({move.rapid ? MotionKind::Rapid : MotionKind::Linear, end, move.feed,
                            move.line, move.mainLine});
      return;
    }
    ProgrammedArc arc;
    arc.start = {element.start.x, element.start.y, move.z};
    arc.end = end;
    arc.centre = {element.centre.x - element.start.x, element.centre.y - element.start.y};
    arc.clockwise = element.clockwise;
    std::string problem;
    std::vector<Vector> points =
        arcChordPoints(arc, options_.sampleTolerance, pointsLeft(), problem);
    if (!problem.empty()) {
      throw ProgramError(program_, move.line, problem);
    }
    for (const Vector& point : points) {
      run_.moves.push_back({MotionKind::Linear, point, move.feed, move.line, move.mainLine});
    }
  }

  // CYCLE832(tolerance, _FINISH|_SEMIFIN|_ROUGH, n) switches high-speed
  // settings on, CYCLE832() off; the path is the same.
  void highSpeedCycle(const SinumerikWord& word) const {
    if (word.text.empty()) {
      return;
    }
    std::string text = word.text;
    std::erase(text, ' ');
    std::size_t first = text.find(',');
    std::size_t second = first == std::string::npos ? first : text.find(',', first + 1);
    std::string mode =
        second == std::string::npos ? "" : text.substr(first + 1, second - first - 1);
    double tolerance = 0;
    bool number =
        first != std::string::npos &&
        std::from_chars(text.data(), text.data() + first, tolerance).ptr == text.data() + first;
    if (!number || !(tolerance > 0) ||
        (mode != "_FINISH" && mode != "_SEMIFIN" && mode != "_ROUGH")) {
      fail(
          fmt::format("CYCLE832({}): expected (tolerance, _FINISH|_SEMIFIN|_ROUGH, n)", word.text));
    }
  }

  void splinePath(const SinumerikWord& word) {
    if (word.text != "1,X,Y" && word.text != "1,X,Y,Z") {
      fail(fmt::format("SPLINEPATH({}) is not modelled (1,X,Y or 1,X,Y,Z)", word.text));
    }
    splineZ_ = word.text == "1,X,Y,Z";
  }

  void setMotion(Motion motion) {
    if (motion != motion_) {
      motionChanged_ = true;
    }
    motion_ = motion;
  }

  void moveTo(const std::array<std::optional<double>, 3>& axes, std::optional<double> weight,
              std::optional<double> interval) {
    Vector target;
    for (std::size_t k = 0; k < 3; ++k) {
      std::optional<double> value = axes[k] ? axes[k] : position_[k];
      if (!value) {
        if (motion_ != Motion::Rapid) {
          fail(fmt::format("{} is not known yet: the first feed move needs every axis",
                           char('X' + k)));
        }
        value = std::nullopt;
      }
      target[Eigen::Index(k)] = value ? *value : 0.0;
    }
    if (isSpline(motion_)) {
      if (axes[2] && !splineZ_) {
        fail("Z in a spline block, but the spline axes are X and Y (SPLINEPATH)");
      }
      if (compensation_.engaged()) {
        fail("spline blocks with G41/G42 on are not modelled");
      }
      splinePoint(target, weight, interval);
      return;
    }
    finishSpline(target);
    if (motion_ == Motion::Linear && !feed_) {
      fail("a G1 move without a feed rate");
    }
    if (compensation_.engaged()) {
      if (!known()) {
        fail("G41/G42 before every axis is known");
      }
      sim::PlaneElement line;
      line.start = {current().x(), current().y()};
      line.end = {target.x(), target.y()};
      compensate(current(), target, line, motion_ == Motion::Rapid);
    } else {
      record(motion_ == Motion::Rapid ? MotionKind::Rapid : MotionKind::Linear, target, axes);
    }
    previous_ = known() ? std::optional<Vector>(current()) : std::nullopt;
    for (std::size_t k = 0; k < 3; ++k) {
      if (axes[k]) {
        position_[k] = axes[k];
      }
    }
    lastLinear_ = motion_ == Motion::Linear;
  }

  // The arc words of a block: the centre or radius, extra full turns.
  struct ArcWords {
    std::array<std::optional<double>, 2> centre; // I J, from the start
    std::optional<double> radius;                // CR=
    double turns = 0;                            // TURN=
  };

  // G2/G3 in the XY plane (sinumerik_arc.h), recorded as chords within the
  // sampling tolerance.
  void arcTo(const std::array<std::optional<double>, 3>& axes, const ArcWords& words) {
    if (!known()) {
      fail("an arc before every axis is known");
    }
    if (!feed_) {
      fail("an arc without a feed rate");
    }
    finishSpline(std::nullopt);
    Vector start = current();
    ProgrammedArc arc;
    arc.start = start;
    arc.end = {axes[0].value_or(start.x()), axes[1].value_or(start.y()),
               axes[2].value_or(start.z())};
    arc.centre = words.centre;
    arc.radius = words.radius;
    arc.turns = int(std::min(words.turns, 1e6));
    arc.clockwise = motion_ == Motion::ClockwiseArc;
    if (compensation_.engaged()) {
      compensateArc(arc);
      return;
    }
    std::string problem;
    std::vector<Vector> points =
        arcChordPoints(arc, options_.sampleTolerance, pointsLeft(), problem);
    if (!problem.empty()) {
      fail(problem);
    }
    for (const Vector& point : points) {
      run_.moves.push_back({MotionKind::Linear, point, *feed_, line_, mainLine_});
    }
    previous_ = start;
    position_ = {arc.end.x(), arc.end.y(), arc.end.z()};
    lastLinear_ = false;
  }

  // An arc given by I J, without turns, in the plane of compensation.
  void compensateArc(const ProgrammedArc& arc) {
    if (!arc.centre[0] && !arc.centre[1]) {
      fail("a CR= arc with G41/G42 on is not modelled: give I and J");
    }
    if (arc.turns != 0) {
      fail("TURN= with G41/G42 on is not modelled");
    }
    sim::PlaneElement element;
    element.arc = true;
    element.clockwise = arc.clockwise;
    element.start = {arc.start.x(), arc.start.y()};
    element.end = {arc.end.x(), arc.end.y()};
    element.centre = {arc.start.x() + arc.centre[0].value_or(0.0),
                      arc.start.y() + arc.centre[1].value_or(0.0)};
    compensate(arc.start, arc.end, element, false);
    previous_ = arc.start;
    position_ = {arc.end.x(), arc.end.y(), arc.end.z()};
    lastLinear_ = false;
  }

  // How many more points the sampled path may take.
  std::size_t pointsLeft() const {
    return run_.moves.size() < options_.pointLimit ? options_.pointLimit - run_.moves.size() : 0;
  }

  bool known() const { return position_[0] && position_[1] && position_[2]; }
  Vector current() const { return {*position_[0], *position_[1], *position_[2]}; }

  void record(MotionKind kind, const Vector& target,
              const std::array<std::optional<double>, 3>& axes) {
    bool wasKnown = known();
    bool becomesKnown =
        (position_[0] || axes[0]) && (position_[1] || axes[1]) && (position_[2] || axes[2]);
    if (!wasKnown) {
      if (becomesKnown) {
        run_.start = target;
        startKnown_ = true;
      }
      return;
    }
    run_.moves.push_back({kind, target, feed_.value_or(0.0), line_, mainLine_});
  }

  void splinePoint(const Vector& target, std::optional<double> weight,
                   std::optional<double> interval) {
    if (!known()) {
      fail("a spline needs a known start: move to it first");
    }
    if (!pending_ || motionChanged_) {
      finishSpline(std::nullopt);
      pending_ = PendingSpline{};
      pending_->motion = motion_;
      pending_->start = current();
      pending_->degree = degree_;
      pending_->startCondition = startCondition_;
      pending_->endCondition = endCondition_;
      if (lastLinear_ && previous_) {
        Vector direction = current() - *previous_;
        if (!splineZ_) {
          direction.z() = 0;
        }
        if (direction.norm() > kNoDirection) {
          pending_->startDirection = direction;
        }
      }
      if (!feed_) {
        fail("a spline without a feed rate");
      }
      pending_->feed = *feed_;
      motionChanged_ = false;
    }
    std::size_t index = pending_->points.size();
    pending_->points.push_back(target);
    pending_->weights.push_back(weight.value_or(1.0));
    pending_->intervals.push_back(interval.value_or(int(index) + 1 < pending_->degree ? 0.0 : 1.0));
    pending_->lines.push_back(line_);
    pending_->mainLines.push_back(mainLine_);
    for (std::size_t k = 0; k < 3; ++k) {
      position_[k] = target[Eigen::Index(k)];
    }
    lastLinear_ = false;
  }

  // Builds and cuts the pending spline; `next` is where the block after it
  // goes (for ETAN).
  void finishSpline(std::optional<Vector> next) {
    if (!pending_) {
      return;
    }
    PendingSpline spline = std::move(*pending_);
    pending_.reset();
    int savedLine = line_;
    line_ = spline.lines.front();
    std::shared_ptr<const geom::Curve> curve;
    try {
      curve = build(spline, next);
    } catch (const geom::GeometryError& error) {
      fail(fmt::format("this spline cannot be built: {}", error.what()));
    }
    line_ = savedLine;
    run_.splines.push_back(
        {kindOf(spline.motion), curve, spline.points.size(), spline.mainLines.front()});
    geom::CurveSamples samples = sampleDensely(*curve, options_.sampleTolerance);
    if (samples.points.size() > pointsLeft()) {
      fail(fmt::format("this spline's path has more than the {} points the model samples in all",
                       options_.pointLimit));
    }
    // Each sample belongs to the block whose point ends the piece it is on.
    std::vector<double> ends = pieceEnds(spline, *curve);
    std::size_t piece = 0;
    for (std::size_t i = 1; i < samples.points.size(); ++i) {
      while (piece + 1 < ends.size() && samples.parameters[i] > ends[piece] + 1e-12) {
        ++piece;
      }
      run_.moves.push_back({kindOf(spline.motion), samples.points[i], spline.feed,
                            spline.lines[piece], spline.mainLines[piece]});
    }
  }

  // The parameter at which each programmed block's share of the curve ends.
  static std::vector<double> pieceEnds(const PendingSpline& spline, const geom::Curve& curve) {
    std::vector<double> ends;
    std::vector<double> breakpoints = curve.breakpoints();
    if (spline.motion == Motion::BSpline) {
      // A B spline has fewer spans than blocks: spread the blocks over its
      // parameter in proportion.
      geom::ParameterRange domain = curve.domain();
      for (std::size_t i = 1; i <= spline.points.size(); ++i) {
        ends.push_back(domain.t0 + domain.length() * double(i) / double(spline.points.size()));
      }
      return ends;
    }
    ends.assign(breakpoints.begin() + 1, breakpoints.end());
    return ends;
  }

  std::shared_ptr<const geom::Curve> build(const PendingSpline& spline,
                                           const std::optional<Vector>& next) const {
    if (spline.motion == Motion::BSpline) {
      return std::make_shared<geom::NurbsCurve>(bsplineOfBlocks(
          spline.start, spline.degree, spline.points, spline.weights, spline.intervals));
    }
    std::vector<Vector> points{spline.start};
    points.insert(points.end(), spline.points.begin(), spline.points.end());
    geom::SplineTransitions transitions;
    transitions.start = spline.startCondition;
    transitions.end = spline.endCondition;
    transitions.startDirection = spline.startDirection;
    if (next) {
      Vector direction = *next - points.back();
      if (!splineZ_) {
        direction.z() = 0;
      }
      if (direction.norm() > kNoDirection) {
        transitions.endDirection = direction;
      }
    }
    if (spline.motion == Motion::CSpline) {
      geom::CSplineOptions options;
      options.windowBlocks = options_.cubicSplineWindow;
      return std::make_shared<geom::PiecewisePolynomialCurve>(
          geom::cSpline(points, transitions, options));
    }
    return std::make_shared<geom::PiecewisePolynomialCurve>(geom::aSpline(points, transitions));
  }

  std::vector<SinumerikProgramUnit> units_;
  const SinumerikRunOptions& options_;
  SinumerikRun& run_;
  ProgramState state_; // R parameters and loops
  std::string program_;
  int line_ = 0;
  int mainLine_ = 0;
  int depth_ = 0;
  Motion motion_ = Motion::Rapid;
  bool motionChanged_ = false;
  std::array<std::optional<double>, 3> position_;
  std::optional<Vector> previous_;
  bool lastLinear_ = false;
  bool startKnown_ = false;
  std::optional<double> feed_;
  int degree_ = 3;
  bool splineZ_ = true;
  geom::SplineEndCondition startCondition_ = geom::SplineEndCondition::Tangent;
  geom::SplineEndCondition endCondition_ = geom::SplineEndCondition::Tangent;
  std::optional<PendingSpline> pending_;
  std::optional<double> tool_; // its number, when it has one
  std::string toolName_;       // as the T word gives it
  int edge_ = 0;               // D: the active cutting edge
  CutterCompensation compensation_{[this](const PlaneMove& move) { recordCompensated(move); }};
};

} // namespace

SinumerikRun runSinumerikProgram(std::string_view text, const SinumerikRunOptions& options) {
  SinumerikRun run;
  try {
    Controller(readSinumerikText(text), options, run).execute();
  } catch (const ProgramError& error) {
    run.error = error;
  }
  return run;
}

ExecutedPath executedPathOf(const SinumerikRun& run,
                            std::span<const std::optional<std::size_t>> cutOfLine) {
  ExecutedPath path;
  path.start = run.start;
  for (const ExecutedSinumerikMove& move : run.moves) {
    ExecutedMove executed;
    executed.rapid = move.kind == MotionKind::Rapid;
    executed.end = move.end;
    executed.feed = move.feed;
    std::size_t index = std::size_t(move.mainLine) - 1;
    if (move.mainLine >= 1 && index < cutOfLine.size()) {
      executed.cut = cutOfLine[index];
    }
    path.moves.push_back(executed);
  }
  return path;
}

} // namespace cncc::backends::sinumerik
