// Document symbols, formatting and semantic tokens.
#include "session.h"

namespace cncc::lsp::testing {
namespace {

constexpr const char* uri = "file:///t/features.cdl";

TEST(DocumentSymbols, PartsFunctionsConstantsAndLets) {
  Session session;
  session.initialize();
  session.open(uri, "const c = 3\nfn f(x) = x\npart p(a = 1) {\n  let l = 2\n"
                    "  for i in 0 .. 1 {\n    let m = i\n  }\n}\n");
  Json symbols = session.on("textDocument/documentSymbol", uri);
  ASSERT_EQ(symbols.size(), 3u);
  EXPECT_EQ(symbols[0]["name"], "c");
  EXPECT_EQ(symbols[0]["kind"], 14);
  EXPECT_EQ(symbols[0]["detail"], "3");
  EXPECT_EQ(symbols[1]["name"], "f");
  EXPECT_EQ(symbols[1]["kind"], 12);
  EXPECT_EQ(symbols[1]["detail"], "f(x)");
  const Json& part = symbols[2];
  EXPECT_EQ(part["name"], "p");
  EXPECT_EQ(part["kind"], 5);
  EXPECT_EQ(part["range"]["end"]["line"], 7);
  std::vector<std::string> children;
  for (const Json& child : part["children"]) {
    children.push_back(child["name"]);
  }
  EXPECT_EQ(children, (std::vector<std::string>{"a", "l", "m"}));
  EXPECT_EQ(part["selectionRange"]["start"], (Json{{"line", 2}, {"character", 5}}));
}

TEST(DocumentSymbols, SkipsItemsWithoutNames) {
  Session session;
  session.initialize();
  session.open(uri, "part (\nfn = 3\nconst\n");
  EXPECT_TRUE(session.on("textDocument/documentSymbol", uri).empty());
}

Json format(Session& session, const std::string& text) {
  session.replace(uri, text, 2);
  return session.request("textDocument/formatting",
                         {{"textDocument", {{"uri", uri}}},
                          {"options", {{"tabSize", 2}, {"insertSpaces", true}}}})["result"];
}

TEST(Formatting, ReplacesTheDocumentWithTheCanonicalText) {
  Session session;
  session.initialize();
  session.open(uri, "");
  Json edits = format(session, "part p(){\ncurve line((0,0),(1,1))   // cut\n}");
  ASSERT_EQ(edits.size(), 1u);
  EXPECT_EQ(edits[0]["newText"], "part p() {\n  curve line((0, 0), (1, 1)) // cut\n}\n");
  EXPECT_EQ(edits[0]["range"]["start"], (Json{{"line", 0}, {"character", 0}}));
  EXPECT_EQ(edits[0]["range"]["end"], (Json{{"line", 2}, {"character", 1}}));
  EXPECT_TRUE(format(session, edits[0]["newText"]).empty());  // already formatted
  EXPECT_TRUE(format(session, "part p() { curve }").empty()); // a syntax error
}

// Decodes the relative encoding into (line, start, length, type, modifiers).
std::vector<std::array<unsigned, 5>> decode(const Json& data) {
  std::vector<std::array<unsigned, 5>> tokens;
  unsigned line = 0;
  unsigned start = 0;
  for (std::size_t i = 0; i + 4 < data.size(); i += 5) {
    unsigned deltaLine = data[i];
    line += deltaLine;
    start = deltaLine == 0 ? start + data[i + 1].get<unsigned>() : data[i + 1].get<unsigned>();
    tokens.push_back({line, start, data[i + 2], data[i + 3], data[i + 4]});
  }
  return tokens;
}

TEST(SemanticTokens, ClassifiesNamesByWhatTheyAre) {
  Session session;
  Json capabilities = session.initialize()["result"]["capabilities"];
  Json legend = capabilities["semanticTokensProvider"]["legend"]["tokenTypes"];
  auto type = [&](const std::string& name) {
    for (unsigned i = 0; i < legend.size(); ++i) {
      if (legend[i] == name) {
        return i;
      }
    }
    return 99u;
  };
  session.open(
      uri,
      "const c = 1 /* a\nb */\npart p(w = 2) {\n  curve line((0, 0), (w, c)) tolerance=0.1\n}\n");
  auto tokens = decode(session.on("textDocument/semanticTokens/full", uri)["data"]);
  auto find = [&](unsigned line, unsigned start) -> std::array<unsigned, 5> {
    for (const auto& token : tokens) {
      if (token[0] == line && token[1] == start) {
        return token;
      }
    }
    return {99, 99, 99, 99, 99};
  };
  EXPECT_EQ(find(0, 0)[3], type("keyword"));  // const
  EXPECT_EQ(find(0, 6)[3], type("variable")); // c (readonly, declaration)
  EXPECT_EQ(find(0, 6)[4], 3u);
  EXPECT_EQ(find(0, 12)[3], type("comment")); // first line of the block comment
  EXPECT_EQ(find(0, 12)[2], 4u);
  EXPECT_EQ(find(1, 0)[3], type("comment"));    // its second line
  EXPECT_EQ(find(2, 7)[3], type("parameter"));  // w
  EXPECT_EQ(find(3, 2)[3], type("keyword"));    // curve
  EXPECT_EQ(find(3, 8)[3], type("function"));   // line (a builtin)
  EXPECT_EQ(find(3, 8)[4], 4u);                 // defaultLibrary
  EXPECT_EQ(find(3, 22)[3], type("parameter")); // w
  EXPECT_EQ(find(3, 25)[3], type("variable"));  // c
  EXPECT_EQ(find(3, 29)[3], type("property"));  // tolerance
  EXPECT_EQ(find(3, 39)[3], type("number"));    // 0.1
}

} // namespace
} // namespace cncc::lsp::testing
