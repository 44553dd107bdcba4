// Compile-time values: what `const`, `fn` calls and part bodies evaluate to
// when every parameter has a number (its default, or a -D override).
#pragma once

#include "cncc/frontend/types.h"

#include <array>
#include <cstddef>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace cncc::frontend {

struct Expr;
struct Declaration;
struct CurveValue;
struct Value;

using ValueList = std::vector<Value>;
// Values bound to declarations: the environment a curve's expressions in
// `t` are evaluated in.
using Environment = std::map<const Declaration*, Value>;

struct Value {
  Type type = Type::error();
  double number = 0;
  bool boolean = false;
  // Strings are rare and Values are copied and moved all the time: a
  // shared pointer moves without copying characters.
  std::shared_ptr<const std::string> string;
  std::array<double, 3> point{0, 0, 0};
  int pointDimensions = 0;               // 2 or 3 for points
  std::shared_ptr<const ValueList> list; // lists
  double low = 0, high = 0;              // ranges
  std::shared_ptr<const CurveValue> curve;

  // Inline: evaluation makes one for nearly every number it computes.
  static Value ofNumber(double number) {
    Value value;
    value.type = Type::num();
    value.number = number;
    return value;
  }
  static Value ofBool(bool value);
  static Value ofString(std::string text);
  static Value ofPoint(std::array<double, 3> coordinates, int dimensions) {
    Value value;
    value.type = Type::point();
    value.point = coordinates;
    value.pointDimensions = dimensions;
    return value;
  }
  static Value ofList(ValueList elements, TypeKind elementType);
  static Value ofRange(double low, double high);
  static Value ofCurve(std::shared_ptr<const CurveValue> curve);

  bool isError() const { return type.kind == TypeKind::Error; }
};

enum class CurveKind { Nurbs, Polar, Param, Line, Arc, Path, Translate, Rotate, Scale };

// A curve's pieces: a path's, or the one a translate, rotate or scale moves.
// Read like a vector. Most curves with pieces are transforms of one, which is
// kept without allocating a vector.
class CurvePieces {
public:
  using Piece = std::shared_ptr<const CurveValue>;
  void reserve(std::size_t count) {
    if (count > 1) {
      many_.reserve(count);
    }
  }
  void push_back(Piece piece) {
    if (count_ == 0) {
      single_ = std::move(piece);
    } else {
      if (count_ == 1) {
        many_.push_back(std::move(single_));
      }
      many_.push_back(std::move(piece));
    }
    ++count_;
  }
  std::size_t size() const { return count_; }
  bool empty() const { return count_ == 0; }
  const Piece* begin() const { return count_ <= 1 ? &single_ : many_.data(); }
  const Piece* end() const { return begin() + count_; }
  const Piece& front() const { return *begin(); }
  const Piece& operator[](std::size_t i) const { return begin()[i]; }

private:
  std::size_t count_ = 0;
  Piece single_;            // the piece, while there is only one
  std::vector<Piece> many_; // every piece, once there are more
};

// A curve with every number it needs. Analytic curves keep their expressions
// in `t` and the environment to evaluate them in.
struct CurveValue {
  CurveKind kind = CurveKind::Nurbs;
  // The name the source used: nurbs, bspline, bezier, ... (a view of the
  // builtin's name, which lives as long as the program).
  std::string_view constructor;

  // Nurbs, bspline, bezier: the control polygon and its knot vector
  // (clamped uniform when the source gave none).
  int degree = 0;
  std::vector<std::array<double, 3>> points;
  std::vector<double> weights;
  std::vector<double> knots;

  // Polar (r) and param (x, y, z): expressions in the parameter `t`.
  const Expr* radius = nullptr;
  const Expr* x = nullptr;
  const Expr* y = nullptr;
  const Expr* z = nullptr;
  const Declaration* parameter = nullptr; // the `t` these expressions use
  Environment environment;
  double low = 0, high = 0; // the parameter range

  // Line: from -> to. Arc: center, radius, angles from -> to.
  std::array<double, 3> from{0, 0, 0};
  std::array<double, 3> to{0, 0, 0};
  std::array<double, 3> center{0, 0, 0};
  double arcRadius = 0;
  double startAngle = 0, endAngle = 0;
  // Arc: its height at the start and the end angle (z = z0 .. z1, a helix; 0 .. 0 without).
  double startZ = 0, endZ = 0;

  // Path: the pieces. Translate/rotate/scale: one piece and the amounts.
  CurvePieces pieces;
  double dx = 0, dy = 0, angle = 0, factor = 1;
};

// A short human description: "3.5", "(25, 50)", "list of 7 points",
// "nurbs curve, degree 3, 7 points".
std::string describeValue(const Value& value);

} // namespace cncc::frontend
