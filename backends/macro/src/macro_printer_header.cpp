// The program's header comments, its parameters' defaults and checks, and
// its tables.
#include "macro_printer.h"

#include "cncc/backends/gcode_writer.h"
#include "cncc/ir/interpreter.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cctype>
#include <set>

namespace cncc::backends {

using ir::Opcode;

std::string MacroProgramPrinter::parameterDefault(std::size_t index) const {
  return expressions_.constant(function_.parameters[index].defaultValue);
}

void MacroProgramPrinter::printHeader() {
  comment(fmt::format("{} - {} {}", options_.sourceName, keyword("part"), options_.partName));
  if (options_.callable) {
    printCallComment();
  }
  bool positional = options_.callable && dialect_.callStyle == CallStyle::PositionalArguments;
  for (std::size_t i = 0; i < function_.parameters.size(); ++i) {
    std::string where = positional ? fmt::format("#{} = ", i + 1) : "";
    comment(fmt::format(
        "{}{} {}, {} {}", where, expressions_.parameterVariable(i), function_.parameters[i].name,
        keyword(function_.parameters[i].fixed ? "fixed at" : "default"), parameterDefault(i)));
    if (dialect_.listsVariables) {
      variableMeanings_[allocation_.parameterVariables[i]].meaning =
          fmt::format("parameter {}", function_.parameters[i].name);
    }
  }
  for (const auto& [base, tables] : ir::tablesByBase(function_, allocation_)) {
    int count = static_cast<int>(function_.tables[tables.front()].size());
    comment(fmt::format("#{}-#{} {} {}, {} {}", base, base + count - 1, keyword("table"),
                        fmt::join(tables, keyword(" and ")), count, keyword("values")));
  }
  if (dialect_.listsVariables) {
    printValueVariables();
  }
}

// How a caller calls the program with the parameters' defaults.
void MacroProgramPrinter::printCallComment() {
  if (dialect_.callStyle == CallStyle::PositionalArguments) {
    std::string call = fmt::format("call: o<{}> call", options_.subroutineName);
    for (std::size_t i = 0; i < function_.parameters.size(); ++i) {
      call += fmt::format(" [{}]", parameterDefault(i));
    }
    comment(call);
    return;
  }
  std::string call = fmt::format("CALL G65 P{}", options_.programNumber);
  for (std::size_t i = 0; i < function_.parameters.size(); ++i) {
    std::optional<char> letter =
        options_.profile != nullptr
            ? options_.profile->letterForLocal(allocation_.parameterVariables[i])
            : std::nullopt;
    if (letter) {
      call += fmt::format(" {}{}", *letter, parameterDefault(i));
    }
  }
  comment(call);
}

// For source maps: what `variable` holds (meanings joined when it is reused)
// and from which statements.
void MacroProgramPrinter::noteVariable(int variable, const std::string& upperMeaning,
                                       frontend::SourceSpan span) {
  VariableMeaning& noted = variableMeanings_[variable];
  std::string meaning = upperMeaning;
  std::transform(meaning.begin(), meaning.end(), meaning.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  // One variable's: "loop index", "work value".
  meaning = meaning.ends_with("indexes") ? meaning.substr(0, meaning.size() - 2)
                                         : meaning.substr(0, meaning.size() - 1);
  if (noted.meaning.find(meaning) == std::string::npos) {
    noted.meaning += (noted.meaning.empty() ? "" : ", ") + meaning;
  }
  if (span.valid() &&
      std::find(noted.spans.begin(), noted.spans.end(), span) == noted.spans.end()) {
    noted.spans.push_back(span);
  }
}

// Variables of values, one line per meaning: `(#4-#8 #10 WORK VALUES)`.
void MacroProgramPrinter::printValueVariables() {
  std::set<std::uint32_t> bounds;
  for (const ir::Instruction& instruction : function_.instructions) {
    if (instruction.opcode == Opcode::Loop && !ir::loopAdvance(function_, instruction).valid()) {
      bounds.insert(instruction.operands[1].index);
    }
  }
  std::map<std::string, std::set<int>> variables;
  for (const ir::Instruction& instruction : function_.instructions) {
    if (!instruction.result.valid() || instruction.opcode == Opcode::Param ||
        allocation_.isSteppedProduct(instruction.result)) {
      continue;
    }
    int variable = allocation_.variableOfValue[instruction.result.index];
    if (variable < 0) {
      continue;
    }
    std::string meaning = "WORK VALUES";
    if (instruction.opcode == Opcode::Loop) {
      bool parameter = allocation_.stepOfLoop.contains(instruction.result.index) ||
                       ir::loopAdvance(function_, instruction).valid();
      meaning = parameter ? "CURVE PARAMETERS" : "LOOP INDEXES";
    } else if (bounds.contains(instruction.result.index)) {
      meaning = "STEP COUNTS";
    }
    variables[meaning].insert(variable);
    noteVariable(variable, meaning, instruction.span);
  }
  // Meanings joined on as few lines as the block length allows.
  std::string text;
  auto append = [&](const std::string& piece, const char* separator) {
    if (!text.empty() &&
        static_cast<int>(text.size() + piece.size()) + 4 > dialect_.maximumLineLength) {
      comment(text);
      text.clear();
    }
    text += (text.empty() ? "" : separator) + piece;
  };
  for (const auto& [meaning, set] : variables) {
    for (auto it = set.begin(); it != set.end();) {
      auto last = it;
      auto next = std::next(it);
      while (next != set.end() && *next == *last + 1) {
        last = next++;
      }
      append(last == it ? fmt::format("#{}", *it) : fmt::format("#{}-#{}", *it, *last),
             it == set.begin() ? ", " : " ");
      it = next;
    }
    append(keyword(meaning), " ");
  }
  if (!text.empty()) {
    comment(text);
  }
}

// A main program assigns the defaults where the operator edits them; a
// macro, or parameters in common variables, keep what the caller or the
// operator set and fill in only what is vacant (#0). A program called with
// positional arguments takes them.
void MacroProgramPrinter::printParameters() {
  bool positional = options_.callable && dialect_.callStyle == CallStyle::PositionalArguments;
  if (positional &&
      function_.parameters.size() > static_cast<std::size_t>(dialect_.maximumCallArguments)) {
    errors_.push_back(fmt::format("the part has {} parameters, a {} call takes up to {} arguments",
                                  function_.parameters.size(), dialect_.controllerName,
                                  dialect_.maximumCallArguments));
  }
  bool assignAlways =
      !dialect_.fillsVacantParameters || (!options_.callable && !options_.parametersInCommon);
  for (std::size_t i = 0; i < function_.parameters.size(); ++i) {
    std::string variable = expressions_.parameterVariable(i);
    std::string value = positional ? fmt::format("#{}", i + 1) : parameterDefault(i);
    if (assignAlways) {
      line(assignment(variable, value));
    } else {
      conditional(fmt::format("[{} EQ #0]", variable), fmt::format("[{} NE #0]", variable),
                  assignment(variable, value));
    }
  }
  printFixedParameterChecks();
}

// A parameter whose default the compiler built into the program (a loop
// bound, a curve's points): any other value raises an alarm rather than
// cutting a part the operator did not ask for. The value is compared with
// the literal the defaults assign, so the test is exact.
void MacroProgramPrinter::printFixedParameterChecks() {
  for (std::size_t i = 0; i < function_.parameters.size(); ++i) {
    if (!function_.parameters[i].fixed) {
      continue;
    }
    std::string variable = expressions_.parameterVariable(i);
    std::string literal = parameterDefault(i);
    std::string condition = fmt::format("[{} NE {}]", variable, literal);
    std::string message = fmt::format("{} is fixed at {}", function_.parameters[i].name, literal);
    bool sameBlock = dialect_.control == ControlWords::WhileDoEnd && dialect_.hasThen;
    conditional(condition, fmt::format("[{} EQ {}]", variable, literal),
                alarmStatement(message, sameBlock ? condition.size() + 9 : 0));
  }
}

// `#3000=1 (MESSAGE)` (alarm 3001), `(abort, message)`: the message cut to
// what the line length leaves beside `reserved` characters (an IF around it).
std::string MacroProgramPrinter::alarmStatement(std::string_view text, std::size_t reserved) const {
  std::string message = gcodeCommentText(text);
  std::size_t used = dialect_.alarmStart.size() + dialect_.alarmEnd.size() + reserved;
  auto limit = static_cast<std::size_t>(std::max(0, dialect_.maximumLineLength));
  std::size_t room = limit > used ? limit - used : 0;
  return dialect_.alarmStart + message.substr(0, room) + dialect_.alarmEnd;
}

void MacroProgramPrinter::printTables() {
  for (const auto& [base, tables] : ir::tablesByBase(function_, allocation_)) {
    const std::vector<double>& values = function_.tables[tables.front()];
    for (std::size_t i = 0; i < values.size(); ++i) {
      line(assignment(fmt::format("#{}", base + static_cast<int>(i)),
                      expressions_.constant(values[i])));
    }
  }
}

} // namespace cncc::backends
