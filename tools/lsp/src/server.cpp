// The server's lifecycle and dispatch: which messages are answered in which
// state, and how each failure becomes the protocol's error response.
#include "cncc/lsp/server.h"

#include "cncc/lsp/features.h"
#include "cncc/lsp/program_map.h"
#include "cncc/lsp/protocol_json.h"
#include "cncc/lsp/uri.h"

#include <cstdlib>
#include <filesystem>
#include <fmt/format.h>
#include <optional>

namespace cncc::lsp {

std::string defaultStdlibDirectory() {
  const char* overridden = std::getenv("CNCC_STDLIB");
  return overridden != nullptr && *overridden != '\0' ? overridden : CNCC_STDLIB_DIR;
}

Server::Server(ServerOptions options) : options_(std::move(options)) {
  registerHandlers();
}

void Server::registerHandlers() {
  requests_["initialize"] = [this](const Json& params) { return initialize(params); };
  requests_["shutdown"] = [this](const Json&) { return shutdown(); };
  requests_["textDocument/hover"] = [this](const Json& params) {
    Position position = positionParam(params); // checked first, as by every request
    if (const Document* program = mappedProgram(params)) {
      return programHover(documentUri(params), program->text, position);
    }
    return hover(analysisOf(params), position);
  };
  requests_["textDocument/definition"] = [this](const Json& params) {
    Position position = positionParam(params);
    if (const Document* program = mappedProgram(params)) {
      return programDefinition(documentUri(params), program->text, position);
    }
    return definition(analysisOf(params), position);
  };
  requests_["textDocument/completion"] = [this](const Json& params) {
    CompletionOptions options{clientSnippets_, options_.stdlibDirectory};
    return completion(analysisOf(params), positionParam(params), options);
  };
  requests_["textDocument/documentSymbol"] = [this](const Json& params) {
    return documentSymbols(analysisOf(params));
  };
  requests_["textDocument/formatting"] = [this](const Json& params) {
    std::string uri = documentUri(params);
    const Document* document = documents_.find(uri);
    if (document == nullptr) {
      throw RequestError(ErrorCode::InvalidParams, fmt::format("'{}' is not open", uri));
    }
    return formatting(uri, document->text);
  };
  requests_["textDocument/codeLens"] = [this](const Json& params) {
    std::string uri = documentUri(params);
    std::vector<std::string> directories = workspaceFolders_;
    if (std::optional<std::string> path = pathFromUri(uri)) {
      directories.push_back(std::filesystem::path(*path).parent_path().string());
    }
    cutLenses_.setDirectories(std::move(directories));
    return cutLenses_.lenses(uri);
  };
  requests_["textDocument/semanticTokens/full"] = [this](const Json& params) {
    return semanticTokens(analysisOf(params));
  };
  notifications_["initialized"] = [](const Json&) {};
  notifications_["textDocument/didOpen"] = [this](const Json& params) { didOpen(params); };
  notifications_["textDocument/didChange"] = [this](const Json& params) { didChange(params); };
  notifications_["textDocument/didClose"] = [this](const Json& params) { didClose(params); };
}

namespace {

// Whether the client's capabilities say it expands completion snippets;
// false for anything missing or malformed.
bool clientExpandsSnippets(const Json& params) {
  const Json* value = &params;
  for (const char* key :
       {"capabilities", "textDocument", "completion", "completionItem", "snippetSupport"}) {
    if (!value->is_object() || !value->contains(key)) {
      return false;
    }
    value = &(*value)[key];
  }
  return value->is_boolean() && value->get<bool>();
}

// The folders of the workspace: `workspaceFolders`, else `rootUri`.
std::vector<std::string> workspaceFolderPaths(const Json& params) {
  std::vector<std::string> folders;
  auto addUri = [&](const Json& uri) {
    if (uri.is_string()) {
      if (std::optional<std::string> path = pathFromUri(uri.get<std::string>())) {
        folders.push_back(*path);
      }
    }
  };
  if (params.contains("workspaceFolders") && params["workspaceFolders"].is_array()) {
    for (const Json& folder : params["workspaceFolders"]) {
      if (folder.is_object() && folder.contains("uri")) {
        addUri(folder["uri"]);
      }
    }
  }
  if (folders.empty() && params.contains("rootUri")) {
    addUri(params["rootUri"]);
  }
  return folders;
}

} // namespace

Json Server::initialize(const Json& params) {
  if (state_ != State::Uninitialized) {
    throw RequestError(ErrorCode::InvalidRequest, "the server is already initialized");
  }
  state_ = State::Running;
  clientSnippets_ = clientExpandsSnippets(params);
  workspaceFolders_ =
      params.is_object() ? workspaceFolderPaths(params) : std::vector<std::string>{};
  Json capabilities = {
      {"positionEncoding", "utf-16"},
      {"textDocumentSync", {{"openClose", true}, {"change", 2}}}, // 2: incremental
      {"hoverProvider", true},
      {"definitionProvider", true},
      {"completionProvider", {{"triggerCharacters", {"\"", "/", "="}}}},
      {"documentSymbolProvider", true},
      {"documentFormattingProvider", true},
      {"codeLensProvider", {{"resolveProvider", false}}},
      {"semanticTokensProvider", {{"legend", semanticTokensLegend()}, {"full", true}}},
  };
  return {{"capabilities", capabilities},
          {"serverInfo", {{"name", "cncc-lsp"}, {"version", CNCC_VERSION}}}};
}

Json Server::shutdown() {
  state_ = State::ShuttingDown;
  shutdownRequested_ = true;
  return nullptr;
}

std::vector<Json> Server::handleText(std::string_view message) {
  Json parsed = Json::parse(message, nullptr, false);
  if (parsed.is_discarded()) {
    return {makeErrorResponse(nullptr, ErrorCode::ParseError, "the message is not valid JSON")};
  }
  return handle(parsed);
}

std::vector<Json> Server::handle(const Json& message) {
  releaseRetired();
  outgoing_.clear();
  bool hasId = message.is_object() && message.contains("id");
  Json id = hasId ? message.at("id") : Json(nullptr);
  bool validId = id.is_null() || id.is_number_integer() || id.is_string();
  if (!message.is_object() || !message.contains("method") || !message.at("method").is_string() ||
      !validId) {
    bool isResponse =
        message.is_object() && hasId && (message.contains("result") || message.contains("error"));
    if (!isResponse) { // the server sends no requests, so a response is ignored
      outgoing_.push_back(makeErrorResponse(validId ? id : Json(nullptr), ErrorCode::InvalidRequest,
                                            "expected a JSON-RPC request or notification"));
    }
    return std::move(outgoing_);
  }
  const std::string& method = message.at("method").get_ref<const std::string&>();
  Json params = message.contains("params") ? message.at("params") : Json::object();
  if (hasId) {
    handleRequest(id, method, params);
  } else {
    handleNotification(method, params);
  }
  return std::move(outgoing_);
}

void Server::handleRequest(const Json& id, const std::string& method, const Json& params) {
  if (state_ == State::Uninitialized && method != "initialize") {
    outgoing_.push_back(makeErrorResponse(id, ErrorCode::ServerNotInitialized,
                                          "the first request must be 'initialize'"));
    return;
  }
  if (state_ == State::ShuttingDown || state_ == State::Exited) {
    outgoing_.push_back(makeErrorResponse(id, ErrorCode::InvalidRequest,
                                          "the server is shutting down; only 'exit' is accepted"));
    return;
  }
  auto handler = requests_.find(method);
  if (handler == requests_.end()) {
    outgoing_.push_back(makeErrorResponse(id, ErrorCode::MethodNotFound,
                                          fmt::format("unknown method '{}'", method)));
    return;
  }
  try {
    Json result = handler->second(params);
    outgoing_.insert(outgoing_.begin(), makeResponse(id, std::move(result)));
  } catch (const RequestError& error) {
    outgoing_.push_back(makeErrorResponse(id, error.code(), error.what()));
  } catch (const Json::exception& error) {
    outgoing_.push_back(makeErrorResponse(id, ErrorCode::InvalidParams, error.what()));
  } catch (const std::exception& error) {
    outgoing_.push_back(makeErrorResponse(id, ErrorCode::InternalError, error.what()));
  }
}

// Notifications get no answer, not even for an error; one that fails is
// dropped (the protocol has no way to report it but a log message).
void Server::handleNotification(const std::string& method, const Json& params) {
  if (method == "exit") {
    state_ = State::Exited;
    return;
  }
  if (state_ != State::Running) {
    return;
  }
  auto handler = notifications_.find(method);
  if (handler == notifications_.end()) {
    return; // unknown, `$/...` and optional notifications are ignored
  }
  try {
    handler->second(params);
  } catch (const std::exception& error) {
    outgoing_.push_back(makeNotification(
        "window/logMessage",
        {{"type", 1}, {"message", fmt::format("{} failed: {}", method, error.what())}}));
  }
}

std::string documentUri(const Json& params) {
  const Json& document = requireMember(params, "textDocument", Json::value_t::object);
  return requireMember(document, "uri", Json::value_t::string).get<std::string>();
}

Position positionParam(const Json& params) {
  return positionFromJson(requireMember(params, "position", Json::value_t::object));
}

} // namespace cncc::lsp
