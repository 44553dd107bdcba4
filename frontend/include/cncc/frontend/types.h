// The types of CDL values, as the semantic checker assigns them.
#pragma once

#include <cstdint>
#include <string>

namespace cncc::frontend {

enum class TypeKind : std::uint8_t {
  Error, // an expression that already produced a diagnostic; accepted anywhere
  Any,   // a parameter of a generic `fn`, checked again at each call
  Num,
  Bool,
  String,
  Point,
  List,
  Range,
  Curve,
};

struct Type {
  TypeKind kind = TypeKind::Error;
  // For lists: the element type (Num, Point, Bool, Curve, or Any when empty).
  TypeKind element = TypeKind::Any;

  static Type num() { return {TypeKind::Num}; }
  static Type boolean() { return {TypeKind::Bool}; }
  static Type string() { return {TypeKind::String}; }
  static Type point() { return {TypeKind::Point}; }
  static Type range() { return {TypeKind::Range}; }
  static Type curve() { return {TypeKind::Curve}; }
  static Type any() { return {TypeKind::Any}; }
  static Type error() { return {TypeKind::Error}; }
  static Type listOf(TypeKind element) { return {TypeKind::List, element}; }

  // Error and Any are compatible with everything, so one mistake yields one
  // message.
  bool isLenient() const { return kind == TypeKind::Error || kind == TypeKind::Any; }
  friend bool operator==(Type, Type) = default;
};

std::string typeName(Type type);
std::string typeKindName(TypeKind kind);

} // namespace cncc::frontend
