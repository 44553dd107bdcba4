// The blocks of a TNC program below the statements: operands of address
// words and jumps (a number or one parameter; a formula goes to a scratch
// parameter first), labels and FN 9..12 jumps on IR conditions, and the
// motion blocks L, CC and C with modal words. A word already in force (the
// same literal, or the same IR value) is not written again; everything is
// forgotten where control flow joins (a label).
#pragma once

#include "heidenhain_formulas.h"

#include "cncc/ir/ir.h"

#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace cncc::backends {

// A coordinate word in force: a literal, or the IR value whose parameter it
// printed (SSA: one number while it is used; a label forgets every word).
struct TncWord {
  std::string text;
  std::optional<std::uint32_t> value; // none for a literal
  friend bool operator==(const TncWord&, const TncWord&) = default;
};

class TncBlockWriter {
public:
  TncBlockWriter(const TncFormulaWriter& formulas, const TncProfile& profile,
                 std::vector<std::string>& lines, std::vector<std::string>& errors)
      : formulas_(formulas), profile_(profile), lines_(lines), errors_(errors) {}

  // `+3.5`, `+QL4`, or `+QL495` after `QL495 = formula`; `coordinate`
  // rounds a number to the coordinate decimals. Scratch parameters are
  // free again after the next block that is not an assignment to one.
  std::string operand(ir::ValueId value, bool coordinate = false);
  // `target = formula` (or `FN 0: target = +n` for a number).
  void assign(const std::string& target, ir::ValueId value);

  // A scratch parameter for this statement.
  std::string scratch();
  // The scratch parameters are free again (at the start of each statement).
  void releaseScratch();

  int newLabel();
  void label(int number);
  void jump(int label);
  // Jumps to `label` when the bool value holds (or, jumpUnless, when not).
  void jumpIf(ir::ValueId condition, int label);
  void jumpUnless(ir::ValueId condition, int label);

  // Up first and down last: a rapid never moves sideways below where it
  // starts or ends; where the heights are not literals, Z goes first.
  void rapid(ir::ValueId x, ir::ValueId y, ir::ValueId z);
  // move.climb: `L Z.. R0 FMAX`, X and Y where they are.
  void climb(ir::ValueId z);
  void feed(ir::ValueId x, ir::ValueId y, ir::ValueId z, ir::ValueId feedRate);
  // move.arc: `CC IX.. IY..` (the centre from the start), then `C X.. Y..
  // DR-|DR+`, a helix with `IZ` the rise from the Z before it.
  void arc(bool clockwise, std::span<const ir::ValueId> operands);
  // move.polynomial: `SPL X.. Y.. Z.. K3X.. K2X.. K1X.. K3Y.. .. K1Z.. F..`,
  // every coordinate and coefficient written (the TNC needs K3 to K1 of
  // each axis it names).
  void spline(std::span<const ir::ValueId> operands);
  // `RL`, `RR` or `R0` on the next L block that moves in the plane (the
  // TNC switches radius compensation on and off on straight lines).
  void radiusCompensation(std::string word) { pendingRadius_ = std::move(word); }
  // An M function for the next motion block (M3 after a tool call).
  void beforeNextMove(std::string words) { pendingWords_ += " " + words; }
  // A block of its own for the pending M functions and `words`.
  void flushWords(std::string_view words = "");
  void forget();
  // The program keeps the tool's Z in a parameter (for helices after a
  // join): every move that changes Z sets it.
  void trackZ(int parameter) { zParameter_ = parameter; }

private:
  void block(std::string text);
  void compare(ir::ValueId condition, bool negated, int label);
  void comparison(int fn, ir::ValueId left, ir::ValueId right, int label);
  std::string word(char letter, ir::ValueId value, bool coordinate = true);
  std::string feedWord(ir::ValueId feedRate);
  void motion(std::string text, ir::ValueId z);

  const TncFormulaWriter& formulas_;
  const TncProfile& profile_;
  std::vector<std::string>& lines_;
  std::vector<std::string>& errors_;
  std::map<char, TncWord> words_; // in force since the last label
  std::string feed_;
  std::string pendingWords_;
  std::string pendingRadius_;
  std::optional<ir::ValueId> z_; // the value the last move left Z at
  int zParameter_ = -1;
  int nextScratch_ = 0;
  int nextLabel_ = 1;
};

} // namespace cncc::backends
