// Arithmetic and conditions of Sinumerik part programs, evaluated when the
// block runs: numbers, R parameters (`R12`), + - * / DIV MOD, comparisons
// == <> > < >= <= (1 or 0), AND OR NOT, brackets ( ) and the functions SIN
// COS TAN ASIN ACOS (degrees) ATAN2(y,x) SQRT ABS POT (the square) TRUNC
// ROUND LN EXP.
#pragma once

#include <functional>
#include <stdexcept>
#include <string_view>

namespace cncc::backends::sinumerik {

class ExpressionError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

// The value of `text` (upper case); `parameter(n)` reads Rn. Throws
// ExpressionError for a malformed expression or one outside a function's
// domain.
double evaluateExpression(std::string_view text, const std::function<double(int)>& parameter);

} // namespace cncc::backends::sinumerik
