// The language server: the protocol's lifecycle (initialize, shutdown,
// exit) and the dispatch of each message to its feature, with the error
// answers the protocol asks for. It takes and returns JSON messages; the
// framing is in framing.h and the loop that connects the two in
// server_loop.h, so tests drive the server message by message.
#pragma once

#include "cncc/lsp/cut_lenses.h"

#include "cncc/lsp/analysis.h"
#include "cncc/lsp/document_store.h"
#include "cncc/lsp/json_rpc.h"

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace cncc::lsp {

struct ServerOptions {
  std::string stdlibDirectory;
};

// The stdlib directory: $CNCC_STDLIB when set, else the one built in.
std::string defaultStdlibDirectory();

class Server {
public:
  explicit Server(ServerOptions options);
  // The handlers hold `this`: a server stays where it was made.
  Server(const Server&) = delete;
  Server& operator=(const Server&) = delete;

  // Handles one message as received and returns what to send back, in
  // order: the response to a request, and notifications (diagnostics).
  // Malformed JSON gets a ParseError response; nothing throws.
  std::vector<Json> handleText(std::string_view message);
  std::vector<Json> handle(const Json& message);

  // Frees the analyses that edits replaced. The loop calls it after
  // sending the answers, so freeing a large file's tree is not part of the
  // time to its diagnostics; handle() also calls it first.
  void releaseRetired() { retired_.clear(); }

  // After `exit`: the process should end, with this code (0 when
  // `shutdown` came first, as the protocol asks).
  bool exitRequested() const { return state_ == State::Exited; }
  int exitCode() const { return shutdownRequested_ ? 0 : 1; }

private:
  enum class State { Uninitialized, Running, ShuttingDown, Exited };
  using RequestHandler = std::function<Json(const Json& params)>;
  using NotificationHandler = std::function<void(const Json& params)>;

  void handleRequest(const Json& id, const std::string& method, const Json& params);
  void handleNotification(const std::string& method, const Json& params);
  void registerHandlers();

  // lifecycle (server.cpp)
  Json initialize(const Json& params);
  Json shutdown();

  // documents (server_documents.cpp)
  void didOpen(const Json& params);
  void didChange(const Json& params);
  void didClose(const Json& params);
  void analyse(const std::string& uri);
  const Analysis& analysisOf(const Json& params) const;
  // The open document of `params` when it is a program with a source map.
  const Document* mappedProgram(const Json& params) const;

  ServerOptions options_;
  State state_ = State::Uninitialized;
  bool shutdownRequested_ = false;
  bool clientSnippets_ = false;
  DocumentStore documents_;
  std::map<std::string, std::unique_ptr<Analysis>> analyses_;
  std::vector<std::unique_ptr<Analysis>> retired_;
  std::map<std::string, RequestHandler> requests_;
  std::map<std::string, NotificationHandler> notifications_;
  std::vector<Json> outgoing_;
  // The workspace's folders and each document's own: where source maps are.
  std::vector<std::string> workspaceFolders_;
  CutLensIndex cutLenses_{CutLensSearch{}};
};

// Reads the params' `textDocument.uri` and `position`, or throws
// RequestError(InvalidParams).
std::string documentUri(const Json& params);
Position positionParam(const Json& params);

} // namespace cncc::lsp
