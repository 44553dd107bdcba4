// Reads a TNC conversational program block by block: `n BEGIN PGM ..`,
// the blocks numbered from 0 in steps of 1, `n END PGM ..` last.
#include "tnc_program_text.h"

#include <fmt/format.h>

#include <array>
#include <charconv>
#include <cmath>

namespace cncc::backends::heidenhain {

namespace {

std::vector<std::string_view> wordsOf(std::string_view text) {
  std::vector<std::string_view> words;
  std::size_t position = 0;
  while (position < text.size()) {
    while (position < text.size() && text[position] == ' ') {
      ++position;
    }
    std::size_t end = text.find(' ', position);
    end = end == std::string_view::npos ? text.size() : end;
    if (end > position) {
      words.push_back(text.substr(position, end - position));
    }
    position = end;
  }
  return words;
}

std::optional<int> wholeNumber(std::string_view text) {
  int value = 0;
  auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || error != std::errc() || end != text.data() + text.size()) {
    return std::nullopt;
  }
  return value;
}

void collectParameters(const TncExpression& expression, std::vector<int>& parameters) {
  if (expression.kind == TncExpression::Kind::Parameter) {
    parameters.push_back(expression.parameter);
  }
  for (const TncExpression& operand : expression.operands) {
    collectParameters(operand, parameters);
  }
}

class BlockReader {
public:
  BlockReader(TncBlock& block, std::string_view content) : block_(block), content_(content) {}

  void read() {
    std::vector<std::string_view> words = wordsOf(content_);
    if (words.empty()) {
      fail("an empty block");
    }
    std::string_view first = words[0];
    if (first == "BEGIN" || first == "END") {
      readProgramMark(words);
    } else if (first == "BLK") {
      block_.kind = TncBlock::Kind::BlankForm;
    } else if (first == "TOOL") {
      readToolCall(words);
    } else if (first == "L" || first == "C" || first == "CC") {
      readMotion(words);
    } else if (first == "SPL") {
      readSpline(words);
    } else if (first == "LBL") {
      readLabel(words);
    } else if (first == "CALL") {
      readCall(words);
    } else if (first == "FN") {
      readFunction();
    } else if (first == "CYCL") {
      readCycle(words);
    } else if (first.starts_with('Q') && content_.find('=') != std::string_view::npos) {
      readFormula();
    } else {
      fail(fmt::format("'{}' is no block the model knows", first));
    }
    for (const std::optional<TncAxisWord>* axis : {&block_.x, &block_.y, &block_.z}) {
      if (*axis) {
        collectParameters((*axis)->value, block_.parametersNamed);
      }
    }
    for (const std::optional<TncExpression>* value : {&block_.feed, &block_.speed}) {
      if (*value) {
        collectParameters(**value, block_.parametersNamed);
      }
    }
    collectParameters(block_.value, block_.parametersNamed);
    collectParameters(block_.right, block_.parametersNamed);
  }

private:
  [[noreturn]] void fail(const std::string& message) const {
    throw TncProgramError(block_.line, message);
  }

  int number(std::string_view text, std::string_view what) const {
    std::optional<int> value = wholeNumber(text);
    if (!value || *value < 0) {
      fail(fmt::format("'{}' is no {}", text, what));
    }
    return *value;
  }

  void readProgramMark(const std::vector<std::string_view>& words) {
    if (words.size() != 4 || words[1] != "PGM" || (words[3] != "MM" && words[3] != "INCH")) {
      fail("expected BEGIN PGM NAME MM|INCH or END PGM NAME MM|INCH");
    }
    block_.kind = words[0] == "BEGIN" ? TncBlock::Kind::Begin : TncBlock::Kind::End;
    block_.inches = words[3] == "INCH";
  }

  void readToolCall(const std::vector<std::string_view>& words) {
    if (words.size() < 2 || words[1] != "CALL") {
      fail("expected TOOL CALL");
    }
    block_.kind = TncBlock::Kind::ToolCall;
    for (std::size_t i = 2; i < words.size(); ++i) {
      std::string_view word = words[i];
      if (word == "Z") {
        continue;
      }
      if (word == "X" || word == "Y") {
        fail("the model mills with the tool along Z only");
      }
      if (word.starts_with('S')) {
        block_.speed = parseTncOperand(word.substr(1), block_.line);
      } else if (i == 2) {
        block_.tool = number(word, "tool number");
      } else {
        fail(fmt::format("'{}' is no word of TOOL CALL the model knows", word));
      }
    }
  }

  void readMotion(const std::vector<std::string_view>& words) {
    block_.kind = words[0] == "L"   ? TncBlock::Kind::Line
                  : words[0] == "C" ? TncBlock::Kind::Circle
                                    : TncBlock::Kind::CircleCentre;
    bool centre = block_.kind == TncBlock::Kind::CircleCentre;
    for (std::size_t i = 1; i < words.size(); ++i) {
      std::string_view word = words[i];
      bool incremental = word.size() > 1 && word[0] == 'I';
      std::string_view address = incremental ? word.substr(1) : word;
      char letter = address[0];
      if ((letter == 'X' || letter == 'Y' || letter == 'Z') && address.size() > 1) {
        std::optional<TncAxisWord>& axis = letter == 'X'   ? block_.x
                                           : letter == 'Y' ? block_.y
                                                           : block_.z;
        if (axis) {
          fail(fmt::format("{} twice in one block", letter));
        }
        axis = TncAxisWord{parseTncOperand(address.substr(1), block_.line), incremental};
      } else if (centre) {
        fail(fmt::format("'{}' is no word of CC", word));
      } else if (word == "FMAX") {
        block_.rapid = true;
      } else if (word.starts_with('F') && word.size() > 1) {
        block_.feed = parseTncOperand(word.substr(1), block_.line);
      } else if (word == "R0" || word == "RL" || word == "RR") {
        if (block_.radiusCompensation) {
          fail("two radius compensation words in one block");
        }
        block_.radiusCompensation = word[1];
      } else if ((word == "DR+" || word == "DR-") && block_.kind == TncBlock::Kind::Circle) {
        block_.clockwise = word == "DR-";
      } else if (word.starts_with('M')) {
        block_.mFunctions.push_back(number(word.substr(1), "M function"));
      } else {
        fail(fmt::format("'{}' is no word of {} the model knows", word, words[0]));
      }
    }
  }

  // `SPL X.. Y.. Z.. K3X.. K2X.. K1X.. K3Y.. .. F..`: absolute end
  // coordinates; a coefficient may be followed by an exponent word `E+2`.
  void readSpline(const std::vector<std::string_view>& words) {
    block_.kind = TncBlock::Kind::Spline;
    std::optional<double>* last = nullptr;
    for (std::size_t i = 1; i < words.size(); ++i) {
      std::string_view word = words[i];
      char letter = word[0];
      if ((letter == 'X' || letter == 'Y' || letter == 'Z') && word.size() > 1) {
        std::optional<TncAxisWord>& axis = letter == 'X'   ? block_.x
                                           : letter == 'Y' ? block_.y
                                                           : block_.z;
        if (axis) {
          fail(fmt::format("{} twice in one block", letter));
        }
        axis = TncAxisWord{parseTncOperand(word.substr(1), block_.line), false};
      } else if (letter == 'K' && word.size() > 3 && word[1] >= '1' && word[1] <= '3' &&
                 (word[2] == 'X' || word[2] == 'Y' || word[2] == 'Z')) {
        int axis = word[2] - 'X';
        std::optional<double>& coefficient = block_.splineCoefficients[axis]['3' - word[1]];
        if (coefficient) {
          fail(fmt::format("{} twice in one block", word.substr(0, 3)));
        }
        coefficient = decimal(word.substr(3));
        last = &coefficient;
      } else if (letter == 'E' && word.size() > 1 && last != nullptr) {
        std::optional<int> exponent = wholeNumber(word.substr(word[1] == '+' ? 2 : 1));
        if (!exponent || *exponent < -255 || *exponent > 255) {
          fail(fmt::format("'{}' is no exponent of -255 to +255", word));
        }
        **last *= std::pow(10.0, *exponent);
        last = nullptr;
      } else if (word.starts_with('F') && word.size() > 1) {
        block_.feed = parseTncOperand(word.substr(1), block_.line);
      } else if (word.starts_with('M')) {
        block_.mFunctions.push_back(number(word.substr(1), "M function"));
      } else {
        fail(fmt::format("'{}' is no word of SPL the model knows", word));
      }
    }
  }

  double decimal(std::string_view text) const {
    TncExpression operand = parseTncOperand(text, block_.line);
    bool negated = operand.kind == TncExpression::Kind::Negation;
    const TncExpression& number = negated ? operand.operands[0] : operand;
    if (number.kind != TncExpression::Kind::Number) {
      fail(fmt::format("'{}' is no number for a spline coefficient", text));
    }
    return negated ? -number.number : number.number;
  }

  void readLabel(const std::vector<std::string_view>& words) {
    if (words.size() != 2) {
      fail("expected LBL n");
    }
    block_.kind = TncBlock::Kind::Label;
    block_.label = number(words[1], "label number");
  }

  void readCall(const std::vector<std::string_view>& words) {
    if (words.size() < 3 || words[1] != "LBL" || (words.size() != 3 && words.size() != 5) ||
        (words.size() == 5 && words[3] != "REP")) {
      fail("expected CALL LBL n or CALL LBL n REP k");
    }
    block_.kind = TncBlock::Kind::CallLabel;
    block_.label = number(words[2], "label number");
    if (block_.label == 0) {
      fail("CALL LBL 0: label 0 ends a subprogram");
    }
    if (words.size() == 5) {
      block_.repeat = number(words[4], "repeat count");
    }
  }

  void readCycle(const std::vector<std::string_view>& words) {
    bool tolerance = words.size() >= 3 && words[1] == "DEF" &&
                     ((words[2] == "32.0" && words.size() == 4 && words[3] == "TOLERANCE") ||
                      (words[2] == "32.1" && words.size() <= 4));
    if (!tolerance) {
      fail("the model knows cycle 32 TOLERANCE only");
    }
    block_.kind = TncBlock::Kind::Tolerance;
  }

  std::pair<int, std::string_view> target(std::string_view text) const {
    std::size_t equals = text.find('=');
    if (equals == std::string_view::npos) {
      fail("expected Qn = ...");
    }
    std::string_view name = text.substr(0, equals);
    while (!name.empty() && name.back() == ' ') {
      name.remove_suffix(1);
    }
    while (!name.empty() && name.front() == ' ') {
      name.remove_prefix(1);
    }
    TncExpression parameter = parseTncOperand(name, block_.line);
    if (parameter.kind != TncExpression::Kind::Parameter || name.starts_with('+')) {
      fail(fmt::format("'{}' is no Q parameter to assign", name));
    }
    return {parameter.parameter, text.substr(equals + 1)};
  }

  void readFormula() {
    block_.kind = TncBlock::Kind::Assign;
    auto [parameter, formula] = target(content_);
    block_.target = parameter;
    block_.parametersNamed.push_back(parameter);
    block_.value = parseTncFormula(formula, block_.line);
  }

  void readFunction() {
    std::size_t colon = content_.find(':');
    if (colon == std::string_view::npos) {
      fail("expected FN n: ...");
    }
    std::vector<std::string_view> head = wordsOf(content_.substr(0, colon));
    if (head.size() != 2) {
      fail("expected FN n: ...");
    }
    int function = number(head[1], "FN number");
    std::string_view rest = content_.substr(colon + 1);
    std::vector<std::string_view> words = wordsOf(rest);
    if (function >= 0 && function <= 4) {
      readArithmetic(function, rest);
    } else if (function >= 9 && function <= 12) {
      readJump(function, words);
    } else if (function == 14) {
      if (words.size() != 3 || words[0] != "ERROR" || words[1] != "=") {
        fail("expected FN 14: ERROR = n");
      }
      block_.kind = TncBlock::Kind::Error;
      block_.errorNumber = number(words[2], "error number");
    } else {
      fail(fmt::format("FN {} is not modelled", function));
    }
  }

  void readArithmetic(int function, std::string_view text) {
    block_.kind = TncBlock::Kind::Assign;
    auto [parameter, expression] = target(text);
    block_.target = parameter;
    block_.parametersNamed.push_back(parameter);
    std::vector<std::string_view> words = wordsOf(expression);
    static constexpr std::array<std::string_view, 5> operators = {"", "+", "-", "*", "DIV"};
    if (function == 0) {
      if (words.size() != 1) {
        fail("expected FN 0: Qn = value");
      }
      block_.value = parseTncOperand(words[0], block_.line);
      return;
    }
    if (words.size() != 3 || words[1] != operators[function]) {
      fail(fmt::format("expected FN {}: Qn = a {} b", function, operators[function]));
    }
    block_.value.kind = TncExpression::Kind::Binary;
    block_.value.op = "+-*/"[function - 1];
    block_.value.operands = {parseTncOperand(words[0], block_.line),
                             parseTncOperand(words[2], block_.line)};
  }

  void readJump(int function, const std::vector<std::string_view>& words) {
    static constexpr std::array<std::string_view, 4> names = {"EQU", "NE", "GT", "LT"};
    if (words.size() != 7 || words[0] != "IF" || words[2] != names[function - 9] ||
        words[4] != "GOTO" || words[5] != "LBL") {
      fail(fmt::format("expected FN {}: IF a {} b GOTO LBL n", function, names[function - 9]));
    }
    block_.kind = TncBlock::Kind::Jump;
    block_.comparison = function;
    block_.value = parseTncOperand(words[1], block_.line);
    block_.right = parseTncOperand(words[3], block_.line);
    block_.label = number(words[6], "label number");
  }

  TncBlock& block_;
  std::string_view content_;
};

} // namespace

std::vector<TncBlock> readTncProgram(std::string_view text) {
  std::vector<TncBlock> blocks;
  int line = 0;
  while (!text.empty()) {
    std::size_t newline = text.find('\n');
    std::string_view row = text.substr(0, newline);
    text = newline == std::string_view::npos ? "" : text.substr(newline + 1);
    ++line;
    if (row.ends_with('\r')) {
      row.remove_suffix(1);
    }
    if (row.find_first_not_of(' ') == std::string_view::npos) {
      continue;
    }
    TncBlock block;
    block.line = line;
    block.text = std::string(row);
    std::size_t space = row.find(' ');
    std::optional<int> number = wholeNumber(row.substr(0, space));
    if (!number || *number != static_cast<int>(blocks.size())) {
      throw TncProgramError(line, fmt::format("expected block number {}", blocks.size()));
    }
    std::string_view content = space == std::string_view::npos ? "" : row.substr(space + 1);
    std::size_t comment = content.find(';');
    std::string_view code = content.substr(0, comment);
    if (content.starts_with('*')) {
      block.kind = TncBlock::Kind::Comment; // `* - structure`
    } else if (code.find_first_not_of(' ') == std::string_view::npos) {
      if (comment == std::string_view::npos) {
        throw TncProgramError(line, "an empty block");
      }
      block.kind = TncBlock::Kind::Comment; // `; text`
    } else {
      BlockReader(block, code).read();
    }
    blocks.push_back(std::move(block));
  }
  return blocks;
}

} // namespace cncc::backends::heidenhain
