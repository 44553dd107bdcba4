#include "linuxcnc_dialect.h"

#include "controller_words.h"

#include "cncc/backends/linuxcnc_program.h"

#include <algorithm>

namespace cncc::backends {

using ir::Opcode;

std::vector<ir::Opcode> linuxcncStatementOpcodes() {
  return {Opcode::Min, Opcode::Max, Opcode::Select, Opcode::Rem};
}

namespace {

// Inside brackets LinuxCNC has precedence (`**`, then `* / MOD`, then
// `+ -`, then `EQ NE GT GE LT LE`, then `AND OR XOR`); a unary minus
// applies to the value right of it alone. Where a word or an assignment
// takes a value, anything but an atom or a number is bracketed: `X[SIN[..]]`
// rather than `XSIN[..]` (both are read, one is read easily).
MacroBareForms linuxcncBareForms() {
  using enum MacroForm;
  using enum MacroPosition;
  MacroForms negations = formsOf(Atom, Function, NegativeNumber, Negation);
  MacroForms products = negations | formsOf(Power, Multiplicative);
  MacroForms sums = products | formsOf(Additive);
  return bareFormsOf({{LeftOfAdditive, sums},
                      {RightOfAdditive, products},
                      {LeftOfMultiplicative, products},
                      {RightOfMultiplicative, negations | formsOf(Power)},
                      {UnderNegation, formsOf(Atom, Function)},
                      {PowerOperand, negations},
                      {Compared, sums},
                      {LeftOfLogical, everyForm},
                      {RightOfLogical, everyForm & ~formsOf(Logical)},
                      {Operand, formsOf(Atom, NegativeNumber)},
                      {AssignedValue, formsOf(Atom, NegativeNumber)},
                      {AssignedDefinition, formsOf(Atom, Function)}});
}

} // namespace

MacroDialect linuxcncDialect(int coordinateDecimals) {
  MacroDialect dialect;
  dialect.name = "linuxcnc";
  dialect.controllerName = "LinuxCNC";
  dialect.linesName = "lines";
  dialect.mainEnd = {"M2"};
  dialect.callableEnd = {"o<{name}> endsub", "M2"};
  dialect.subroutineStart = "o<{name}> sub";
  dialect.callStyle = CallStyle::PositionalArguments;
  dialect.maximumCallArguments = linuxcncMaximumCallArguments;
  dialect.parametersBeforeSetUp = true;
  dialect.fillsVacantParameters = false;
  dialect.listsVariables = false;
  dialect.comments = CommentStyle::Semicolon;
  dialect.upperCaseComments = false;
  dialect.diameterOnToolBlock = false;
  dialect.maximumLineLength = linuxcncMaximumLineLength;
  dialect.assignment = " = ";
  dialect.alarmStart = "(abort, ";
  dialect.alarmEnd = ")";
  dialect.control = ControlWords::OWords;
  dialect.firstLabel = 100;
  dialect.keepsWordsThroughLoops = false;
  // `0.5`: it reads better and LinuxCNC accepts both.
  dialect.numbers = {linuxcncSignificantDigits, coordinateDecimals,
                     std::numeric_limits<double>::infinity(), false, false};
  dialect.bareForms = linuxcncBareForms();
  // FIX rounds down, FUP up.
  dialect.functionWords = {{Opcode::Floor, "FIX"}, {Opcode::Ceil, "FUP"}};
  dialect.power = PowerStyle::Operator;
  dialect.minMax = MinMaxStyle::ChooseBetween;
  dialect.remainder = RemainderStyle::SignedAbsMod;
  dialect.statementOpcodes = linuxcncStatementOpcodes();
  dialect.one = "1";
  dialect.trueComparison = "1 EQ 1";
  dialect.falseComparison = "1 EQ 0";
  dialect.comparesBoolVariables = true;
  dialect.hasNurbsBlocks = false;
  // G41.1/G42.1 D<diameter>: compensation needs no tool table entry.
  dialect.dynamicCompensation = true;
  return dialect;
}

ir::InlineShape linuxcncInlineShape(const ir::Function&, const ir::Instruction& instruction,
                                    std::span<const ir::InlineShape> operands) {
  switch (instruction.opcode) {
  case Opcode::Const:
  case Opcode::Param:
  case Opcode::Loop:
    return {};
  default:
    break;
  }
  int depth = 0;
  int operations = 1;
  for (const ir::InlineShape& operand : operands) {
    depth = std::max(depth, operand.bracketDepth);
    operations += operand.operations;
  }
  // Trigonometry adds its conversion to degrees.
  bool converts = isTrigonometric(instruction.opcode) ||
                  isInverseTrigonometric(instruction.opcode) ||
                  instruction.opcode == Opcode::Atan || instruction.opcode == Opcode::Atan2;
  return {depth + 1, ir::InlineForm::Atom, operations + (converts ? 1 : 0)};
}

} // namespace cncc::backends
