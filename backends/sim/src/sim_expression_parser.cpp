#include "sim_expression_parser.h"

#include <fmt/format.h>

#include <array>
#include <charconv>
#include <utility>

namespace cncc::backends::sim {

void BlockCursor::skipSpaces() {
  while (position_ < code_.size() && (code_[position_] == ' ' || code_[position_] == '\t')) {
    ++position_;
  }
}

bool BlockCursor::atEnd() {
  skipSpaces();
  return position_ >= code_.size();
}

char BlockCursor::peek() {
  skipSpaces();
  return position_ < code_.size() ? code_[position_] : '\0';
}

bool BlockCursor::consume(char expected) {
  if (peek() != expected) {
    return false;
  }
  ++position_;
  return true;
}

bool BlockCursor::consumeKeyword(std::string_view keyword) {
  skipSpaces();
  if (code_.substr(position_, keyword.size()) != keyword) {
    return false;
  }
  position_ += keyword.size();
  return true;
}

namespace {

// Two-letter abbreviations of macro words (backends/sim/README.md), read
// only where the profile says the control reads them: the full word is
// always tried first, so SIN is never read as SI + N.
struct Abbreviation {
  std::string_view word;
  std::string_view abbreviation;
};

constexpr std::array abbreviations = {
    Abbreviation{"WHILE", "WH"}, Abbreviation{"GOTO", "GO"}, Abbreviation{"END", "EN"},
    Abbreviation{"THEN", "TH"},  Abbreviation{"SIN", "SI"},  Abbreviation{"COS", "CO"},
    Abbreviation{"TAN", "TA"},   Abbreviation{"ASIN", "AS"}, Abbreviation{"ACOS", "AC"},
    Abbreviation{"ATAN", "AT"},  Abbreviation{"SQRT", "SQ"}, Abbreviation{"ABS", "AB"},
    Abbreviation{"ROUND", "RO"}, Abbreviation{"FIX", "FI"},  Abbreviation{"FUP", "FU"},
    Abbreviation{"EXP", "EX"},   Abbreviation{"AND", "AN"},  Abbreviation{"XOR", "XO"},
    Abbreviation{"MOD", "MO"}};

} // namespace

bool BlockCursor::consumeMacroWord(std::string_view word) {
  if (consumeKeyword(word)) {
    return true;
  }
  if (!abbreviations_) {
    return false;
  }
  for (const Abbreviation& entry : abbreviations) {
    if (entry.word == word) {
      return consumeKeyword(entry.abbreviation);
    }
  }
  return false;
}

namespace {

std::string_view abbreviationOf(std::string_view word) {
  for (const Abbreviation& entry : abbreviations) {
    if (entry.word == word) {
      return entry.abbreviation;
    }
  }
  return word;
}

} // namespace

std::optional<std::string_view> BlockCursor::abbreviationAhead() {
  skipSpaces();
  for (const Abbreviation& entry : abbreviations) {
    std::string_view ahead = code_.substr(position_, entry.abbreviation.size() + 1);
    if (ahead.size() > entry.abbreviation.size() &&
        ahead.substr(0, entry.abbreviation.size()) == entry.abbreviation &&
        !(ahead.back() >= 'A' && ahead.back() <= 'Z')) {
      return entry.word;
    }
  }
  return std::nullopt;
}

void BlockCursor::failOnAbbreviation() {
  if (abbreviations_) {
    return;
  }
  if (std::optional<std::string_view> word = abbreviationAhead()) {
    fail(fmt::format("'{}' abbreviates {}, read only where the machine file's [profile] sets "
                     "macro_word_abbreviations = true, and never in strict reading; write {}",
                     abbreviationOf(*word), *word, *word));
  }
}

void BlockCursor::expect(char expected, std::string_view what) {
  if (!consume(expected)) {
    char found = peek();
    fail(found == '\0' ? fmt::format("expected {} at the end of the block", what)
                       : fmt::format("expected {}, found '{}'", what, found));
  }
}

void BlockCursor::fail(const std::string& message) const {
  throw SimulationError(line_, std::string(lineText_), message);
}

void BlockCursor::openBracket() {
  ++bracketDepth_;
  if (bracketDepth_ > profile_.maximumBracketNesting) {
    fail(fmt::format("brackets nested {} deep; {} allows {}", bracketDepth_, profile_.name,
                     profile_.maximumBracketNesting));
  }
}

namespace {

bool isDigit(char c) {
  return c >= '0' && c <= '9';
}

Expression numberExpression(double value) {
  Expression expression;
  expression.number = value;
  return expression;
}

Expression binary(Operator op, Expression left, Expression right) {
  Expression expression;
  expression.kind = Expression::Kind::Binary;
  expression.op = op;
  expression.operands.push_back(std::move(left));
  expression.operands.push_back(std::move(right));
  return expression;
}

struct OperatorKeyword {
  std::string_view text;
  Operator op;
};

constexpr std::array comparisonKeywords = {
    OperatorKeyword{"EQ", Operator::Equal},          OperatorKeyword{"NE", Operator::NotEqual},
    OperatorKeyword{"GT", Operator::Greater},        OperatorKeyword{"LT", Operator::Less},
    OperatorKeyword{"GE", Operator::GreaterOrEqual}, OperatorKeyword{"LE", Operator::LessOrEqual}};

constexpr std::array additiveKeywords = {
    OperatorKeyword{"+", Operator::Add}, OperatorKeyword{"-", Operator::Subtract},
    OperatorKeyword{"OR", Operator::Or}, OperatorKeyword{"XOR", Operator::Xor}};

constexpr std::array multiplicativeKeywords = {
    OperatorKeyword{"*", Operator::Multiply}, OperatorKeyword{"/", Operator::Divide},
    OperatorKeyword{"AND", Operator::And}, OperatorKeyword{"MOD", Operator::Modulo}};

template <std::size_t count>
std::optional<Operator> consumeOperator(BlockCursor& cursor,
                                        const std::array<OperatorKeyword, count>& keywords) {
  for (const OperatorKeyword& keyword : keywords) {
    if (cursor.consumeMacroWord(keyword.text)) {
      return keyword.op;
    }
  }
  return std::nullopt;
}

struct FunctionKeyword {
  std::string_view text;
  Function function;
};

// Longer names first where one is a prefix of another.
constexpr std::array functionKeywords = {
    FunctionKeyword{"SIN", Function::Sin},     FunctionKeyword{"COS", Function::Cos},
    FunctionKeyword{"TAN", Function::Tan},     FunctionKeyword{"ASIN", Function::Asin},
    FunctionKeyword{"ACOS", Function::Acos},   FunctionKeyword{"ATAN", Function::ArcTangent},
    FunctionKeyword{"SQRT", Function::Sqrt},   FunctionKeyword{"ABS", Function::Abs},
    FunctionKeyword{"ROUND", Function::Round}, FunctionKeyword{"FIX", Function::Fix},
    FunctionKeyword{"FUP", Function::Fup},     FunctionKeyword{"LN", Function::Ln},
    FunctionKeyword{"EXP", Function::Exp},     FunctionKeyword{"POW", Function::Power}};

Expression parseUnary(BlockCursor& cursor);

// `[a, b]` of POW and the 30i's ATAN; the comma form only where the profile
// has the 30i functions.
Expression parseTwoArgumentCall(BlockCursor& cursor, Function function, std::string_view name) {
  if (!cursor.profile().hasPowerFunction) {
    cursor.fail(fmt::format("{}[a,b] is not available on {}", name, cursor.profile().name));
  }
  Expression call;
  call.kind = Expression::Kind::Call;
  call.function = function;
  cursor.expect('[', "'['");
  cursor.openBracket();
  call.operands.push_back(parseExpression(cursor));
  cursor.expect(',', "','");
  call.operands.push_back(parseExpression(cursor));
  cursor.expect(']', "']'");
  cursor.closeBracket();
  return call;
}

Expression arcTangent(Expression first, Expression second) {
  Expression call;
  call.kind = Expression::Kind::Call;
  call.function = Function::ArcTangent;
  call.operands.push_back(std::move(first));
  call.operands.push_back(std::move(second));
  return call;
}

// `ATAN[a]/[b]` everywhere; `ATAN[a,b]` only with the 30i functions; the
// one-argument form is refused because its range differs between controllers.
Expression parseArcTangent(BlockCursor& cursor) {
  cursor.expect('[', "'[' after ATAN");
  cursor.openBracket();
  Expression first = parseExpression(cursor);
  if (cursor.consume(',')) {
    if (!cursor.profile().hasPowerFunction) {
      cursor.fail(fmt::format("ATAN[a,b] is not available on {}; write ATAN[a]/[b]",
                              cursor.profile().name));
    }
    Expression second = parseExpression(cursor);
    cursor.expect(']', "']'");
    cursor.closeBracket();
    return arcTangent(std::move(first), std::move(second));
  }
  cursor.expect(']', "']'");
  cursor.closeBracket();
  if (!cursor.consume('/') || cursor.peek() != '[') {
    cursor.fail("a one-argument ATAN differs between controllers; write ATAN[a]/[b]");
  }
  Expression second = parseBracketed(cursor);
  return arcTangent(std::move(first), std::move(second));
}

std::optional<Expression> parseFunctionCall(BlockCursor& cursor) {
  for (const FunctionKeyword& keyword : functionKeywords) {
    if (!cursor.consumeMacroWord(keyword.text)) {
      continue;
    }
    if (keyword.function == Function::ArcTangent) {
      return parseArcTangent(cursor);
    }
    if (keyword.function == Function::Power) {
      return parseTwoArgumentCall(cursor, Function::Power, "POW");
    }
    if (cursor.peek() != '[') {
      cursor.fail(fmt::format("expected '[' after {}", keyword.text));
    }
    Expression call;
    call.kind = Expression::Kind::Call;
    call.function = keyword.function;
    call.operands.push_back(parseBracketed(cursor));
    return call;
  }
  return std::nullopt;
}

Expression parsePrimary(BlockCursor& cursor) {
  char next = cursor.peek();
  if (isDigit(next) || next == '.') {
    return numberExpression(parseNumber(cursor).value);
  }
  if (next == '#') {
    cursor.advance();
    Expression variable;
    variable.kind = Expression::Kind::Variable;
    variable.operands.push_back(parseVariableNumber(cursor));
    return variable;
  }
  if (next == '[') {
    return parseBracketed(cursor);
  }
  if (std::optional<Expression> call = parseFunctionCall(cursor)) {
    return std::move(*call);
  }
  cursor.failOnAbbreviation();
  cursor.fail(next == '\0' ? std::string("expected a value at the end of the block")
                           : fmt::format("expected a value, found '{}'", next));
}

Expression parseUnary(BlockCursor& cursor) {
  if (cursor.consume('-')) {
    Expression negation;
    negation.kind = Expression::Kind::Negate;
    negation.operands.push_back(parseUnary(cursor));
    return negation;
  }
  if (cursor.consume('+')) {
    return parseUnary(cursor);
  }
  return parsePrimary(cursor);
}

Expression parseTerm(BlockCursor& cursor) {
  Expression left = parseUnary(cursor);
  while (std::optional<Operator> op = consumeOperator(cursor, multiplicativeKeywords)) {
    left = binary(*op, std::move(left), parseUnary(cursor));
  }
  return left;
}

Expression parseAdditive(BlockCursor& cursor) {
  Expression left = parseTerm(cursor);
  while (std::optional<Operator> op = consumeOperator(cursor, additiveKeywords)) {
    left = binary(*op, std::move(left), parseTerm(cursor));
  }
  return left;
}

bool isComparison(Operator op) {
  return op == Operator::Equal || op == Operator::NotEqual || op == Operator::Greater ||
         op == Operator::Less || op == Operator::GreaterOrEqual || op == Operator::LessOrEqual;
}

bool isLogical(Operator op) {
  return op == Operator::And || op == Operator::Or || op == Operator::Xor;
}

// Whether `expression` is a truth value: a comparison, or truth values
// joined by AND, OR, XOR. Mixing a truth value with a number is an error.
bool isTruthValue(const Expression& expression, const BlockCursor& cursor) {
  if (expression.kind != Expression::Kind::Binary) {
    checkArithmetic(expression, cursor);
    return false;
  }
  if (isComparison(expression.op)) {
    checkArithmetic(expression.operands[0], cursor);
    checkArithmetic(expression.operands[1], cursor);
    return true;
  }
  if (isLogical(expression.op)) {
    bool left = isTruthValue(expression.operands[0], cursor);
    bool right = isTruthValue(expression.operands[1], cursor);
    if (left != right) {
      cursor.fail("AND, OR and XOR join two comparisons or two numbers, not one of each");
    }
    return left;
  }
  checkArithmetic(expression, cursor);
  return false;
}

} // namespace

NumberLiteral parseNumber(BlockCursor& cursor) {
  cursor.skipSpaces();
  std::string_view code = cursor.code();
  std::size_t start = cursor.position();
  std::size_t end = start;
  std::string digits;
  NumberLiteral literal;
  while (end < code.size() && (isDigit(code[end]) || (code[end] == '.' && !literal.hasPoint))) {
    if (code[end] == '.') {
      literal.hasPoint = true;
    } else {
      digits += code[end];
      literal.decimals += literal.hasPoint ? 1 : 0;
    }
    ++end;
  }
  if (digits.empty()) {
    cursor.fail("expected digits");
  }
  std::size_t firstSignificant = digits.find_first_not_of('0');
  int significant = firstSignificant == std::string::npos
                        ? 0
                        : static_cast<int>(digits.size() - firstSignificant);
  if (significant > cursor.profile().significantDigits) {
    cursor.fail(fmt::format("the constant '{}' has {} digits; {} allows {}",
                            code.substr(start, end - start), significant, cursor.profile().name,
                            cursor.profile().significantDigits));
  }
  std::string text(code.substr(start, end - start));
  if (text.back() == '.') {
    text.pop_back();
  }
  if (text.front() == '.') {
    text.insert(text.begin(), '0');
  }
  std::from_chars(text.data(), text.data() + text.size(), literal.value);
  while (cursor.position() < end) {
    cursor.advance();
  }
  return literal;
}

Expression parseExpression(BlockCursor& cursor) {
  Expression left = parseAdditive(cursor);
  if (std::optional<Operator> op = consumeOperator(cursor, comparisonKeywords)) {
    left = binary(*op, std::move(left), parseAdditive(cursor));
    if (consumeOperator(cursor, comparisonKeywords)) {
      cursor.fail("two comparisons in a row need brackets: [[a LT b] AND [b LT c]]");
    }
  }
  return left;
}

Expression parseBracketed(BlockCursor& cursor) {
  cursor.expect('[', "'['");
  cursor.openBracket();
  Expression inner = parseExpression(cursor);
  cursor.expect(']', "']'");
  cursor.closeBracket();
  return inner;
}

Expression parseVariableNumber(BlockCursor& cursor) {
  char next = cursor.peek();
  if (next == '[') {
    if (!cursor.profile().hasIndirectVariables) {
      cursor.fail(fmt::format("{} has no indirect variables #[...]", cursor.profile().name));
    }
    return parseBracketed(cursor);
  }
  if (!isDigit(next)) {
    cursor.fail("expected a variable number or '[' after '#'");
  }
  NumberLiteral literal = parseNumber(cursor);
  if (literal.hasPoint) {
    cursor.fail("a variable number has no decimal point");
  }
  return numberExpression(literal.value);
}

Expression parseAddressValue(BlockCursor& cursor, NumberLiteral* literal, bool& isLiteral) {
  isLiteral = false;
  bool negative = false;
  if (cursor.consume('-')) {
    negative = true;
  } else {
    cursor.consume('+');
  }
  char next = cursor.peek();
  Expression value;
  if (isDigit(next) || next == '.') {
    *literal = parseNumber(cursor);
    isLiteral = true;
    value = numberExpression(negative ? -literal->value : literal->value);
    return value;
  }
  if (next == '#') {
    cursor.advance();
    value.kind = Expression::Kind::Variable;
    value.operands.push_back(parseVariableNumber(cursor));
  } else if (next == '[') {
    value = parseBracketed(cursor);
  } else {
    cursor.fail(next == '\0' ? std::string("an address without a value")
                             : fmt::format("an address value cannot start with '{}'", next));
  }
  if (!negative) {
    return value;
  }
  Expression negation;
  negation.kind = Expression::Kind::Negate;
  negation.operands.push_back(std::move(value));
  return negation;
}

void checkArithmetic(const Expression& expression, const BlockCursor& cursor) {
  if (expression.kind == Expression::Kind::Binary && isComparison(expression.op)) {
    cursor.fail("a comparison can only be the condition of IF or WHILE");
  }
  for (const Expression& operand : expression.operands) {
    checkArithmetic(operand, cursor);
  }
}

void checkCondition(const Expression& expression, const BlockCursor& cursor) {
  if (!isTruthValue(expression, cursor)) {
    cursor.fail("the condition is not a comparison (EQ, NE, GT, LT, GE, LE)");
  }
}

bool containsFunction(const Expression& expression, Function function) {
  if (expression.kind == Expression::Kind::Call && expression.function == function) {
    return true;
  }
  for (const Expression& operand : expression.operands) {
    if (containsFunction(operand, function)) {
      return true;
    }
  }
  return false;
}

} // namespace cncc::backends::sim
