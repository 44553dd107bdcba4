#include "cncc/lsp/protocol_json.h"

#include <fmt/format.h>
#include <limits>

namespace cncc::lsp {

Json toJson(Position position) {
  return {{"line", position.line}, {"character", position.character}};
}

Json toJson(Range range) {
  return {{"start", toJson(range.start)}, {"end", toJson(range.end)}};
}

Json toJson(const Location& location) {
  return {{"uri", location.uri}, {"range", toJson(location.range)}};
}

namespace {

bool hasType(const Json& value, Json::value_t type) {
  if (type == Json::value_t::number_unsigned) {
    return value.is_number_unsigned() || (value.is_number_integer() && value.get<long long>() >= 0);
  }
  if (type == Json::value_t::number_integer) {
    return value.is_number_integer();
  }
  return value.type() == type;
}

// A position component: a non-negative integer; huge values are clamped
// (the position is clamped into the document anyway).
std::uint32_t coordinate(const Json& object, const char* name) {
  const Json& value = requireMember(object, name, Json::value_t::number_unsigned);
  auto number = value.get<unsigned long long>();
  return static_cast<std::uint32_t>(
      std::min<unsigned long long>(number, std::numeric_limits<std::uint32_t>::max()));
}

} // namespace

const Json& requireMember(const Json& object, const char* name, Json::value_t type) {
  if (!object.is_object()) {
    throw RequestError(ErrorCode::InvalidParams, fmt::format("expected an object with '{}'", name));
  }
  auto found = object.find(name);
  if (found == object.end() || !hasType(*found, type)) {
    throw RequestError(ErrorCode::InvalidParams,
                       fmt::format("'{}' is missing or has the wrong type", name));
  }
  return *found;
}

Position positionFromJson(const Json& json) {
  return {coordinate(json, "line"), coordinate(json, "character")};
}

Range rangeFromJson(const Json& json) {
  return {positionFromJson(requireMember(json, "start", Json::value_t::object)),
          positionFromJson(requireMember(json, "end", Json::value_t::object))};
}

} // namespace cncc::lsp
