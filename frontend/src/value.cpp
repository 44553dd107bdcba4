#include "cncc/frontend/value.h"

#include <fmt/format.h>

namespace cncc::frontend {

Value Value::ofBool(bool boolean) {
  Value value;
  value.type = Type::boolean();
  value.boolean = boolean;
  return value;
}

Value Value::ofString(std::string text) {
  Value value;
  value.type = Type::string();
  value.string = std::make_shared<const std::string>(std::move(text));
  return value;
}

Value Value::ofList(ValueList elements, TypeKind elementType) {
  Value value;
  value.type = Type::listOf(elementType);
  value.list = std::make_shared<const ValueList>(std::move(elements));
  return value;
}

Value Value::ofRange(double low, double high) {
  Value value;
  value.type = Type::range();
  value.low = low;
  value.high = high;
  return value;
}

Value Value::ofCurve(std::shared_ptr<const CurveValue> curve) {
  Value value;
  value.type = Type::curve();
  value.curve = std::move(curve);
  return value;
}

namespace {

std::string describePoint(const Value& value) {
  if (value.pointDimensions == 3) {
    return fmt::format("({:g}, {:g}, {:g})", value.point[0], value.point[1], value.point[2]);
  }
  return fmt::format("({:g}, {:g})", value.point[0], value.point[1]);
}

std::string describeCurve(const CurveValue& curve) {
  switch (curve.kind) {
  case CurveKind::Nurbs:
    return fmt::format("{} curve, degree {}, {} control points", curve.constructor, curve.degree,
                       curve.points.size());
  case CurveKind::Polar:
    return fmt::format("polar curve, t in {:g} .. {:g}", curve.low, curve.high);
  case CurveKind::Param:
    return fmt::format("parametric curve, t in {:g} .. {:g}", curve.low, curve.high);
  case CurveKind::Line:
    return "line";
  case CurveKind::Arc:
    return fmt::format("arc, radius {:g}", curve.arcRadius);
  case CurveKind::Path:
    return fmt::format("path of {} curves", curve.pieces.size());
  case CurveKind::Translate:
  case CurveKind::Rotate:
  case CurveKind::Scale:
    return fmt::format("{} {}", curve.constructor,
                       curve.pieces.empty() ? "" : describeCurve(*curve.pieces.front()));
  }
  return "curve";
}

} // namespace

std::string describeValue(const Value& value) {
  switch (value.type.kind) {
  case TypeKind::Num:
    return fmt::format("{:g}", value.number);
  case TypeKind::Bool:
    return value.boolean ? "true" : "false";
  case TypeKind::String:
    return fmt::format("\"{}\"", value.string ? *value.string : std::string());
  case TypeKind::Point:
    return describePoint(value);
  case TypeKind::List: {
    std::size_t count = value.list ? value.list->size() : 0;
    if (count > 0 && count <= 8 && value.type.element == TypeKind::Num) {
      std::string text = "[";
      for (std::size_t i = 0; i < count; ++i) {
        text += fmt::format("{}{:g}", i == 0 ? "" : ", ", (*value.list)[i].number);
      }
      return text + "]";
    }
    return fmt::format("list of {} {}{}", count, typeKindName(value.type.element),
                       count == 1 ? "" : "s");
  }
  case TypeKind::Range:
    return fmt::format("{:g} .. {:g}", value.low, value.high);
  case TypeKind::Curve:
    return value.curve ? describeCurve(*value.curve) : "curve";
  case TypeKind::Error:
  case TypeKind::Any:
    break;
  }
  return "?";
}

} // namespace cncc::frontend
