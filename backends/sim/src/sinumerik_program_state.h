// The state a running Sinumerik program keeps beside the machine's: its R
// parameters and its loops, and where a control block (IF, ELSE, FOR, ...,
// sinumerik_blocks.h) sends the run next.
#pragma once

#include "sinumerik_blocks.h"

#include <array>
#include <cstddef>
#include <map>
#include <string>

namespace cncc::backends::sinumerik {

class ProgramState {
public:
  // R0..R299 (the 828D's default count; the 840D's is a machine datum).
  static constexpr int parameterCount = 300;

  // The value of `expression` now. Throws ExpressionError.
  double evaluate(const std::string& expression) const;
  // A word's number, or its expression evaluated now. Throws ExpressionError
  // when it has neither.
  double valueOf(const SinumerikWord& word) const;
  // Rn; throws ExpressionError for a parameter that does not exist.
  double parameter(int number) const;
  void setParameter(int number, double value);

  // The index of the block after control block `at` of `unit`: IF and WHILE
  // go on or past their end, FOR counts its R parameter up by 1 to the end
  // value read when the loop began. Throws ExpressionError.
  std::size_t next(const SinumerikProgramUnit& unit, std::size_t at);

private:
  std::array<double, parameterCount> parameters_{};  // 0 at the start
  std::map<const SinumerikBlock*, double> loopEnds_; // FOR: the end value
};

} // namespace cncc::backends::sinumerik
