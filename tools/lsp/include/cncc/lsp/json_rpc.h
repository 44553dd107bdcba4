// JSON-RPC 2.0 as the protocol uses it: responses, errors, notifications,
// and the error codes.
#pragma once

#include <nlohmann/json.hpp>

#include <stdexcept>
#include <string>

namespace cncc::lsp {

using Json = nlohmann::json;

enum class ErrorCode {
  ParseError = -32700,
  InvalidRequest = -32600,
  MethodNotFound = -32601,
  InvalidParams = -32602,
  InternalError = -32603,
  ServerNotInitialized = -32002,
  RequestFailed = -32803,
};

// Thrown by a handler to answer its request with an error.
class RequestError : public std::runtime_error {
public:
  RequestError(ErrorCode code, const std::string& message)
      : std::runtime_error(message), code_(code) {}
  ErrorCode code() const { return code_; }

private:
  ErrorCode code_;
};

Json makeResponse(const Json& id, Json result);
Json makeErrorResponse(const Json& id, ErrorCode code, const std::string& message);
Json makeNotification(const std::string& method, Json params);

// Compact JSON text; invalid UTF-8 in strings becomes U+FFFD instead of an
// exception, so no document content can stop the server from answering.
std::string serialize(const Json& message);

} // namespace cncc::lsp
