// The server's document notifications: keeping the text in step with the
// editor, checking it after every change and publishing the diagnostics.
#include "cncc/lsp/features.h"
#include "cncc/lsp/program_map.h"
#include "cncc/lsp/protocol_json.h"
#include "cncc/lsp/server.h"

#include <fmt/format.h>

namespace cncc::lsp {

namespace {

long long versionOf(const Json& document) {
  auto found = document.find("version");
  return found != document.end() && found->is_number_integer() ? found->get<long long>() : 0;
}

std::vector<TextChange> textChanges(const Json& params) {
  const Json& changes = requireMember(params, "contentChanges", Json::value_t::array);
  std::vector<TextChange> result;
  for (const Json& change : changes) {
    TextChange textChange;
    textChange.text = requireMember(change, "text", Json::value_t::string).get<std::string>();
    if (change.is_object() && change.contains("range")) {
      textChange.range = rangeFromJson(change.at("range"));
    }
    result.push_back(std::move(textChange));
  }
  return result;
}

} // namespace

void Server::didOpen(const Json& params) {
  const Json& document = requireMember(params, "textDocument", Json::value_t::object);
  std::string uri = requireMember(document, "uri", Json::value_t::string).get<std::string>();
  std::string text = requireMember(document, "text", Json::value_t::string).get<std::string>();
  documents_.open(uri, std::move(text), versionOf(document));
  if (!isMappedProgram(uri)) { // a compiled program is not CDL
    analyse(uri);
  }
}

void Server::didChange(const Json& params) {
  std::string uri = documentUri(params);
  std::vector<TextChange> changes = textChanges(params);
  long long version = versionOf(params.at("textDocument"));
  if (!documents_.change(uri, changes, version)) {
    throw RequestError(ErrorCode::InvalidParams, fmt::format("'{}' is not open", uri));
  }
  if (!isMappedProgram(uri)) {
    analyse(uri);
  }
}

void Server::didClose(const Json& params) {
  std::string uri = documentUri(params);
  documents_.close(uri);
  if (auto found = analyses_.find(uri); found != analyses_.end()) {
    retired_.push_back(std::move(found->second));
    analyses_.erase(found);
  }
  outgoing_.push_back(makeNotification("textDocument/publishDiagnostics",
                                       {{"uri", uri}, {"diagnostics", Json::array()}}));
}

void Server::analyse(const std::string& uri) {
  const Document* document = documents_.find(uri);
  AnalysisOptions options;
  options.importPaths = {options_.stdlibDirectory};
  auto analysis = std::make_unique<Analysis>(uri, document->text, options);
  outgoing_.push_back(makeNotification("textDocument/publishDiagnostics",
                                       publishDiagnosticsParams(*analysis, document->version)));
  std::unique_ptr<Analysis>& slot = analyses_[uri];
  if (slot) {
    retired_.push_back(std::move(slot));
  }
  slot = std::move(analysis);
}

const Document* Server::mappedProgram(const Json& params) const {
  std::string uri = documentUri(params);
  const Document* document = documents_.find(uri);
  return document != nullptr && isMappedProgram(uri) ? document : nullptr;
}

const Analysis& Server::analysisOf(const Json& params) const {
  std::string uri = documentUri(params);
  auto found = analyses_.find(uri);
  if (found == analyses_.end()) {
    throw RequestError(ErrorCode::InvalidParams, fmt::format("'{}' is not open", uri));
  }
  return *found->second;
}

} // namespace cncc::lsp
