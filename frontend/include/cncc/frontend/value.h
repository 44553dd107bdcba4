// Compile-time values: what `const`, `fn` calls and part bodies evaluate to
// when every parameter has a number (its default, or a -D override).
#pragma once

#include "cncc/frontend/types.h"

#include <array>
#include <map>
#include <memory>
#include <string>
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

// A curve with every number it needs. Analytic curves keep their expressions
// in `t` and the environment to evaluate them in.
struct CurveValue {
  CurveKind kind = CurveKind::Nurbs;
  std::string constructor; // the name the source used: nurbs, bspline, bezier, ...

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

  // Path: the pieces. Translate/rotate/scale: one piece and the amounts.
  std::vector<std::shared_ptr<const CurveValue>> pieces;
  double dx = 0, dy = 0, angle = 0, factor = 1;
};

// A short human description: "3.5", "(25, 50)", "list of 7 points",
// "nurbs curve, degree 3, 7 points".
std::string describeValue(const Value& value);

} // namespace cncc::frontend
