// Reads the text form that printer.cpp writes, one instruction a line.
#include "curve_table_text.h"
#include "cut_table_text.h"
#include "ir_text.h"

#include "cncc/ir/builder.h"
#include "cncc/ir/printer.h"

#include <fmt/format.h>
#include <map>
#include <memory>

namespace cncc::ir {

namespace {

using namespace text;

class IrParser {
public:
  Function parse(std::string_view text) {
    std::size_t lineNumber = 0;
    while (!text.empty()) {
      std::size_t newline = text.find('\n');
      std::string_view line = trim(text.substr(0, newline));
      text.remove_prefix(newline == std::string_view::npos ? text.size() : newline + 1);
      ++lineNumber;
      line_ = static_cast<int>(lineNumber);
      if (!line.empty() && !startsWith(line, "//")) {
        parseLine(line);
      }
    }
    if (!builder_ || !finished_) {
      throw Failure{"the function is not closed with '}'"};
    }
    Function function = builder_->finish();
    function.cuts = std::move(cuts_);
    for (std::uint32_t index : fixed_) {
      function.parameters[index].fixed = true;
    }
    return function;
  }

  int line() const { return line_; }

private:
  // The loops, ifs and curve.laps being read, innermost last.
  struct OpenRegions {
    Opcode opcode = Opcode::Loop;
    std::size_t regions = 0; // curve.lap: how many its curve needs
    std::size_t region = 0;  // curve.lap: the one being read
    bool pointEnded = false; // curve.lap: its curve.point was read
  };

  void parseLine(std::string_view line) {
    if (!builder_) {
      parseHeader(line);
      return;
    }
    if (finished_) {
      throw Failure{"text after the end of the function"};
    }
    if (curve_) {
      if (readCurveEntryLine(line, *curve_, builder_->function().curves)) {
        builder_->addCurve(std::move(*curve_));
        curve_.reset();
      }
      return;
    }
    if (!open_.empty() && open_.back().pointEnded && line != "}" && line != "} piece {") {
      throw Failure{"'curve.point' ends a curve.lap region: expected '} piece {' or '}'"};
    }
    if (line == "}") {
      close();
      return;
    }
    if (line == "} else {") {
      if (open_.empty() || open_.back().opcode != Opcode::If) {
        throw Failure{"'else' without 'if'"};
      }
      builder_->beginElse();
      return;
    }
    if (line == "} piece {") {
      nextLapRegion();
      return;
    }
    if (startsWith(line, "table @")) {
      parseTable(line);
      return;
    }
    if (startsWith(line, "curve @")) {
      curve_ = readCurveEntryHeader(line, builder_->function().curves.size());
      return;
    }
    if (startsWith(line, "cut @")) {
      cuts_.push_back(readCutEntry(line, cuts_.size()));
      return;
    }
    std::string_view result;
    if (startsWith(line, "%")) {
      std::size_t equals = line.find(" = ");
      if (equals == std::string_view::npos) {
        throw Failure{"expected '%name = operation'"};
      }
      result = line.substr(0, equals);
      line = line.substr(equals + 3);
    }
    parseOperation(result, line);
  }

  void parseHeader(std::string_view line) {
    if (!startsWith(line, "func @") || line.back() != '{') {
      throw Failure{"expected 'func @name(...) {'"};
    }
    std::size_t open = line.find('(');
    std::size_t close = line.rfind(')');
    if (open == std::string_view::npos || close == std::string_view::npos || close < open) {
      throw Failure{"expected the parameter list in parentheses"};
    }
    builder_.emplace(std::string(line.substr(6, open - 6)));
    for (std::string_view parameter : splitList(line.substr(open + 1, close - open - 1))) {
      std::size_t equals = parameter.find('=');
      if (equals == std::string_view::npos) {
        throw Failure{"a parameter needs a default: 'name = value'"};
      }
      std::string name(trim(parameter.substr(0, equals)));
      // `r = 5 fixed`: its default was read as a constant (Parameter::fixed).
      std::string_view value = trim(parameter.substr(equals + 1));
      bool fixed = value.ends_with(" fixed");
      if (fixed) {
        value.remove_suffix(6);
      }
      parameters_[name] = builder_->addParameter(name, parseNumber(value));
      if (fixed) {
        fixed_.push_back(parameters_[name]);
      }
    }
  }

  void parseTable(std::string_view line) {
    std::size_t open = line.find('[');
    std::size_t close = line.rfind(']');
    if (open == std::string_view::npos || close == std::string_view::npos) {
      throw Failure{"expected 'table @n = [...]'"};
    }
    std::vector<double> values;
    for (std::string_view value : splitList(line.substr(open + 1, close - open - 1))) {
      values.push_back(parseNumber(value));
    }
    builder_->addTable(std::move(values));
  }

  ValueId value(std::string_view name) {
    auto found = values_.find(std::string(trim(name)));
    if (found == values_.end()) {
      throw Failure{fmt::format("'{}' is not defined", trim(name))};
    }
    return found->second;
  }

  std::vector<ValueId> operandList(std::string_view text) {
    std::vector<ValueId> operands;
    for (std::string_view name : splitList(text)) {
      operands.push_back(value(name));
    }
    return operands;
  }

  void define(std::string_view name, ValueId id) {
    if (name.empty()) {
      throw Failure{"this operation has a result; write '%name = ...'"};
    }
    if (!values_.emplace(std::string(name), id).second) {
      throw Failure{fmt::format("'{}' is defined twice", name)};
    }
  }

  void parseOperation(std::string_view result, std::string_view line) {
    std::size_t space = line.find(' ');
    std::string spelling(line.substr(0, space));
    std::string_view rest = space == std::string_view::npos ? "" : trim(line.substr(space + 1));
    auto opcode = opcodes().find(spelling);
    if (opcode == opcodes().end()) {
      throw Failure{fmt::format("unknown operation '{}'", spelling)};
    }
    switch (opcode->second) {
    case Opcode::Const:
      define(result, builder_->constant(parseNumber(rest)));
      return;
    case Opcode::ConstBool:
      define(result, builder_->constantBool(rest == "true"));
      return;
    case Opcode::Param: {
      auto found = parameters_.find(std::string(rest));
      if (found == parameters_.end()) {
        throw Failure{fmt::format("'{}' is not a parameter of the function", rest)};
      }
      define(result, builder_->parameter(found->second));
      return;
    }
    case Opcode::TableLoad: {
      std::vector<std::string_view> parts = splitList(rest);
      if (parts.size() != 2 || !startsWith(parts[0], "@")) {
        throw Failure{"expected 'table.load @n, %index'"};
      }
      auto table = static_cast<std::uint32_t>(parseNumber(parts[0].substr(1)));
      define(result, builder_->tableLoad(table, value(parts[1])));
      return;
    }
    case Opcode::Nurbs: {
      std::vector<std::string_view> parts = splitList(rest);
      if (parts.size() < 3 || !startsWith(parts[0], "@")) {
        throw Failure{"expected 'move.nurbs @n, %z, %f, %weight, ...'"};
      }
      auto table = static_cast<std::uint32_t>(parseNumber(parts[0].substr(1)));
      std::vector<ValueId> weights;
      for (std::size_t i = 3; i < parts.size(); ++i) {
        weights.push_back(value(parts[i]));
      }
      builder_->nurbs(table, value(parts[1]), value(parts[2]), weights);
      return;
    }
    case Opcode::Spline: {
      std::vector<std::string_view> parts = splitList(rest);
      if (parts.size() != 3 || !startsWith(parts[0], "@")) {
        throw Failure{"expected 'move.spline @n, %z, %f'"};
      }
      auto table = static_cast<std::uint32_t>(parseNumber(parts[0].substr(1)));
      builder_->spline(table, value(parts[1]), value(parts[2]));
      return;
    }
    case Opcode::Tool:
      parseTool(rest);
      return;
    case Opcode::Origin:
      parseOrigin(rest);
      return;
    case Opcode::Coolant: {
      std::optional<CoolantMode> mode = coolantModeNamed(rest);
      if (!mode) {
        throw Failure{"expected 'coolant off', 'flood', 'mist' or 'through'"};
      }
      builder_->coolant(*mode);
      return;
    }
    case Opcode::Home:
      if (!rest.empty()) {
        throw Failure{"'move.home' takes nothing"};
      }
      builder_->home();
      return;
    case Opcode::Contouring:
      builder_->contouring(rest == "off" ? 0 : parseNumber(rest));
      return;
    case Opcode::Compensation:
      parseCompensation(rest);
      return;
    case Opcode::Comment:
      builder_->comment(unquote(rest));
      return;
    case Opcode::Alarm:
      builder_->alarm(unquote(rest));
      return;
    case Opcode::CutBegin:
      builder_->cutBegin(parseWholeNumber(rest));
      return;
    case Opcode::Arc:
      parseArc(rest);
      return;
    case Opcode::Loop: {
      if (rest.empty() || rest.back() != '{') {
        throw Failure{"expected '{' after the loop's bounds"};
      }
      std::vector<ValueId> bounds = operandList(rest.substr(0, rest.size() - 1));
      if (bounds.size() != 2) {
        throw Failure{"a loop has two bounds"};
      }
      define(result, builder_->beginLoop(bounds[0], bounds[1]));
      open_.push_back({Opcode::Loop});
      return;
    }
    case Opcode::If: {
      if (rest.empty() || rest.back() != '{') {
        throw Failure{"expected '{' after the condition"};
      }
      builder_->beginIf(value(rest.substr(0, rest.size() - 1)));
      open_.push_back({Opcode::If});
      return;
    }
    case Opcode::CurveLap:
      define(result, parseCurveLap(rest));
      return;
    case Opcode::CurvePoint:
    case Opcode::CurveArc:
    case Opcode::CurveWalk:
      if (!open_.empty() && open_.back().opcode == Opcode::CurveLap) {
        parseRegionEnd(opcode->second, rest);
        open_.back().pointEnded = true;
        return;
      }
      break; // out of place: the verifier says so
    default:
      break;
    }
    const OpcodeInfo& info = opcodeInfo(opcode->second);
    std::vector<ValueId> operands = operandList(rest);
    if (info.operandCount >= 0 && static_cast<int>(operands.size()) != info.operandCount) {
      throw Failure{fmt::format("'{}' takes {} operands, not {}", spelling, info.operandCount,
                                operands.size())};
    }
    ValueId id = builder_->operation(opcode->second, std::move(operands));
    if (info.result != ValueType::None) {
      define(result, id);
    } else if (!result.empty()) {
      throw Failure{fmt::format("'{}' has no result", spelling)};
    }
  }

  // `tool n length h, %diameter`; without `length h` the dialect's default.
  void parseTool(std::string_view rest) {
    std::vector<std::string_view> parts = splitList(rest);
    std::vector<std::string_view> words = splitWords(parts.empty() ? "" : parts[0]);
    bool withLength = words.size() == 3 && words[1] == "length";
    if (parts.size() != 2 || (words.size() != 1 && !withLength)) {
      throw Failure{"expected 'tool number [length register], %diameter'"};
    }
    builder_->tool(parseNumber(words[0]), value(parts[1]),
                   withLength ? parseWholeNumber(words[2]) : 0);
  }

  // `origin 54` or `origin 54.1 p`
  void parseOrigin(std::string_view rest) {
    std::vector<std::string_view> words = splitWords(rest);
    if (words.empty() || words.size() > 2) {
      throw Failure{"expected 'origin code' or 'origin 54.1 number'"};
    }
    builder_->origin(parseNumber(words[0]), words.size() == 2 ? parseWholeNumber(words[1]) : 0);
  }

  // `compensation left|right register radius` or `compensation off`.
  void parseCompensation(std::string_view rest) {
    std::vector<std::string_view> words = splitWords(rest);
    if (words.size() == 1 && words[0] == "off") {
      builder_->compensation(0, 0);
      return;
    }
    if (words.size() != 3 || (words[0] != "left" && words[0] != "right")) {
      throw Failure{"expected 'compensation left|right register radius' or 'compensation off'"};
    }
    double radius = parseNumber(words[2]);
    builder_->compensation(words[0] == "left" ? radius : -radius, parseWholeNumber(words[1]));
  }

  // `move.arc cw|ccw %x, %y, %z, %i, %j, %f`
  void parseArc(std::string_view rest) {
    std::size_t space = rest.find(' ');
    std::string_view turn = rest.substr(0, space);
    if (turn != "cw" && turn != "ccw") {
      throw Failure{"expected 'move.arc cw' or 'move.arc ccw'"};
    }
    std::vector<ValueId> operands =
        operandList(space == std::string_view::npos ? "" : rest.substr(space + 1));
    if (operands.size() != 6) {
      throw Failure{
          fmt::format("'move.arc' takes 6 operands (x, y, z, i, j, f), not {}", operands.size())};
    }
    builder_->arc(turn == "cw" ? ArcTurn::Clockwise : ArcTurn::CounterClockwise, operands[0],
                  operands[1], operands[2], operands[3], operands[4], operands[5]);
  }

  void close() {
    if (open_.empty()) {
      finished_ = true;
      return;
    }
    const OpenRegions& open = open_.back();
    if (open.opcode == Opcode::Loop) {
      builder_->endLoop();
    } else if (open.opcode == Opcode::If) {
      builder_->endIf();
    } else {
      // The builder left the lap at its last region's curve.point.
      endLapRegion(open);
      if (open.region + 1 < open.regions) {
        throw Failure{fmt::format("this curve.lap has {} regions, its curve needs {}",
                                  open.region + 1, open.regions)};
      }
    }
    open_.pop_back();
  }

  // `%t = curve.lap @c, %zFrom, %zTo, %f {`
  ValueId parseCurveLap(std::string_view rest) {
    if (rest.empty() || rest.back() != '{') {
      throw Failure{"expected '{' after the curve.lap's operands"};
    }
    std::vector<std::string_view> parts = splitList(rest.substr(0, rest.size() - 1));
    if (parts.size() < 4 || !startsWith(parts[0], "@")) {
      throw Failure{"expected 'curve.lap @c, %zFrom, %zTo, %f {'"};
    }
    std::uint32_t curve = parseWholeNumber(parts[0].substr(1));
    const std::vector<CurveTableEntry>& curves = builder_->function().curves;
    if (curve >= curves.size()) {
      throw Failure{fmt::format("curve @{} is not in the curve table", curve)};
    }
    std::size_t regions = curves[curve].regionCount();
    if (regions == 0) {
      throw Failure{fmt::format("curve @{} has no pieces", curve)};
    }
    // A NURBS block's weights, one per control point, are the verifier's to count.
    std::size_t more = curves[curve].lapOperandCount() - 3;
    bool weights = curves[curve].sampling == CurveSampling::NurbsBlocks;
    if (!weights && parts.size() != 1 + 3 + more) {
      throw Failure{fmt::format("curve @{} wants {} operands after the lap's three (a range and a "
                                "count for each region whose steps the program computes, then an "
                                "offset's distance)",
                                curve, more)};
    }
    std::vector<ValueId> computedSteps;
    for (std::size_t k = 4; k < parts.size(); ++k) {
      computedSteps.push_back(value(parts[k]));
    }
    ValueId lap = builder_->beginCurveLap(curve, value(parts[1]), value(parts[2]), value(parts[3]),
                                          computedSteps);
    open_.push_back({Opcode::CurveLap, regions});
    return lap;
  }

  void endLapRegion(const OpenRegions& open) {
    if (!open.pointEnded) {
      throw Failure{"a curve.lap region must end with 'curve.point'"};
    }
  }

  // `} piece {`: the builder moved to the next region at the curve.point.
  void nextLapRegion() {
    if (open_.empty() || open_.back().opcode != Opcode::CurveLap) {
      throw Failure{"'} piece {' outside a curve.lap"};
    }
    OpenRegions& open = open_.back();
    endLapRegion(open);
    if (open.region + 1 >= open.regions) {
      throw Failure{
          fmt::format("this curve.lap has more regions than the {} its curve needs", open.regions)};
    }
    ++open.region;
    open.pointEnded = false;
  }

  // A curve.lap region's curve.point, curve.arc or curve.walk.
  void parseRegionEnd(Opcode opcode, std::string_view rest) {
    std::vector<ValueId> point = operandList(rest);
    const OpcodeInfo& info = opcodeInfo(opcode);
    if (point.size() != static_cast<std::size_t>(info.operandCount)) {
      throw Failure{
          fmt::format("expected '{}' with {} operands", info.spelling, info.operandCount)};
    }
    if (opcode == Opcode::CurveArc) {
      builder_->curveArc(point[0], point[1], point[2], point[3], point[4]);
    } else if (opcode == Opcode::CurveWalk) {
      builder_->curveWalk(point[0], point[1], point[2], point[3]);
    } else {
      builder_->curvePoint(point[0], point[1], point[2]);
    }
  }

  static const std::map<std::string, Opcode>& opcodes() {
    static const std::map<std::string, Opcode> table = [] {
      std::map<std::string, Opcode> result;
      for (Opcode opcode : allOpcodes()) {
        result[std::string(opcodeInfo(opcode).spelling)] = opcode;
      }
      return result;
    }();
    return table;
  }

  std::optional<FunctionBuilder> builder_;
  std::map<std::string, std::uint32_t> parameters_;
  std::vector<std::uint32_t> fixed_; // the parameters marked `fixed`
  std::map<std::string, ValueId> values_;
  std::vector<OpenRegions> open_; // innermost last
  // A `curve @c ... {` block being read.
  std::optional<CurveTableEntry> curve_;
  std::vector<CutGeometry> cuts_; // the `cut @n` lines read

  bool finished_ = false;
  int line_ = 0;
};

} // namespace

std::optional<Function> parseFunction(std::string_view text, ParseError& error) {
  IrParser parser;
  try {
    return parser.parse(text);
  } catch (const Failure& failure) {
    error = {parser.line(), failure.message};
    return std::nullopt;
  }
}

} // namespace cncc::ir
