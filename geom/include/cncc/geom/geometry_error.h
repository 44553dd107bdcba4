#pragma once

#include <stdexcept>
#include <string>

namespace cncc::geom {

/// Thrown when a curve is built from inputs that do not describe a valid curve
/// (bad degree, knot vector, weights, empty or mismatched point lists, zero-length
/// lines, ...), or when an operation is given arguments outside its domain.
/// The message says what is wrong in words a user can act on; callers that must not
/// throw (the semantic checker) can call the matching `findProblem` function first.
class GeometryError : public std::invalid_argument {
public:
  explicit GeometryError(const std::string& message) : std::invalid_argument(message) {}
};

} // namespace cncc::geom
