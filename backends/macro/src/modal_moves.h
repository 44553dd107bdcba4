// The motion blocks of a macro program: G0/G1/G2/G3 with modal words, a
// word already in force not written again. What is in force is ModalState;
// the printer saves, joins and forgets it where control flow joins.
#pragma once

#include "macro_expressions.h"

#include "cncc/ir/ir.h"

#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace cncc::backends {

// A word in force: a literal, or the IR value it printed (SSA: the same
// value is the same number while it is used, its variable is not reused).
struct ModalWord {
  std::string text;
  std::optional<std::uint32_t> value; // none for a literal
  friend bool operator==(const ModalWord&, const ModalWord&) = default;
};

// The words a move printed last. Where control flow joins only what both
// ways agree on is kept (a loop: what holds at its entry and after its body).
struct ModalState {
  std::string motion;
  std::map<char, ModalWord> words;
  std::optional<double> z; // the last literal Z, to order a rapid's axes
  void forget() { *this = ModalState{}; }
  ModalState agreedWith(const ModalState& other) const;
  friend bool operator==(const ModalState&, const ModalState&) = default;
};

class ModalMoveWriter {
public:
  ModalMoveWriter(const MacroExpressionWriter& expressions, std::vector<std::string>& lines)
      : expressions_(expressions), lines_(lines) {}

  // Up first and down last, so a rapid never moves sideways below where it
  // starts or ends; where the heights are not literals, Z goes first (the
  // lowering's rapids climb to the safe height).
  void rapid(ir::ValueId x, ir::ValueId y, ir::ValueId z);
  // move.climb: `G0 Z..`, X and Y where they are.
  void climb(ir::ValueId z);
  void feed(ir::ValueId x, ir::ValueId y, ir::ValueId z, ir::ValueId feedRate);
  // move.arc: G2/G3 with X and Y always (a full turn ends where it starts),
  // Z when it changes (a helix), the centre's I J from the start always.
  void arc(bool clockwise, std::span<const ir::ValueId> operands);
  // " X12.5", or nothing when that word is in force already (a computed
  // word too: its SSA value is one number while it is used).
  std::string word(char letter, ir::ValueId value, bool isCoordinate = true);
  // Words the next move with a Z word carries (the length offset after a
  // tool change).
  void beforeNextZ(std::string words) { beforeZ_ = std::move(words); }
  // Words the next feed move in the plane carries (G41/G42 D.. or G40: the
  // controls switch cutter radius compensation on and off on such a move).
  void beforeNextPlaneMove(std::string words) { beforePlane_ = std::move(words); }
  ModalState& state() { return modal_; }
  void forget() { modal_.forget(); }

private:
  std::string zWord(ir::ValueId z);
  // One motion block: `G1 X.. Y.. F..`, the motion word left out when in
  // force, nothing when no word is left.
  void block(std::string_view motion, const std::string& words);

  const MacroExpressionWriter& expressions_;
  std::vector<std::string>& lines_;
  ModalState modal_;
  std::string beforeZ_;
  std::string beforePlane_;
};

} // namespace cncc::backends
