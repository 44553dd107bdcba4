// Runs a read TNC program: Q arithmetic, jumps, subprogram calls and
// repeats, and the motion blocks, counting the operations of loop blocks.
// Radius compensation RL/RR runs the blocks through the virtual Fanuc's
// compensation (sim_compensation.h) with the TNC's transition arcs.
#include "sim_compensation.h"
#include "tnc_program_text.h"

#include "cncc/ir/interpreter.h"
#include "cncc/ir/polynomial_move.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>

namespace cncc::backends::heidenhain {

namespace {

constexpr double radiansPerDegree = 3.14159265358979323846 / 180;

struct Position {
  std::array<std::optional<double>, 3> axes;
  bool known() const { return axes[0] && axes[1] && axes[2]; }
};

class TncExecutor {
public:
  TncExecutor(std::vector<TncBlock> blocks, const TncRunOptions& options, TncRun& run)
      : blocks_(std::move(blocks)), options_(options), run_(run),
        compensation_(compensated_, {"RL/RR", "R0", true}) {}

  void execute() {
    if (blocks_.empty() || blocks_.front().kind != TncBlock::Kind::Begin) {
      throw TncProgramError(blocks_.empty() ? 1 : blocks_.front().line,
                            "a program starts with BEGIN PGM");
    }
    if (blocks_.back().kind != TncBlock::Kind::End) {
      throw TncProgramError(blocks_.back().line, "a program ends with END PGM");
    }
    run_.inches = blocks_.front().inches;
    indexLabels();
    markLoops();
    std::size_t next = 0;
    while (next < blocks_.size()) {
      if (++run_.blocksExecuted > options_.stepLimit) {
        throw TncProgramError(
            blocks_[next].line,
            fmt::format("the program runs more than {} blocks", options_.stepLimit));
      }
      std::optional<std::size_t> jump = step(next);
      if (blocks_[next].kind == TncBlock::Kind::End) {
        compensation_.finish(simBlock(blocks_[next]));
        return;
      }
      next = jump ? *jump : next + 1;
    }
  }

private:
  [[noreturn]] void fail(const TncBlock& block, const std::string& message) const {
    throw TncProgramError(block.line, message);
  }

  void indexLabels() {
    for (std::size_t i = 0; i < blocks_.size(); ++i) {
      const TncBlock& block = blocks_[i];
      if (block.kind == TncBlock::Kind::Label && block.label != 0) {
        if (block.label > options_.profile.maximumLabel) {
          fail(block, fmt::format("LBL {} is beyond the control's LBL {}", block.label,
                                  options_.profile.maximumLabel));
        }
        if (!labels_.emplace(block.label, i).second) {
          fail(block, fmt::format("LBL {} is defined twice", block.label));
        }
      }
      for (int parameter : block.parametersNamed) {
        named_.insert(parameter);
      }
    }
    run_.parametersNamed = named_.size();
  }

  std::size_t labelIndex(const TncBlock& block) const {
    auto found = labels_.find(block.label);
    if (found == labels_.end()) {
      fail(block, fmt::format("there is no LBL {}", block.label));
    }
    return found->second;
  }

  // A block between a label and a later block that jumps back to it runs
  // in a loop.
  void markLoops() {
    inLoop_.assign(blocks_.size(), false);
    for (std::size_t i = 0; i < blocks_.size(); ++i) {
      const TncBlock& block = blocks_[i];
      bool jumps = block.kind == TncBlock::Kind::Jump ||
                   (block.kind == TncBlock::Kind::CallLabel && block.repeat);
      auto found = labels_.find(block.label);
      if (jumps && found != labels_.end() && found->second < i) {
        std::fill(inLoop_.begin() + static_cast<std::ptrdiff_t>(found->second),
                  inLoop_.begin() + static_cast<std::ptrdiff_t>(i) + 1, true);
      }
    }
  }

  // ---- values ---------------------------------------------------------------

  double parameter(const TncBlock& block, int encoded) const {
    auto found = parameters_.find(encoded);
    if (found == parameters_.end()) {
      fail(block, fmt::format("{} is read before any block sets it", tncParameterName(encoded)));
    }
    return found->second;
  }

  // One operation of the block being executed, when it runs in a loop.
  void count(std::size_t sim::OperationCounts::*kind) {
    if (countingBlock_ && inLoop_[*countingBlock_]) {
      ++(run_.loopOperations.operations.*kind);
    }
  }

  double checked(const TncBlock& block, double value, std::string_view what) const {
    if (!std::isfinite(value)) {
      fail(block, fmt::format("{} has no finite value", what));
    }
    return value;
  }

  double function(const TncBlock& block, const std::string& name, double x) {
    count(&sim::OperationCounts::functions);
    auto domain = [&](bool holds) {
      if (!holds) {
        fail(block, fmt::format("{} of {} is not defined", name, x));
      }
    };
    if (name == "SIN")
      return std::sin(x * radiansPerDegree);
    if (name == "COS")
      return std::cos(x * radiansPerDegree);
    if (name == "TAN")
      return std::tan(x * radiansPerDegree);
    if (name == "ASIN" || name == "ACOS") {
      domain(x >= -1 && x <= 1);
      return (name == "ASIN" ? std::asin(x) : std::acos(x)) / radiansPerDegree;
    }
    if (name == "ATAN")
      return std::atan(x) / radiansPerDegree;
    if (name == "SQRT") {
      domain(x >= 0);
      return std::sqrt(x);
    }
    if (name == "SQ")
      return x * x;
    if (name == "LN" || name == "LOG") {
      domain(x > 0);
      return name == "LN" ? std::log(x) : std::log10(x);
    }
    if (name == "EXP")
      return std::exp(x);
    if (name == "NEG")
      return -x;
    if (name == "INT")
      return std::trunc(x);
    if (name == "ABS")
      return std::abs(x);
    if (name == "FRAC")
      return x - std::trunc(x);
    return x < 0 ? -1 : (x > 0 ? 1 : 0); // SGN
  }

  double evaluate(const TncBlock& block, const TncExpression& expression) {
    switch (expression.kind) {
    case TncExpression::Kind::Number:
      return expression.number;
    case TncExpression::Kind::Parameter:
      return parameter(block, expression.parameter);
    case TncExpression::Kind::Negation:
      count(&sim::OperationCounts::arithmetic);
      return -evaluate(block, expression.operands[0]);
    case TncExpression::Kind::Function:
      return function(block, expression.function, evaluate(block, expression.operands[0]));
    case TncExpression::Kind::Binary:
      break;
    }
    double a = evaluate(block, expression.operands[0]);
    double b = evaluate(block, expression.operands[1]);
    count(&sim::OperationCounts::arithmetic);
    if ((expression.op == '/' || expression.op == '%') && b == 0) {
      fail(block, "division by zero");
    }
    switch (expression.op) {
    case '+':
      return a + b;
    case '-':
      return a - b;
    case '*':
      return a * b;
    case '/':
      return a / b;
    case '%':
      return std::fmod(a, b);
    default:
      return checked(block, std::pow(a, b), "the power");
    }
  }

  // ---- blocks ---------------------------------------------------------------

  std::optional<std::size_t> step(std::size_t index) {
    const TncBlock& block = blocks_[index];
    countingBlock_ = index;
    switch (block.kind) {
    case TncBlock::Kind::Assign: {
      double value = evaluate(block, block.value);
      if (!std::isfinite(value) || std::abs(value) > options_.profile.maximumMagnitude) {
        fail(block,
             fmt::format("{} = {} is beyond the control's +-{:.0f}", tncParameterName(block.target),
                         value, options_.profile.maximumMagnitude));
      }
      count(&sim::OperationCounts::assignments);
      parameters_[block.target] = value;
      return std::nullopt;
    }
    case TncBlock::Kind::Jump:
      return jump(block);
    case TncBlock::Kind::CallLabel:
      return call(block, index);
    case TncBlock::Kind::Label:
      if (block.label == 0 && !returns_.empty()) {
        std::size_t back = returns_.back();
        returns_.pop_back();
        return back;
      }
      return std::nullopt;
    case TncBlock::Kind::Error:
      fail(block, fmt::format("FN 14: ERROR = {}", block.errorNumber));
    case TncBlock::Kind::Begin:
      if (index != 0) {
        fail(block, "BEGIN PGM inside the program");
      }
      return std::nullopt;
    case TncBlock::Kind::ToolCall:
      if (compensation_.isOn()) {
        fail(block, "TOOL CALL while radius compensation RL/RR is on: cancel it with R0 first");
      }
      if (block.tool) {
        tool_ = block.tool;
      }
      if (block.speed) {
        double speed = evaluate(block, *block.speed);
        if (speed < 0) {
          fail(block, "a negative spindle speed");
        }
      }
      return std::nullopt;
    case TncBlock::Kind::Line:
      line(block, index);
      return std::nullopt;
    case TncBlock::Kind::CircleCentre:
      circleCentre(block);
      return std::nullopt;
    case TncBlock::Kind::Circle:
      circle(block, index);
      return std::nullopt;
    case TncBlock::Kind::Spline:
      spline(block, index);
      return std::nullopt;
    default: // comments, BLK FORM, cycle 32, END PGM
      return std::nullopt;
    }
  }

  std::optional<std::size_t> jump(const TncBlock& block) {
    double a = evaluate(block, block.value);
    double b = evaluate(block, block.right);
    count(&sim::OperationCounts::comparisons);
    bool holds = block.comparison == 9    ? a == b
                 : block.comparison == 10 ? a != b
                 : block.comparison == 11 ? a > b
                                          : a < b;
    return holds ? std::optional<std::size_t>(labelIndex(block)) : std::nullopt;
  }

  // CALL LBL n REP k repeats the part from LBL n k times; CALL LBL n runs
  // LBL n up to LBL 0 and comes back.
  std::optional<std::size_t> call(const TncBlock& block, std::size_t index) {
    std::size_t target = labelIndex(block);
    if (block.repeat) {
      int& done = repeats_[index];
      if (done < *block.repeat) {
        ++done;
        return target;
      }
      done = 0;
      return std::nullopt;
    }
    if (static_cast<int>(returns_.size()) >= options_.profile.maximumCallNesting) {
      fail(block, fmt::format("subprogram calls nest deeper than {}",
                              options_.profile.maximumCallNesting));
    }
    returns_.push_back(index + 1);
    return target;
  }

  // The end point of a block's axis words (incremental from the position).
  Position target(const TncBlock& block) {
    Position end = position_;
    const std::optional<TncAxisWord>* words[3] = {&block.x, &block.y, &block.z};
    for (int axis = 0; axis < 3; ++axis) {
      if (!*words[axis]) {
        continue;
      }
      double value = evaluate(block, (*words[axis])->value);
      if ((*words[axis])->incremental) {
        if (!position_.axes[axis]) {
          fail(block, fmt::format("an incremental {} from an unknown position", "XYZ"[axis]));
        }
        value += *position_.axes[axis];
      }
      end.axes[axis] = value;
    }
    return end;
  }

  void machineFunctions(const TncBlock& block) {
    for (int m : block.mFunctions) {
      static constexpr std::array known = {2, 3, 4, 5, 7, 8, 9, 30, 91};
      if (std::find(known.begin(), known.end(), m) == known.end()) {
        fail(block, fmt::format("M{} is not modelled", m));
      }
    }
  }

  double feedOf(const TncBlock& block) {
    if (block.feed) {
      double feed = evaluate(block, *block.feed);
      if (feed <= 0) {
        fail(block, "a feed rate that is not positive");
      }
      feed_ = feed;
    }
    if (!feed_) {
      fail(block, "a feed move before any feed rate");
    }
    return *feed_;
  }

  // `further`: another move the same block interpolates (an SPL's), which
  // does not count as a feed block again.
  void record(ir::MachineEvent event, std::size_t index, bool further = false) {
    if (!started_) {
      if (!position_.known()) {
        return;
      }
      started_ = true;
      ir::MachineEvent start;
      start.x = *position_.axes[0];
      start.y = *position_.axes[1];
      start.z = *position_.axes[2];
      run_.path.events.push_back(start);
      if (event.kind == ir::MachineEvent::Kind::Rapid) {
        return; // the start is this move's end
      }
    }
    if (event.kind != ir::MachineEvent::Kind::Rapid && inLoop_[index] && !further) {
      ++run_.loopOperations.feedMoves;
    }
    run_.path.events.push_back(event);
  }

  void line(const TncBlock& block, std::size_t index) {
    machineFunctions(block);
    Position end = target(block);
    bool machineCoordinates =
        std::find(block.mFunctions.begin(), block.mFunctions.end(), 91) != block.mFunctions.end();
    if (machineCoordinates) {
      if (compensation_.isOn()) {
        fail(block, "M91 while radius compensation RL/RR is on: cancel it with R0 first");
      }
      ir::MachineEvent home;
      home.kind = ir::MachineEvent::Kind::Home;
      run_.path.events.push_back(home);
      return;
    }
    bool moves = block.x || block.y || block.z;
    bool rapid = block.rapid;
    double feed = moves && !rapid ? feedOf(block) : 0;
    if (!moves && block.feed) {
      feedOf(block);
    }
    setCompensation(block, end);
    if (compensation_.isOn()) {
      sim::ExecutedEvent event;
      event.kind = rapid ? sim::ExecutedEvent::Kind::Rapid : sim::ExecutedEvent::Kind::Feed;
      compensate(block, index, event, end, moves, feed);
      return;
    }
    position_ = end;
    if (!moves) {
      return;
    }
    ir::MachineEvent event;
    event.kind = rapid ? ir::MachineEvent::Kind::Rapid : ir::MachineEvent::Kind::Feed;
    event.feed = feed;
    if (position_.known()) {
      event.x = *position_.axes[0];
      event.y = *position_.axes[1];
      event.z = *position_.axes[2];
    }
    record(event, index);
  }

  void circleCentre(const TncBlock& block) {
    if (!block.x || !block.y || block.z) {
      fail(block, "CC takes X and Y (or IX and IY)");
    }
    Position centre = target(block);
    centre_ = {*centre.axes[0], *centre.axes[1]};
  }

  void circle(const TncBlock& block, std::size_t index) {
    machineFunctions(block);
    if (!block.clockwise) {
      fail(block, "C needs DR+ or DR-");
    }
    if (!centre_) {
      fail(block, "C before any CC");
    }
    if (!position_.known()) {
      fail(block, "C from an unknown position");
    }
    Position end = target(block);
    double startRadius =
        std::hypot(*position_.axes[0] - centre_->first, *position_.axes[1] - centre_->second);
    double endRadius = std::hypot(*end.axes[0] - centre_->first, *end.axes[1] - centre_->second);
    if (std::abs(startRadius - endRadius) >
        options_.arcRadiusTolerance * (run_.inches ? 1 / 25.4 : 1)) {
      fail(block, fmt::format("the end point is {:.6f} from the circle through the start",
                              std::abs(startRadius - endRadius)));
    }
    double feed = feedOf(block);
    setCompensation(block, end);
    if (compensation_.isOn()) {
      sim::ExecutedEvent event;
      event.kind = *block.clockwise ? sim::ExecutedEvent::Kind::ClockwiseArc
                                    : sim::ExecutedEvent::Kind::CounterclockwiseArc;
      event.centre = {centre_->first, centre_->second, *position_.axes[2]};
      compensate(block, index, event, end, true, feed);
      return;
    }
    position_ = end;
    ir::MachineEvent event;
    event.kind = ir::MachineEvent::Kind::Arc;
    event.x = *end.axes[0];
    event.y = *end.axes[1];
    event.z = *end.axes[2];
    event.centreX = centre_->first;
    event.centreY = centre_->second;
    event.clockwise = *block.clockwise;
    event.feed = feed;
    record(event, index);
  }

  // SPL: per axis K3 t^3 + K2 t^2 + K1 t + end, t from 1 to 0; an axis
  // with an end coordinate needs all three coefficients, one without stays.
  void spline(const TncBlock& block, std::size_t index) {
    machineFunctions(block);
    if (compensation_.isOn()) {
      fail(block, "SPL while radius compensation RL/RR is on is not modelled");
    }
    if (!position_.known()) {
      fail(block, "SPL from an unknown position");
    }
    Position end = target(block);
    const std::optional<TncAxisWord>* words[3] = {&block.x, &block.y, &block.z};
    std::array<double, 12> values{};
    for (int axis = 0; axis < 3; ++axis) {
      values[axis] = *end.axes[axis];
      for (int k = 0; k < 3; ++k) {
        const std::optional<double>& coefficient = block.splineCoefficients[axis][k];
        if (words[axis]->has_value() != coefficient.has_value()) {
          fail(block, fmt::format("SPL needs K3{0} K2{0} K1{0} with {0}, and no K{1}{0} without",
                                  "XYZ"[axis], 3 - k));
        }
        values[3 + 3 * axis + k] = coefficient.value_or(0);
      }
    }
    double feed = feedOf(block);
    std::array<double, 3> start{*position_.axes[0], *position_.axes[1], *position_.axes[2]};
    std::vector<ir::MachineEvent> events;
    try {
      ir::polynomialMove(start, ir::polynomialMoveOf(values), feed, events);
    } catch (const ir::InterpreterError& error) {
      fail(block, error.what());
    }
    position_ = end;
    for (std::size_t i = 0; i < events.size(); ++i) {
      record(events[i], index, i > 0);
    }
  }

  // ---- radius compensation ----------------------------------------------------

  static sim::Block simBlock(const TncBlock& block) {
    sim::Block words;
    words.kind = sim::Block::Kind::Words;
    words.line = block.line;
    words.text = block.text;
    return words;
  }

  // RL/RR switch compensation on, with the tool table's R of the called
  // tool, on an L block in the plane (the TNC's rule); R0 switches it off
  // on one. A block without the word keeps what is in force.
  void setCompensation(const TncBlock& block, const Position& end) {
    if (!block.radiusCompensation) {
      return;
    }
    bool circle = block.kind == TncBlock::Kind::Circle;
    bool inPlane = (end.axes[0] != position_.axes[0] || end.axes[1] != position_.axes[1]);
    char word = *block.radiusCompensation;
    if (word == '0') {
      if (!compensation_.isOn()) {
        return;
      }
      if (circle || !inPlane) {
        fail(block, circle ? "R0 on a C block: the TNC cancels radius compensation on a "
                             "straight line (L) in the plane"
                           : "R0 on a block without an X or Y move while RL/RR is on: the TNC "
                             "cancels radius compensation on a straight line in the plane");
      }
      compensation_.cancel(simBlock(block));
      return;
    }
    bool left = word == 'L';
    if (compensation_.isOn()) {
      if (left != compensatingLeft_) {
        fail(block, fmt::format("{} while {} is on: the TNC needs a move with R0 between them",
                                left ? "RL" : "RR", left ? "RR" : "RL"));
      }
      return;
    }
    if (circle) {
      fail(block, "RL/RR on a C block: the TNC starts radius compensation on a straight line (L) "
                  "in the plane, not on an arc");
    }
    if (!position_.known() || !inPlane) {
      fail(block, !position_.known() ? "RL/RR from an unknown position"
                                     : "RL/RR on a block without an X or Y move: the TNC starts "
                                       "radius compensation on a straight line in the plane");
    }
    if (!tool_) {
      fail(block, "RL/RR before any TOOL CALL: no tool radius to compensate by");
    }
    auto radius = options_.toolRadii.find(*tool_);
    if (radius == options_.toolRadii.end()) {
      fail(block, fmt::format("RL/RR: the radius R of tool {0} is not in the tool table; give it "
                              "with --tool-radius {0}=R",
                              *tool_));
    }
    compensatingLeft_ = left;
    compensation_.start(left, radius->second, simBlock(block));
  }

  // A move of `block` to `end` (`event`'s kind and centre set) through the
  // compensation, and what it let through onto the path.
  void compensate(const TncBlock& block, std::size_t index, sim::ExecutedEvent event,
                  const Position& end, bool moves, double feed) {
    if (!end.known()) {
      fail(block, "a move with radius compensation from an unknown position");
    }
    event.start = {*position_.axes[0], *position_.axes[1], *position_.axes[2]};
    event.end = {*end.axes[0], *end.axes[1], *end.axes[2]};
    event.feed = feed;
    event.line = block.line;
    position_ = end;
    sim::Block words = simBlock(block);
    if (moves) {
      if (event.kind != sim::ExecutedEvent::Kind::Rapid && inLoop_[index]) {
        ++run_.loopOperations.feedMoves;
      }
      compensation_.add(event, words);
    }
    compensation_.endOfBlock(words);
    for (const ir::MachineEvent& executed : sim::executedToolPath(compensated_).events) {
      run_.path.events.push_back(executed);
    }
    compensated_.events.clear();
  }

  std::vector<TncBlock> blocks_;
  const TncRunOptions& options_;
  TncRun& run_;
  std::map<int, std::size_t> labels_;
  std::set<int> named_;
  std::vector<bool> inLoop_;
  std::map<int, double> parameters_;
  std::map<std::size_t, int> repeats_;
  std::vector<std::size_t> returns_;
  std::optional<std::size_t> countingBlock_;
  Position position_;
  std::optional<std::pair<double, double>> centre_;
  std::optional<double> feed_;
  bool started_ = false;
  std::optional<int> tool_; // of the last TOOL CALL that named one
  sim::ExecutedPath compensated_;
  sim::RadiusCompensation compensation_;
  bool compensatingLeft_ = false;
};

std::string lineText(std::string_view text, int line) {
  for (int i = 1; i < line; ++i) {
    std::size_t newline = text.find('\n');
    if (newline == std::string_view::npos) {
      return "";
    }
    text.remove_prefix(newline + 1);
  }
  return std::string(text.substr(0, text.find('\n')));
}

} // namespace

TncRun runTncProgram(std::string_view text, const TncRunOptions& options) {
  TncRun run;
  try {
    TncExecutor(readTncProgram(text), options, run).execute();
  } catch (const TncProgramError& error) {
    run.error = TncError{error.line(), error.what(), lineText(text, error.line())};
  } catch (const sim::SimulationError& error) { // from the radius compensation
    run.error = TncError{error.line(), error.what(), lineText(text, error.line())};
  }
  return run;
}

std::optional<std::string> withEditedParameter(std::string_view text, int encodedParameter,
                                               double value) {
  std::string assignment = fmt::format(" FN 0: {} = ", tncParameterName(encodedParameter));
  std::size_t begin = 0;
  while (begin < text.size()) {
    std::size_t end = text.find('\n', begin);
    end = end == std::string_view::npos ? text.size() : end;
    std::string_view row = text.substr(begin, end - begin);
    std::size_t at = row.find(assignment);
    bool numbered =
        at != std::string_view::npos && at > 0 && row.find_first_not_of("0123456789") == at;
    if (numbered) {
      std::string edited(text.substr(0, begin + at + assignment.size()));
      std::string number = fmt::format("{:.9f}", value);
      number.erase(number.find_last_not_of('0') + 1);
      if (number.ends_with('.')) {
        number.pop_back();
      }
      edited += number.starts_with('-') ? number : "+" + number;
      edited += text.substr(end);
      return edited;
    }
    begin = end + 1;
  }
  return std::nullopt;
}

} // namespace cncc::backends::heidenhain
