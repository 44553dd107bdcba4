#include "macro_dialect.h"

#include "controller_words.h"

#include <algorithm>

namespace cncc::backends {

using ir::Opcode;

bool MacroDialect::isStatement(Opcode opcode) const {
  return std::find(statementOpcodes.begin(), statementOpcodes.end(), opcode) !=
         statementOpcodes.end();
}

std::string_view MacroDialect::functionWord(Opcode opcode) const {
  for (const auto& [known, word] : functionWords) {
    if (known == opcode) {
      return word;
    }
  }
  return sharedFunctionName(opcode);
}

std::vector<ir::Opcode> macroStatementOpcodes() {
  return {Opcode::Min,  Opcode::Max, Opcode::Select, Opcode::Floor,
          Opcode::Ceil, Opcode::Rem, Opcode::Atan,   Opcode::Atan2};
}

MacroBareForms bareFormsOf(std::initializer_list<std::pair<MacroPosition, MacroForms>> positions) {
  MacroBareForms forms{};
  for (const auto& [position, bare] : positions) {
    forms[static_cast<std::size_t>(position)] = bare;
  }
  return forms;
}

MacroBareForms customMacroBareForms() {
  using enum MacroForm;
  using enum MacroPosition;
  // Functions first, then * /, then + -; everything else in brackets (a
  // unary minus too, except alone on the right of `=`).
  MacroForms atoms = formsOf(Atom, Function, NegativeNumber);
  // A condition assigned is bracketed, `#5=[#1 LT 2.]`.
  MacroForms expressions = everyForm & ~formsOf(Comparison, Logical);
  return bareFormsOf({{LeftOfAdditive, atoms | formsOf(Multiplicative, Additive)},
                      {RightOfAdditive, atoms | formsOf(Multiplicative)},
                      {LeftOfMultiplicative, atoms | formsOf(Multiplicative)},
                      {RightOfMultiplicative, atoms},
                      {UnderNegation, atoms},
                      {PowerOperand, atoms},
                      {Compared, atoms},
                      {LeftOfLogical, formsOf(Atom)},
                      {RightOfLogical, formsOf(Atom)},
                      {Operand, atoms},
                      {AssignedValue, expressions},
                      {AssignedDefinition, expressions}});
}

MacroDialect customMacroDialect(const ControllerProfile& profile) {
  MacroDialect dialect;
  dialect.name = profile.name;
  dialect.controllerName = "the controller";
  dialect.linesName = "blocks";
  dialect.programStart = {"%", "O{number}"};
  dialect.mainEnd = {"M30", "%"};
  dialect.callableEnd = {"M99", "%"};
  dialect.maximumLineLength = profile.maximumBlockLength;
  dialect.hasThen = profile.hasThen;
  dialect.maximumLabel = profile.maximumSequenceNumber;
  dialect.maximumLoopNesting = std::min(profile.maximumLoopNesting, profile.maximumLoopIdentifier);
  dialect.numbers = {profile.significantDigits, profile.coordinateDecimals,
                     profile.maximumCoordinate, true, true};
  dialect.bareForms = customMacroBareForms();
  dialect.power = profile.hasPowerFunction ? PowerStyle::PowFunction : PowerStyle::ExpOfLn;
  dialect.statementOpcodes = macroStatementOpcodes();
  dialect.nurbs = profile.name == "m80" ? NurbsDialect::Mitsubishi : NurbsDialect::Fanuc;
  return dialect;
}

} // namespace cncc::backends
