// The protocol's small JSON shapes (Position, Range, Location) to and from
// the server's types. Reading throws RequestError(InvalidParams) for a
// missing or mistyped field.
#pragma once

#include "cncc/lsp/analysis.h"
#include "cncc/lsp/json_rpc.h"
#include "cncc/lsp/text_positions.h"

namespace cncc::lsp {

Json toJson(Position position);
Json toJson(Range range);
Json toJson(const Location& location);

Position positionFromJson(const Json& json);
Range rangeFromJson(const Json& json);

// A required member of `object` of the given JSON type, or InvalidParams.
const Json& requireMember(const Json& object, const char* name, Json::value_t type);

} // namespace cncc::lsp
