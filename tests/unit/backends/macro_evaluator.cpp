#include "macro_evaluator.h"

#include <cctype>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>
#include <stdexcept>

namespace cncc::testing {

namespace {

constexpr double vacant = std::numeric_limits<double>::quiet_NaN();
constexpr double degree = std::numbers::pi / 180;

double arithmetic(double value) {
  return std::isnan(value) ? 0 : value;
}

class Evaluator {
public:
  explicit Evaluator(const std::map<int, double>& arguments) : variables_(arguments) {}

  MacroEvaluation run(const std::string& text) {
    std::istringstream stream(text);
    for (std::string line; std::getline(stream, line);) {
      lines_.push_back(withoutComments(line));
    }
    MacroEvaluation evaluation;
    try {
      execute();
    } catch (const std::exception& error) {
      evaluation.error = error.what();
    }
    evaluation.moves = std::move(moves_);
    evaluation.variables = variables_;
    return evaluation;
  }

private:
  static std::string withoutComments(const std::string& line) {
    std::string out;
    int depth = 0;
    for (char c : line) {
      depth += c == '(' ? 1 : 0;
      if (depth == 0) {
        out += c;
      }
      depth -= (c == ')' && depth > 0) ? 1 : 0;
    }
    while (!out.empty() && out.back() == ' ') {
      out.pop_back();
    }
    return out;
  }

  // ---- expressions -------------------------------------------------------

  char peek() const { return position_ < text_.size() ? text_[position_] : '\0'; }
  bool accept(std::string_view word) {
    if (text_.compare(position_, word.size(), word) == 0) {
      position_ += word.size();
      return true;
    }
    return false;
  }
  void expect(char c) {
    if (peek() != c) {
      throw std::runtime_error("expected '" + std::string(1, c) + "' in: " + text_);
    }
    ++position_;
  }

  double read(int variable) const {
    if (variable == 0) {
      return vacant;
    }
    auto found = variables_.find(variable);
    return found == variables_.end() ? vacant : found->second;
  }

  int variableNumber() {
    expect('#');
    if (peek() == '[') {
      ++position_;
      double index = expression();
      expect(']');
      return static_cast<int>(std::lround(arithmetic(index)));
    }
    return static_cast<int>(std::lround(number()));
  }

  double number() {
    std::size_t start = position_;
    while (std::isdigit(static_cast<unsigned char>(peek())) || peek() == '.') {
      ++position_;
    }
    if (start == position_) {
      throw std::runtime_error("expected a number in: " + text_);
    }
    return std::stod("0" + text_.substr(start, position_ - start));
  }

  // `[a]`, `[a OP b]`, `[[c] AND [d]]`: comparisons give 1 or 0.
  double bracket() {
    expect('[');
    double left = expression();
    double result = left;
    for (std::string_view op : {" EQ ", " NE ", " LT ", " LE ", " GT ", " GE ", " AND ", " OR "}) {
      if (accept(op)) {
        double right = expression();
        result = compare(op, left, right);
        break;
      }
    }
    expect(']');
    return result;
  }

  static double compare(std::string_view op, double a, double b) {
    if (op == " EQ " || op == " NE ") {
      bool equal = (std::isnan(a) && std::isnan(b)) || (!std::isnan(a) && !std::isnan(b) && a == b);
      return (op == " EQ ") == equal ? 1 : 0;
    }
    a = arithmetic(a);
    b = arithmetic(b);
    if (op == " LT ")
      return a < b;
    if (op == " LE ")
      return a <= b;
    if (op == " GT ")
      return a > b;
    if (op == " GE ")
      return a >= b;
    if (op == " AND ")
      return a != 0 && b != 0;
    return a != 0 || b != 0;
  }

  double function(std::string_view name) {
    double a = arithmetic(bracket());
    if (name == "ATAN") {
      expect('/');
      double b = arithmetic(bracket());
      double angle = std::atan2(a, b) / degree;
      return angle < 0 ? angle + 360 : angle; // Fanuc's default range 0..360
    }
    if (name == "SIN")
      return std::sin(a * degree);
    if (name == "COS")
      return std::cos(a * degree);
    if (name == "TAN")
      return std::tan(a * degree);
    if (name == "ASIN")
      return std::asin(a) / degree;
    if (name == "ACOS")
      return std::acos(a) / degree;
    if (name == "SQRT")
      return std::sqrt(a);
    if (name == "ABS")
      return std::abs(a);
    if (name == "EXP")
      return std::exp(a);
    if (name == "LN")
      return std::log(a);
    if (name == "ROUND")
      return std::round(a);
    if (name == "FIX")
      return std::trunc(a);
    return a < 0 ? std::floor(a) : std::ceil(a); // FUP
  }

  double primary() {
    if (peek() == '-') {
      ++position_;
      return -arithmetic(primary());
    }
    if (peek() == '#') {
      return read(variableNumber());
    }
    if (peek() == '[') {
      return bracket();
    }
    for (std::string_view name : {"SIN", "COS", "TAN", "ASIN", "ACOS", "ATAN", "SQRT", "ABS", "EXP",
                                  "LN", "ROUND", "FIX", "FUP"}) {
      if (text_.compare(position_, name.size() + 1, std::string(name) + "[") == 0) {
        position_ += name.size();
        return function(name);
      }
    }
    return number();
  }

  double term() {
    double value = primary();
    while (peek() == '*' || (peek() == '/')) {
      char op = text_[position_++];
      double right = arithmetic(primary());
      value = op == '*' ? arithmetic(value) * right : arithmetic(value) / right;
    }
    return value;
  }

  double expression() {
    double value = term();
    while (peek() == '+' || peek() == '-') {
      char op = text_[position_++];
      double right = arithmetic(term());
      value = op == '+' ? arithmetic(value) + right : arithmetic(value) - right;
    }
    return value;
  }

  double evaluate(const std::string& text) {
    text_ = text;
    position_ = 0;
    double value = expression();
    if (position_ != text_.size()) {
      throw std::runtime_error("unexpected text in: " + text);
    }
    return value;
  }

  // ---- statements --------------------------------------------------------

  void assign(const std::string& statement) {
    std::size_t equals = statement.find('=');
    text_ = statement.substr(0, equals);
    position_ = 0;
    int variable = variableNumber();
    variables_[variable] = evaluate(statement.substr(equals + 1));
  }

  // The value of the word starting at `text_[position_]`: a number, a
  // variable, a bracket, with an optional minus.
  double wordValue() { return arithmetic(primary()); }

  void motion(const std::string& block) {
    text_ = block;
    position_ = 0;
    bool moved = false;
    while (position_ < text_.size()) {
      if (peek() == ' ') {
        ++position_;
        continue;
      }
      char letter = text_[position_++];
      double value = wordValue();
      switch (letter) {
      case 'G':
        if (value == 0 || value == 1) {
          rapid_ = value == 0;
        }
        break;
      case 'X':
        x_ = value;
        moved = true;
        break;
      case 'Y':
        y_ = value;
        moved = true;
        break;
      case 'Z':
        z_ = value;
        moved = true;
        break;
      case 'F':
        feed_ = value;
        break;
      case 'M':
        if (value == 30 || value == 99) {
          finished_ = true;
        }
        break;
      default:
        break;
      }
    }
    if (moved) {
      moves_.push_back({rapid_, x_, y_, z_, feed_});
    }
  }

  std::size_t labelLine(int label) const {
    std::string wanted = "N" + std::to_string(label);
    for (std::size_t i = 0; i < lines_.size(); ++i) {
      if (lines_[i] == wanted || lines_[i].starts_with(wanted + " ")) {
        return i;
      }
    }
    throw std::runtime_error("no " + wanted);
  }

  // The line after the END m that closes the WHILE at `line`, or the WHILE
  // that the END m at `line` closes.
  std::size_t matchingEnd(std::size_t line, const std::string& identifier) const {
    for (std::size_t i = line + 1; i < lines_.size(); ++i) {
      if (lines_[i] == "END" + identifier) {
        return i;
      }
    }
    throw std::runtime_error("no END" + identifier);
  }
  std::size_t matchingWhile(std::size_t line, const std::string& identifier) const {
    for (std::size_t i = line; i-- > 0;) {
      if (lines_[i].starts_with("WHILE") && lines_[i].ends_with("] DO" + identifier)) {
        return i;
      }
    }
    throw std::runtime_error("no WHILE for END" + identifier);
  }

  double condition(const std::string& text) {
    text_ = text;
    position_ = 0;
    return bracket();
  }

  // Runs one statement; returns the next line.
  std::size_t step(std::size_t line) {
    const std::string& block = lines_[line];
    if (block.empty() || block == "%" || block.starts_with("O") ||
        (block[0] == 'N' && block.find(' ') == std::string::npos)) {
      return line + 1;
    }
    if (block.starts_with("WHILE ")) {
      std::size_t close = block.rfind("] DO");
      std::string identifier = block.substr(close + 4);
      bool holds = condition(block.substr(6, close + 1 - 6)) != 0;
      return holds ? line + 1 : matchingEnd(line, identifier) + 1;
    }
    if (block.starts_with("END")) {
      return matchingWhile(line, block.substr(3));
    }
    if (block.starts_with("GOTO ")) {
      return labelLine(std::stoi(block.substr(5)));
    }
    if (block.starts_with("IF ")) {
      std::size_t then = block.find("] THEN ");
      std::size_t jump = block.find("] GOTO ");
      std::size_t end = then != std::string::npos ? then : jump;
      bool holds = condition(block.substr(3, end + 1 - 3)) != 0;
      if (!holds) {
        return line + 1;
      }
      if (then != std::string::npos) {
        assign(block.substr(then + 7));
        return line + 1;
      }
      return labelLine(std::stoi(block.substr(jump + 7)));
    }
    if (block[0] == '#') {
      assign(block);
      return line + 1;
    }
    motion(block);
    return line + 1;
  }

  void execute() {
    std::size_t line = 0;
    for (long steps = 0; line < lines_.size() && !finished_; ++steps) {
      if (steps > 10'000'000) {
        throw std::runtime_error("too many steps");
      }
      line = step(line);
    }
    if (!finished_) {
      throw std::runtime_error("no M30 or M99");
    }
  }

  std::map<int, double> variables_;
  std::vector<std::string> lines_;
  std::vector<EvaluatedMove> moves_;
  std::string text_;
  std::size_t position_ = 0;
  bool rapid_ = true;
  bool finished_ = false;
  double x_ = 0, y_ = 0, z_ = 0, feed_ = 0;
};

} // namespace

MacroEvaluation evaluateMacroProgram(const std::string& text,
                                     const std::map<int, double>& arguments) {
  return Evaluator(arguments).run(text);
}

} // namespace cncc::testing
