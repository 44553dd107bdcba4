#include "cncc/lsp/framing.h"

#include <charconv>
#include <optional>

namespace cncc::lsp {

namespace {

std::string_view trim(std::string_view text) {
  while (!text.empty() && (text.front() == ' ' || text.front() == '\t')) {
    text.remove_prefix(1);
  }
  while (!text.empty() && (text.back() == ' ' || text.back() == '\t' || text.back() == '\r')) {
    text.remove_suffix(1);
  }
  return text;
}

bool equalsIgnoringCase(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) {
    return false;
  }
  for (std::size_t i = 0; i < a.size(); ++i) {
    auto lower = [](char c) { return c >= 'A' && c <= 'Z' ? static_cast<char>(c + 32) : c; };
    if (lower(a[i]) != lower(b[i])) {
      return false;
    }
  }
  return true;
}

// The value of a `Content-Length` header line, or nullopt when the line is
// another header; sets `problem` for a Content-Length it cannot use.
std::optional<std::size_t> contentLength(std::string_view line, std::string& problem) {
  std::size_t colon = line.find(':');
  if (colon == std::string_view::npos) {
    problem = "header line without ':'";
    return std::nullopt;
  }
  if (!equalsIgnoringCase(trim(line.substr(0, colon)), "Content-Length")) {
    return std::nullopt;
  }
  std::string_view value = trim(line.substr(colon + 1));
  std::size_t length = 0;
  auto [end, error] = std::from_chars(value.data(), value.data() + value.size(), length);
  if (error != std::errc() || end != value.data() + value.size()) {
    problem = "Content-Length is not a number";
    return std::nullopt;
  }
  if (length > maximumMessageSize) {
    problem = "Content-Length is too large";
    return std::nullopt;
  }
  return length;
}

} // namespace

ReadResult readMessage(std::istream& input) {
  ReadResult result;
  std::optional<std::size_t> length;
  std::string problem;
  std::string line;
  bool sawHeader = false;
  while (std::getline(input, line)) {
    if (trim(line).empty()) {
      if (!sawHeader) {
        continue; // stray blank lines between messages
      }
      break;
    }
    sawHeader = true;
    if (std::optional<std::size_t> value = contentLength(line, problem)) {
      length = value;
    }
  }
  if (!sawHeader) {
    return result; // end of input
  }
  if (!input && !length) {
    return result;
  }
  if (!length) {
    result.status = ReadStatus::BadHeader;
    result.problem = problem.empty() ? "no Content-Length header" : problem;
    return result;
  }
  result.body.resize(*length);
  input.read(result.body.data(), static_cast<std::streamsize>(*length));
  if (static_cast<std::size_t>(input.gcount()) != *length) {
    result.body.clear();
    return result; // the stream ended inside the message
  }
  result.status = ReadStatus::Message;
  return result;
}

void writeMessage(std::ostream& output, std::string_view body) {
  output << "Content-Length: " << body.size() << "\r\n\r\n" << body;
  output.flush();
}

} // namespace cncc::lsp
