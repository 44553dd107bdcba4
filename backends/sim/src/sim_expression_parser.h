// The expression grammar of Custom Macro B, shared by the block reader:
//
//   comparison := additive [ (EQ|NE|GT|LT|GE|LE) additive ]
//   additive   := term { (+ | - | OR | XOR) term }
//   term       := unary { (* | / | AND | MOD) unary }
//   unary      := [+|-] unary | primary
//   primary    := number | #digits | #[e] | [e] | FUNCTION[e] | ATAN[e]/[e]
//
// Spaces between tokens are ignored, as controllers do. Every `[` counts
// against the profile's bracket nesting limit.
#pragma once

#include "cncc/backends/controller_profile.h"
#include "cncc/backends/sim_program.h"

#include <optional>
#include <string>
#include <string_view>

namespace cncc::backends::sim {

// A position in the code of one block (the line without its comments).
class BlockCursor {
public:
  BlockCursor(std::string_view code, int line, std::string_view lineText,
              const ControllerProfile& profile, bool abbreviations = false)
      : code_(code), line_(line), lineText_(lineText), profile_(profile),
        abbreviations_(abbreviations) {}

  void skipSpaces();
  bool atEnd();
  char peek(); // after skipping spaces; '\0' at the end
  bool consume(char expected);
  // Consumes `keyword` when the code continues with it.
  bool consumeKeyword(std::string_view keyword);
  // Consumes the macro word `word` (WHILE, SIN, AND, ...), or its two-letter
  // abbreviation when the reading rules accept abbreviations.
  bool consumeMacroWord(std::string_view word);
  // Fails, naming the word, when the code continues with the abbreviation of
  // a macro word (WH[...) that these reading rules do not accept.
  void failOnAbbreviation();
  void expect(char expected, std::string_view what);
  [[noreturn]] void fail(const std::string& message) const;

  void openBracket();
  void closeBracket() { --bracketDepth_; }
  const ControllerProfile& profile() const { return profile_; }
  std::size_t position() const { return position_; }
  std::string_view code() const { return code_; }
  void advance() { ++position_; }

private:
  // The full word when the code continues with an abbreviation (WH, SI, ...).
  std::optional<std::string_view> abbreviationAhead();

  std::string_view code_;
  std::size_t position_ = 0;
  int line_;
  std::string_view lineText_;
  const ControllerProfile& profile_;
  bool abbreviations_;
  int bracketDepth_ = 0;
};

struct NumberLiteral {
  double value = 0;
  bool hasPoint = false;
  int decimals = 0;
};

// Digits with an optional decimal point, no sign.
NumberLiteral parseNumber(BlockCursor& cursor);
// A comparison or an arithmetic expression; see checkArithmetic/checkCondition.
Expression parseExpression(BlockCursor& cursor);
// `[ expression ]`.
Expression parseBracketed(BlockCursor& cursor);
// What follows `#`: digits or `[expression]`.
Expression parseVariableNumber(BlockCursor& cursor);
// An operand without binary operators, as an address takes it: `[+|-]`
// then a number, `#n`, `#[e]` or `[e]`.
Expression parseAddressValue(BlockCursor& cursor, NumberLiteral* literal, bool& isLiteral);

// Comparisons belong only to IF and WHILE conditions.
void checkArithmetic(const Expression& expression, const BlockCursor& cursor);
// A condition: a comparison, or comparisons joined by AND, OR, XOR.
void checkCondition(const Expression& expression, const BlockCursor& cursor);
bool containsFunction(const Expression& expression, Function function);

} // namespace cncc::backends::sim
