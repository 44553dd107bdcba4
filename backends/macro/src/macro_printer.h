// The one printer of the macro dialects (Fanuc, M80, LinuxCNC): the IR with
// controller loops, ifs, values in controller variables, moves and set-up
// ops, as a program of the dialect its MacroDialect table describes.
// writeMacroProgram and writeLinuxcncProgram allocate the variables and
// call it; the sources are macro_printer.cpp (the program and its control
// flow), macro_printer_header.cpp (header, parameters, tables) and
// macro_printer_statements.cpp (assignments, tools, NURBS).
#pragma once

#include "macro_dialect.h"
#include "macro_expressions.h"
#include "modal_moves.h"

#include "cncc/backends/line_spans.h"
#include "cncc/backends/machine_setup.h"
#include "cncc/backends/macro_program.h"
#include "cncc/ir/ir.h"
#include "cncc/ir/register_allocation.h"

#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace cncc::backends {

struct MacroPrintOptions {
  std::string sourceName; // for the header comment, e.g. "s_profile.cdl"
  std::string partName;
  int programNumber = 0;
  std::string subroutineName; // `{name}` in the dialect's frame
  bool inches = false;
  bool callable = false;
  bool parametersInCommon = false;
  std::string blend; // {blend} in the start blocks
  const MachineSetup* setup = nullptr;
  // The G65 argument letters (CallStyle::ArgumentLetters).
  const ControllerProfile* profile = nullptr;
  // The part's parameters' names where the dialect names them.
  std::vector<std::string> parameterNames;
};

struct PrintedMacroProgram {
  std::string text;
  LineOrigins lineOrigins; // of each line of text
  std::map<int, VariableMeaning> variables;
};

class MacroProgramPrinter {
public:
  MacroProgramPrinter(const ir::Function& function, const ir::Allocation& allocation,
                      const MacroDialect& dialect, const MacroPrintOptions& options,
                      std::vector<std::string>& errors)
      : function_(function), allocation_(allocation), dialect_(dialect), options_(options),
        errors_(errors),
        expressions_(function, allocation, dialect, options.parameterNames, errors),
        moves_(expressions_, lines_), nextLabel_(dialect.firstLabel) {}

  PrintedMacroProgram print();

private:
  // Lines printed aside (a loop body, a branch) before they are placed,
  // with the CDL span of each.
  struct Captured {
    std::vector<std::string> lines;
    std::vector<LineOrigin> origins;
  };

  // ---- lines (macro_printer.cpp)
  void line(std::string text) { lines_.push_back(std::move(text)); }
  std::string commentText(std::string_view text) const;
  void comment(std::string_view text) { line(commentText(text)); }
  // The header's own words, upper-cased where the dialect's comments are.
  std::string keyword(std::string_view words) const;
  // `{number}` and `{name}` of a frame line.
  std::string frameLine(const std::string& pattern) const;
  std::string assignment(const std::string& target, const std::string& value) const {
    return target + dialect_.assignment + value;
  }
  PrintedMacroProgram finish();

  // ---- header, parameters, tables (macro_printer_header.cpp)
  std::string parameterDefault(std::size_t index) const;
  void printHeader();
  void printCallComment();
  void noteVariable(int variable, const std::string& upperMeaning, frontend::SourceSpan span);
  void printValueVariables();
  void printParameters();
  void printFixedParameterChecks();
  std::string alarmStatement(std::string_view text, std::size_t reserved) const;
  void printTables();

  // ---- control flow (macro_printer.cpp)
  int newLabel();
  // `IF [c] THEN statement`, a jump over it where THEN is missing, or
  // `o1 if [c]` statement `o1 endif`.
  void conditional(const std::string& condition, const std::string& negatedCondition,
                   const std::string& statement);
  // `target` = whenTrue where the condition holds, whenFalse where not.
  void choose(const std::string& condition, const std::string& negatedCondition,
              const std::string& target, const std::string& whenTrue, const std::string& whenFalse);
  void printRegion(const ir::Region& region);
  void printInstruction(const ir::Instruction& instruction);
  void printLoop(const ir::Instruction& instruction);
  void openLoop(const ir::Instruction& instruction, const std::string& index, int label);
  void stepLoop(const ir::Instruction& instruction, const std::string& index);
  Captured loopBody(const ir::Instruction& instruction);
  void printIf(const ir::Instruction& instruction);
  void printOWordIf(const ir::Instruction& instruction);
  Captured capture(const ir::Region& region, const ModalState& entry);
  Captured capture(const ir::Region& region);
  Captured captureLines(const ir::Region& region);
  void append(const Captured& captured);

  // ---- statements (macro_printer_statements.cpp)
  void printAssignment(const ir::Instruction& instruction);
  void printMinMax(const ir::Instruction& instruction, const std::string& target);
  void printFloorCeil(const ir::Instruction& instruction, const std::string& target);
  void printRemainder(const ir::Instruction& instruction, const std::string& target);
  void printArctangent(const ir::Instruction& instruction, const std::string& target);
  void printSpindle(const ir::Instruction& instruction);
  void printTool(const ir::Instruction& instruction);
  std::string compensationWords(const ir::Instruction& instruction);
  void printCornerArc(const ir::Instruction& instruction);
  void printNurbs(const ir::Instruction& instruction);

  const ir::Function& function_;
  const ir::Allocation& allocation_;
  const MacroDialect& dialect_;
  const MacroPrintOptions& options_;
  std::vector<std::string>& errors_;
  MacroExpressionWriter expressions_;
  std::vector<std::string> lines_;
  ModalMoveWriter moves_;
  std::map<int, VariableMeaning> variableMeanings_;
  int loopDepth_ = 0;
  bool reportedLoopDepth_ = false;
  int nextLabel_;
  bool spindleOn_ = false;
  long long toolNumber_ = 0; // of the last tool change
  LineSpans lineSpans_;
  LineOrigin currentOrigin_;
  std::vector<ControllerLoop> loops_; // every loop printed
};

} // namespace cncc::backends
