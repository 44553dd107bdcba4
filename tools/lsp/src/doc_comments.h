// Documentation comments: the comment lines right above a declaration, as
// stdlib functions carry them ("// Full circle of the given radius ...").
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace cncc::lsp {

// The text of the `//` lines (or one `/* */` block) that end on the line
// before the line holding `offset`, without their comment markers; empty
// when a blank line or code comes first.
std::string docCommentAbove(std::string_view text, std::uint32_t offset);

} // namespace cncc::lsp
