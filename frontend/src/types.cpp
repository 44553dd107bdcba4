#include "cncc/frontend/types.h"

namespace cncc::frontend {

std::string typeKindName(TypeKind kind) {
  switch (kind) {
  case TypeKind::Error:
    return "error";
  case TypeKind::Any:
    return "any";
  case TypeKind::Num:
    return "num";
  case TypeKind::Bool:
    return "bool";
  case TypeKind::String:
    return "string";
  case TypeKind::Point:
    return "point";
  case TypeKind::List:
    return "list";
  case TypeKind::Range:
    return "range";
  case TypeKind::Curve:
    return "curve";
  }
  return "error";
}

std::string typeName(Type type) {
  if (type.kind == TypeKind::List) {
    return type.element == TypeKind::Any ? "list" : "list of " + typeKindName(type.element);
  }
  return typeKindName(type.kind);
}

} // namespace cncc::frontend
