#include "cncc/lsp/uri.h"

#include <fmt/format.h>

namespace cncc::lsp {

namespace {

int hexValue(char c) {
  if (c >= '0' && c <= '9') {
    return c - '0';
  }
  if (c >= 'a' && c <= 'f') {
    return c - 'a' + 10;
  }
  if (c >= 'A' && c <= 'F') {
    return c - 'A' + 10;
  }
  return -1;
}

bool isUnreserved(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' ||
         c == '.' || c == '_' || c == '~' || c == '/';
}

} // namespace

std::optional<std::string> pathFromUri(std::string_view uri) {
  constexpr std::string_view scheme = "file://";
  if (uri.substr(0, scheme.size()) != scheme) {
    return std::nullopt;
  }
  std::string_view rest = uri.substr(scheme.size());
  // "file://host/path": only an empty host or localhost is a local file.
  std::size_t slash = rest.find('/');
  if (slash == std::string_view::npos) {
    return std::nullopt;
  }
  std::string_view host = rest.substr(0, slash);
  if (!host.empty() && host != "localhost") {
    return std::nullopt;
  }
  std::string path;
  for (std::size_t i = slash; i < rest.size(); ++i) {
    if (rest[i] != '%') {
      path += rest[i];
      continue;
    }
    if (i + 2 >= rest.size() || hexValue(rest[i + 1]) < 0 || hexValue(rest[i + 2]) < 0) {
      return std::nullopt;
    }
    path += static_cast<char>(hexValue(rest[i + 1]) * 16 + hexValue(rest[i + 2]));
    i += 2;
  }
  return path;
}

std::string uriFromPath(std::string_view path) {
  std::string uri = "file://";
  for (char c : path) {
    if (isUnreserved(c)) {
      uri += c;
    } else {
      uri += fmt::format("%{:02X}", static_cast<unsigned char>(c));
    }
  }
  return uri;
}

} // namespace cncc::lsp
