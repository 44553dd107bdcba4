// Compiled programs with a source map beside them (`cncc --source-map`,
// PROGRAM.map.json): go to definition from a program line opens the CDL
// statement that printed it, and a hover says which one.
#pragma once

#include "cncc/lsp/json_rpc.h"
#include "cncc/lsp/text_positions.h"

#include <string>
#include <string_view>

namespace cncc::lsp {

// FNV-1a, 64 bits, in hex: the hash a source map keeps of its program.
std::string programHash(std::string_view text);

// Where a source of the map is: `source` as the map names it, read against
// the map's "directory" when it is relative (what `cncc where` reads too).
std::string resolvedSourcePath(const Json& map, const std::string& source);

// Whether `uri` is a program (not a .cdl file) with a source map beside it.
bool isMappedProgram(std::string_view uri);

// `textDocument/definition` on line `position.line` of the program `text`:
// the CDL location its map gives, or null (no map, a map of another
// version of the program, a line it does not have).
Json programDefinition(std::string_view uri, std::string_view text, Position position);
// `textDocument/hover` there: on a `#n` variable what it holds and from
// which statements (macro programs), else the line's statement, its
// location and source line.
Json programHover(std::string_view uri, std::string_view text, Position position);

} // namespace cncc::lsp
