#include "cncc/backends/macro_program.h"

#include "macro_dialect.h"
#include "macro_inline_shape.h"
#include "macro_printer.h"

#include <fmt/format.h>

#include <algorithm>
#include <string>

namespace cncc::backends {

std::vector<int> macroParameterVariables(std::size_t parameterCount,
                                         const ControllerProfile& profile, bool inCommon,
                                         std::vector<std::string>& errors) {
  std::vector<int> candidates;
  if (inCommon) {
    for (const VariableRange& range : profile.retainedCommon) {
      for (int variable = range.first; variable <= range.last; ++variable) {
        candidates.push_back(variable);
      }
    }
  } else {
    for (const ArgumentLetter& argument : profile.argumentLetters) {
      candidates.push_back(argument.variable);
    }
    std::sort(candidates.begin(), candidates.end());
  }
  if (candidates.size() < parameterCount) {
    errors.push_back(fmt::format("the part has {} parameters, the controller has {} {} for them",
                                 parameterCount, candidates.size(),
                                 inCommon ? "retained common variables" : "argument letters"));
    candidates.resize(parameterCount, 0);
  }
  candidates.resize(parameterCount);
  return candidates;
}

ir::AllocationOptions macroAllocationOptions(const ControllerProfile& profile,
                                             std::vector<int> parameterVariables) {
  ir::AllocationOptions options;
  options.variables.push_back({profile.locals.first, profile.locals.last});
  for (const VariableRange& range : profile.volatileCommon) {
    options.variables.push_back({range.first, range.last});
  }
  for (const VariableRange& range : profile.retainedCommon) {
    options.variables.push_back({range.first, range.last});
  }
  options.parameterVariables = std::move(parameterVariables);
  options.maximumBracketDepth = profile.maximumBracketNesting;
  // Counted in characters (macroInlineShape with the profile), with room
  // for the addresses of a move or `#nnn=`; the printer checks every block's
  // real length.
  options.maximumInlineOperations = std::max(16, profile.maximumBlockLength - 20);
  options.maximumAssignmentOperations = std::max(16, profile.maximumBlockLength - 8);
  options.shape = [&profile](const ir::Function& function, const ir::Instruction& instruction,
                             std::span<const ir::InlineShape> operands) {
    return macroInlineShape(profile, function, instruction, operands);
  };
  // `#104` is four characters; before the variables are numbered, `#nn`.
  options.readCharacters = [](int variable) {
    return 1 + static_cast<int>(std::to_string(variable).size());
  };
  options.estimatedReadCharacters = 3;
  options.statementOpcodes = macroStatementOpcodes();
  // A curve's parameter u = i * c in the loop's variable, stepped by c:
  // one multiplication and one assignment fewer per point.
  options.stepScaledLoops = true;
  return options;
}

ir::LoweringOptions macroLoweringOptions(const ControllerProfile& profile, bool inches) {
  ir::LoweringOptions options;
  options.controllerLoops = true;
  options.literalSignificantDigits = profile.significantDigits;
  options.coordinateIncrement =
      inches ? profile.leastInputIncrement / 10 : profile.leastInputIncrement;
  options.maximumLoopNesting = std::min(profile.maximumLoopNesting, profile.maximumLoopIdentifier);
  options.compensationCornerArcs = true; // G39
  options.cornerArcsAfterLinesOnly = profile.cornerArcOnMoveBlock;
  options.passesBeforePrinting = macroPassesBeforePrinting();
  return options;
}

std::vector<std::string> macroPassesBeforePrinting() {
  return {"drop-pass-depths", "expand-whole-powers", "fold-finite"};
}

MacroProgram writeMacroProgram(const ir::Function& function, const ControllerProfile& profile,
                               const MacroProgramOptions& options) {
  MacroProgram program;
  if (options.programNumber < 1 || options.programNumber > profile.maximumProgramNumber) {
    program.errors.push_back(fmt::format("program number O{} is outside the controller's 1..{}",
                                         options.programNumber, profile.maximumProgramNumber));
    return program;
  }
  if (!profile.hasIndirectVariables && !function.tables.empty()) {
    program.errors.push_back(fmt::format("the part reads {} tables, and the controller has no "
                                         "indirect variables #[..] to read them",
                                         function.tables.size()));
    return program;
  }
  std::vector<int> parameterVariables = macroParameterVariables(
      function.parameters.size(), profile, options.parametersInCommon, program.errors);
  if (!program.errors.empty()) {
    return program;
  }
  MacroPrintOptions printOptions;
  printOptions.sourceName = options.sourceName;
  printOptions.partName = options.partName;
  printOptions.programNumber = options.programNumber;
  printOptions.inches = options.inches;
  printOptions.callable = options.callable;
  printOptions.parametersInCommon = options.parametersInCommon;
  printOptions.setup = &options.setup;
  printOptions.profile = &profile;
  ir::AllocationResult allocated =
      ir::allocateVariables(function, macroAllocationOptions(profile, parameterVariables));
  for (const ir::AllocationFailure& failure : allocated.failures) {
    program.errors.push_back(failure.message);
  }
  if (!program.errors.empty()) {
    return program;
  }
  // The printer checks every block's length as printed (the allocator
  // counts the expressions and the variables they read, with room for the
  // addresses).
  PrintedMacroProgram printed =
      MacroProgramPrinter(function, allocated.allocation, customMacroDialect(profile), printOptions,
                          program.errors)
          .print();
  program.lineOrigins = std::move(printed.lineOrigins);
  program.variables = std::move(printed.variables);
  if (!program.errors.empty()) {
    return program;
  }
  program.text = std::move(printed.text);
  program.statistics = measureMacroProgram(program.text);
  program.statistics.variables = static_cast<int>(allocated.allocation.usedVariables.size());
  return program;
}

} // namespace cncc::backends
