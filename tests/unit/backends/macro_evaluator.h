// A tiny evaluator of the Custom Macro B subset the macro printer writes,
// for tests only: variables (vacant reads as 0 in arithmetic), + - * / with
// precedence, brackets, SIN COS TAN ASIN ACOS (degrees) ATAN[a]/[b] SQRT ABS
// EXP LN ROUND FIX FUP, #[..], WHILE/DO/END, IF THEN, IF GOTO, GOTO, and
// G0/G1 X Y Z F words. It records where the tool goes. The real virtual
// controller (backends/sim) is the reference; this only checks that the
// printed program means what the IR means.
#pragma once

#include <map>
#include <string>
#include <vector>

namespace cncc::testing {

struct EvaluatedMove {
  bool rapid = false;
  double x = 0, y = 0, z = 0, feed = 0;
};

struct MacroEvaluation {
  std::vector<EvaluatedMove> moves;
  std::map<int, double> variables;
  std::string error; // empty when the program ran to M30/M99
};

MacroEvaluation evaluateMacroProgram(const std::string& text,
                                     const std::map<int, double>& arguments = {});

} // namespace cncc::testing
