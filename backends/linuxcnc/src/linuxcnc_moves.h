// The motion lines of a LinuxCNC program: G0/G1 with modal words. A literal
// word already in force is not written again; anything computed is always
// written (a parameter may have changed), and everything is forgotten where
// control flow joins. Every motion line goes through motionLine(), so that
// another motion (an arc) is one more caller of it.
#pragma once

#include "linuxcnc_expressions.h"

#include "cncc/ir/ir.h"

#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace cncc::backends {

class LinuxcncMoveWriter {
public:
  LinuxcncMoveWriter(const LinuxcncExpressionWriter& expressions, std::vector<std::string>& lines)
      : expressions_(expressions), lines_(lines) {}

  // Up first and down last, so a rapid never moves sideways below where it
  // starts or ends; where the heights are not literals, Z goes first (the
  // lowering's rapids climb to the safe height).
  void rapid(ir::ValueId x, ir::ValueId y, ir::ValueId z);
  void feed(ir::ValueId x, ir::ValueId y, ir::ValueId z, ir::ValueId feedRate);
  // move.arc: G2/G3 with X and Y always (a full turn ends where it starts),
  // Z when it changes (a helix), the centre's I J from the start always.
  void arc(bool clockwise, std::span<const ir::ValueId> operands);
  void forget();
  // Words the next move with a Z word carries (the length offset after a
  // tool change).
  void beforeNextZ(std::string words) { beforeZ_ = std::move(words); }

private:
  std::string zWord(ir::ValueId z);
  // One motion line: `G1 X.. Y.. F..`, the motion word left out when in
  // force, nothing when no word is left.
  void motionLine(std::string_view motion, const std::string& words);
  // " X12.5", or nothing when that literal is in force already.
  std::string word(char letter, ir::ValueId value, bool isCoordinate = true);

  const LinuxcncExpressionWriter& expressions_;
  std::vector<std::string>& lines_;
  std::string motion_;
  std::string beforeZ_;
  std::map<char, std::string> literals_;
  std::optional<double> z_; // the last literal Z
};

} // namespace cncc::backends
