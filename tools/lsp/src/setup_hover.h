// Hovers on the machine set-up words, which name no declaration: `origin`,
// `coolant`, and a tool's `length=` and `radius=`.
#pragma once

#include "cncc/frontend/ast.h"

#include <cstdint>
#include <optional>
#include <string>

namespace cncc::lsp {

struct SetupHover {
  std::string markdown;
  frontend::SourceSpan span; // what the hover is about
};

// The hover at `offset` in a part body of `module`, if a set-up word is there.
std::optional<SetupHover> setupHover(const frontend::Module& module, std::uint32_t offset);

} // namespace cncc::lsp
