// A document mid-edit, with every kind of syntax error, and positions
// anywhere: every request gets an answer and nothing throws or crashes.
#include "session.h"

#include <filesystem>

namespace cncc::lsp::testing {
namespace {

constexpr const char* uri = "file:///t/editing.cdl";

// Asks everything the server offers about `text`, at `positions` spots
// spread over the document and beyond its end.
void askEverything(Session& session, const std::string& text, int version, int positions) {
  Json published = session.replace(uri, text, version);
  ASSERT_TRUE(published.is_object()) << "no diagnostics for version " << version;
  EXPECT_EQ(published["version"], version);
  unsigned lines = static_cast<unsigned>(std::count(text.begin(), text.end(), '\n')) + 2;
  for (int i = 0; i < positions; ++i) {
    unsigned line = static_cast<unsigned>(i) * lines / static_cast<unsigned>(positions);
    unsigned character = static_cast<unsigned>(i * 7 % 50);
    for (const char* method :
         {"textDocument/hover", "textDocument/definition", "textDocument/completion"}) {
      Json response =
          session.request(method, {{"textDocument", {{"uri", uri}}},
                                   {"position", {{"line", line}, {"character", character}}}});
      EXPECT_TRUE(response.contains("result")) << method << " " << response.dump();
    }
  }
  for (const char* method : {"textDocument/documentSymbol", "textDocument/semanticTokens/full",
                             "textDocument/formatting"}) {
    Json response = session.request(method, {{"textDocument", {{"uri", uri}}}});
    EXPECT_TRUE(response.contains("result")) << method << " " << response.dump();
  }
}

// Every prefix of an example at a stride, as if it were being typed.
TEST(Robustness, AnExampleBeingTyped) {
  std::string text = readSourceFile("examples/rosette_plate.cdl");
  Session session;
  session.initialize();
  session.open(uri, "");
  int version = 1;
  for (std::size_t length = 0; length <= text.size(); length += 37) {
    askEverything(session, text.substr(0, length), ++version, 3);
  }
}

// Each diagnostic's golden input: every kind of error the front end knows.
TEST(Robustness, EveryDiagnosticGoldenInput) {
  Session session;
  session.initialize();
  session.open(uri, "");
  int version = 1;
  std::filesystem::path folder =
      std::filesystem::path(CNCC_SOURCE_DIR) / "tests/golden/diagnostics";
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    if (entry.path().extension() == ".cdl") {
      askEverything(session,
                    readSourceFile(entry.path().lexically_relative(CNCC_SOURCE_DIR).string()),
                    ++version, 6);
      ++files;
    }
  }
  EXPECT_GE(files, 30);
}

TEST(Robustness, HostileText) {
  Session session;
  session.initialize();
  session.open(uri, "");
  std::string nested(5000, '(');
  std::string deepBlocks;
  for (int i = 0; i < 400; ++i) {
    deepBlocks += "if a {";
  }
  int version = 1;
  for (const std::string& text :
       {nested, "part p() {" + deepBlocks, std::string("\0\x01\xff\xfe part", 9),
        std::string("/* never closed"), std::string("\"\xF0\x9F\x98"), std::string(1, '\n')}) {
    askEverything(session, text, ++version, 4);
  }
}

} // namespace
} // namespace cncc::lsp::testing
