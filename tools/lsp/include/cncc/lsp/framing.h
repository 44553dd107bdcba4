// The protocol's base layer: each message is `Content-Length: N` (other
// headers allowed and ignored), an empty line, and N bytes of JSON. Kept
// apart from the server so the server's handlers take and return JSON only.
#pragma once

#include <cstddef>
#include <istream>
#include <ostream>
#include <string>
#include <string_view>

namespace cncc::lsp {

enum class ReadStatus {
  Message,    // `body` holds one message
  EndOfInput, // the stream ended (cleanly or inside a message)
  BadHeader,  // a header block without a usable Content-Length; skipped
};

struct ReadResult {
  ReadStatus status = ReadStatus::EndOfInput;
  std::string body;
  std::string problem; // for BadHeader: what was wrong, for the log
};

// Messages larger than this are refused as a bad header rather than
// allocated.
inline constexpr std::size_t maximumMessageSize = std::size_t{256} << 20;

ReadResult readMessage(std::istream& input);
void writeMessage(std::ostream& output, std::string_view body);

} // namespace cncc::lsp
