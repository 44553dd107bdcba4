// A language server driven message by message, for the unit tests: JSON in,
// JSON out, no framing.
#pragma once

#include "cncc/lsp/server.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <fstream>
#include <sstream>
#include <string>

namespace cncc::lsp::testing {

inline std::string readSourceFile(const std::string& relativePath) {
  std::ifstream file(std::string(CNCC_SOURCE_DIR) + "/" + relativePath, std::ios::binary);
  std::ostringstream text;
  text << file.rdbuf();
  return text.str();
}

class Session {
public:
  Session() : server_({CNCC_STDLIB_DIR}) {}

  std::vector<Json> send(const Json& message) { return server_.handle(message); }
  std::vector<Json> sendText(std::string_view text) { return server_.handleText(text); }

  // A request's response (the first message with its id).
  Json request(const std::string& method, Json params = Json::object()) {
    int id = nextId_++;
    for (Json& message : send(
             {{"jsonrpc", "2.0"}, {"id", id}, {"method", method}, {"params", std::move(params)}})) {
      if (message.contains("id") && message["id"] == id) {
        return message;
      }
    }
    ADD_FAILURE() << "no response to " << method;
    return nullptr;
  }
  std::vector<Json> notify(const std::string& method, Json params = Json::object()) {
    return send({{"jsonrpc", "2.0"}, {"method", method}, {"params", std::move(params)}});
  }

  Json initialize(Json capabilities = Json::object()) {
    Json response = request("initialize", {{"capabilities", std::move(capabilities)}});
    notify("initialized");
    return response;
  }

  // Opens a document and returns the diagnostics published for it.
  Json open(const std::string& uri, const std::string& text) {
    return publishedDiagnostics(notify(
        "textDocument/didOpen",
        {{"textDocument", {{"uri", uri}, {"languageId", "cdl"}, {"version", 1}, {"text", text}}}}));
  }
  Json replace(const std::string& uri, const std::string& text, int version) {
    return publishedDiagnostics(
        notify("textDocument/didChange", {{"textDocument", {{"uri", uri}, {"version", version}}},
                                          {"contentChanges", {{{"text", text}}}}}));
  }

  // A request about `uri` at a position (hover, definition, completion).
  Json at(const std::string& method, const std::string& uri, unsigned line, unsigned character) {
    return request(method, {{"textDocument", {{"uri", uri}}},
                            {"position", {{"line", line}, {"character", character}}}})["result"];
  }
  Json on(const std::string& method, const std::string& uri) {
    return request(method, {{"textDocument", {{"uri", uri}}}})["result"];
  }

  static Json publishedDiagnostics(const std::vector<Json>& messages) {
    for (const Json& message : messages) {
      if (message.value("method", "") == "textDocument/publishDiagnostics") {
        return message["params"];
      }
    }
    return nullptr;
  }

  Server& server() { return server_; }

private:
  Server server_;
  int nextId_ = 1;
};

// `line` with every `line:column` replaced by `L:C`.
inline std::string replacePositions(const std::string& line) {
  std::string result;
  for (std::size_t i = 0; i < line.size();) {
    bool wordStart = i == 0 || !std::isalnum(static_cast<unsigned char>(line[i - 1]));
    std::size_t digitsEnd = std::min(line.find_first_not_of("0123456789", i), line.size());
    if (wordStart && digitsEnd > i && digitsEnd < line.size() && line[digitsEnd] == ':') {
      std::size_t columnEnd =
          std::min(line.find_first_not_of("0123456789", digitsEnd + 1), line.size());
      if (columnEnd > digitsEnd + 1) {
        result += "L:C";
        i = columnEnd;
        continue;
      }
    }
    result += line[i++];
  }
  return result;
}

// The dump without positions, its first line (the file's name) and the
// Error statements a lone `;` leaves (the formatter drops those).
inline std::string withoutPositions(const std::string& dump) {
  std::istringstream lines(dump);
  std::string result;
  std::string line;
  std::getline(lines, line);
  while (std::getline(lines, line)) {
    std::size_t text = line.find_first_not_of(' ');
    if (text == std::string::npos || line.compare(text, 6, "Error ") != 0) {
      result += replacePositions(line) + "\n";
    }
  }
  return result;
}

// The labels of a completion result.
inline std::vector<std::string> labels(const Json& completionList) {
  std::vector<std::string> result;
  for (const Json& item : completionList["items"]) {
    result.push_back(item["label"]);
  }
  return result;
}

} // namespace cncc::lsp::testing
