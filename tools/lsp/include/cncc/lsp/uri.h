// `file://` URIs (how the protocol names documents) and file system paths.
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace cncc::lsp {

// The path of a `file:` URI with its percent-escapes decoded
// ("file:///home/a%20b/x.cdl" -> "/home/a b/x.cdl"); nullopt for any other
// scheme or a malformed escape.
std::optional<std::string> pathFromUri(std::string_view uri);

// The `file:` URI of an absolute path, escaping what RFC 3986 reserves.
std::string uriFromPath(std::string_view path);

} // namespace cncc::lsp
