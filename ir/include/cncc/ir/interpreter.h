// Runs a Function for given parameter values and records the tool path.
#pragma once

#include "cncc/ir/ir.h"
#include "cncc/ir/tool_path.h"

#include <map>
#include <stdexcept>
#include <string>

namespace cncc::ir {

// A run that cannot finish: a table index out of range, a loop bound that
// is not finite, or more work than `maximumSteps`.
class InterpreterError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

struct InterpreterOptions {
  // Values of the function's parameters by name; missing ones take their
  // defaults.
  std::map<std::string, double> parameters;
  std::size_t maximumSteps = 200'000'000;
};

ToolPath interpret(const Function& function, const InterpreterOptions& options = {});

} // namespace cncc::ir
