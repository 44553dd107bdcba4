// The protocol's lifecycle and its error answers.
#include "session.h"

namespace cncc::lsp::testing {
namespace {

int errorCode(const Json& response) {
  return response.contains("error") ? response["error"]["code"].get<int>() : 0;
}

TEST(ServerLifecycle, RequestsBeforeInitializeAreRefused) {
  Session session;
  EXPECT_EQ(errorCode(session.request("textDocument/hover")), -32002);
  // Notifications before initialize are dropped without an answer.
  EXPECT_TRUE(session.notify("textDocument/didOpen", {{"textDocument", {{"uri", "u"}}}}).empty());
  Json response = session.initialize();
  EXPECT_TRUE(response["result"]["capabilities"]["hoverProvider"].get<bool>());
  EXPECT_EQ(response["result"]["capabilities"]["textDocumentSync"]["change"], 2);
  EXPECT_EQ(errorCode(session.request("initialize")), -32600);
}

TEST(ServerLifecycle, ShutdownThenExit) {
  Session session;
  session.initialize();
  Json shutdown = session.request("shutdown");
  EXPECT_TRUE(shutdown.contains("result"));
  EXPECT_TRUE(shutdown["result"].is_null());
  EXPECT_EQ(errorCode(session.request("textDocument/hover")), -32600);
  EXPECT_FALSE(session.server().exitRequested());
  session.notify("exit");
  EXPECT_TRUE(session.server().exitRequested());
  EXPECT_EQ(session.server().exitCode(), 0);
}

TEST(ServerLifecycle, ExitWithoutShutdownIsAnError) {
  Session session;
  session.initialize();
  session.notify("exit");
  EXPECT_TRUE(session.server().exitRequested());
  EXPECT_EQ(session.server().exitCode(), 1);
}

TEST(ServerErrors, MalformedMessages) {
  Session session;
  session.initialize();
  for (std::string_view text : {"{", "", "nul", "{\"jsonrpc\": \"2.0\", \"id\": 1, "}) {
    std::vector<Json> answer = session.sendText(text);
    ASSERT_EQ(answer.size(), 1u) << text;
    EXPECT_EQ(errorCode(answer[0]), -32700);
    EXPECT_TRUE(answer[0]["id"].is_null());
  }
  for (std::string_view text : {"[]", "42", "{\"id\": 3}", "{\"id\": 4, \"method\": 7}",
                                "{\"id\": [1], \"method\": \"shutdown\"}"}) {
    std::vector<Json> answer = session.sendText(text);
    ASSERT_EQ(answer.size(), 1u) << text;
    EXPECT_EQ(errorCode(answer[0]), -32600) << text;
  }
  EXPECT_EQ(session.sendText("{\"id\": 4, \"method\": 7}")[0]["id"], 4);
  // A response from the client (the server sends no requests) is ignored.
  EXPECT_TRUE(session.sendText("{\"jsonrpc\": \"2.0\", \"id\": 9, \"result\": null}").empty());
}

TEST(ServerErrors, UnknownMethodsAndBadParams) {
  Session session;
  session.initialize();
  EXPECT_EQ(errorCode(session.request("workspace/frobnicate")), -32601);
  EXPECT_TRUE(session.notify("$/cancelRequest", {{"id", 1}}).empty());
  EXPECT_TRUE(session.notify("workspace/unknownNotification").empty());
  EXPECT_EQ(errorCode(session.request("textDocument/hover", {{"textDocument", {{"uri", "u"}}}})),
            -32602);
  EXPECT_EQ(errorCode(session.request("textDocument/hover", Json::array())), -32602);
  Json notOpen =
      session.request("textDocument/hover", {{"textDocument", {{"uri", "file:///nope.cdl"}}},
                                             {"position", {{"line", 0}, {"character", 0}}}});
  EXPECT_EQ(errorCode(notOpen), -32602);
  Json negative =
      session.request("textDocument/hover", {{"textDocument", {{"uri", "u"}}},
                                             {"position", {{"line", -1}, {"character", 0}}}});
  EXPECT_EQ(errorCode(negative), -32602);
  // A failing notification gets no response, only a log message.
  std::vector<Json> changed = session.notify(
      "textDocument/didChange", {{"textDocument", {{"uri", "file:///nope.cdl"}, {"version", 2}}},
                                 {"contentChanges", Json::array()}});
  ASSERT_EQ(changed.size(), 1u);
  EXPECT_EQ(changed[0]["method"], "window/logMessage");
}

TEST(ServerLifecycle, MalformedCapabilitiesAreIgnored) {
  for (Json capabilities :
       {Json(5), Json::array({1, 2}), Json{{"textDocument", {{"completion", Json::array({1})}}}},
        Json{{"textDocument", {{"completion", {{"completionItem", "yes"}}}}}}}) {
    Session session;
    Json response = session.initialize(capabilities);
    EXPECT_TRUE(response.contains("result")) << capabilities.dump();
  }
}

TEST(ServerErrors, StringIdsAreEchoed) {
  Session session;
  std::vector<Json> answer = session.send(
      {{"jsonrpc", "2.0"}, {"id", "abc"}, {"method", "initialize"}, {"params", Json::object()}});
  ASSERT_EQ(answer.size(), 1u);
  EXPECT_EQ(answer[0]["id"], "abc");
  EXPECT_TRUE(answer[0].contains("result"));
}

TEST(ServerDocuments, CloseClearsDiagnostics) {
  Session session;
  session.initialize();
  Json opened = session.open("file:///t/a.cdl", "part p() { curve }");
  EXPECT_FALSE(opened["diagnostics"].empty());
  Json closed = Session::publishedDiagnostics(
      session.notify("textDocument/didClose", {{"textDocument", {{"uri", "file:///t/a.cdl"}}}}));
  EXPECT_TRUE(closed["diagnostics"].empty());
  EXPECT_EQ(errorCode(session.request("textDocument/documentSymbol",
                                      {{"textDocument", {{"uri", "file:///t/a.cdl"}}}})),
            -32602);
}

} // namespace
} // namespace cncc::lsp::testing
