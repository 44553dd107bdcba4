// Lexing and parsing a byte range of a file as if it were the whole file,
// and joining the modules of several ranges into one.
#include "cncc/frontend/ast_printer.h"
#include "cncc/frontend/parser.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace cncc::frontend {
namespace {

const std::string threeItems = "import \"std/curves\"\n"
                               "const depth = 2mm\n"
                               "fn lobes(n, t) = 1 + 0.1 * cos(n * t)\n"
                               "part p(size = 10) {\n"
                               "  tool 1 diameter=6\n"
                               "  for i in 0 .. 3 { curve circle((i, 0), r=size) sweep }\n"
                               "}\n";

std::uint32_t offsetOf(const std::string& text, const std::string& what) {
  return static_cast<std::uint32_t>(text.find(what));
}

std::uint32_t sizeOf(const std::string& text) {
  return static_cast<std::uint32_t>(text.size());
}

TEST(ParseFileRangeTest, TheWholeRangeIsTheWholeFile) {
  SourceManager sources;
  FileId file = sources.addFile("test.cdl", threeItems);
  DiagnosticEngine wholeDiagnostics(0);
  DiagnosticEngine rangeDiagnostics(0);
  Module whole = parseFile(sources, file, wholeDiagnostics);
  Module range = parseFileRange(sources, file, 0, sizeOf(threeItems), rangeDiagnostics);
  EXPECT_EQ(dumpAst(range, sources), dumpAst(whole, sources));
  EXPECT_EQ(range.items.size(), 4u);
  EXPECT_TRUE(wholeDiagnostics.diagnostics().empty());
  EXPECT_TRUE(rangeDiagnostics.diagnostics().empty());
}

TEST(ParseFileRangeTest, TwoHalvesSplitAtAnItemJoinToTheWhole) {
  SourceManager sources;
  FileId file = sources.addFile("test.cdl", threeItems);
  DiagnosticEngine diagnostics(0);
  Module whole = parseFile(sources, file, diagnostics);
  std::uint32_t split = offsetOf(threeItems, "fn lobes");
  Module joined = parseFileRange(sources, file, 0, split, diagnostics);
  {
    Module second = parseFileRange(sources, file, split, sizeOf(threeItems), diagnostics);
    ASSERT_EQ(joined.items.size(), 2u);
    ASSERT_EQ(second.items.size(), 2u);
    EXPECT_EQ(second.items[0]->span.begin, split);
    appendModule(joined, std::move(second));
  } // the items of the second half outlive the module they were parsed into
  EXPECT_TRUE(diagnostics.diagnostics().empty());
  // Each half's arenas (items, part bodies) are the joined module's.
  EXPECT_EQ(joined.arenas.size(), 2 * whole.arenas.size());
  ASSERT_EQ(joined.items.size(), whole.items.size());
  for (std::size_t i = 0; i < whole.items.size(); ++i) {
    EXPECT_EQ(joined.items[i]->kind, whole.items[i]->kind);
    EXPECT_EQ(joined.items[i]->span, whole.items[i]->span);
  }
  EXPECT_EQ(dumpAst(joined, sources), dumpAst(whole, sources));
}

TEST(LexRangeTest, TheRangeEndsTheTokensAndItsFirstTokenStartsALine) {
  SourceManager sources;
  std::string text = "const a = 1 + 2 * 3\n";
  FileId file = sources.addFile("test.cdl", text);
  DiagnosticEngine diagnostics(0);
  std::uint32_t begin = offsetOf(text, "1 +");
  std::uint32_t end = offsetOf(text, " * 3");
  std::vector<Token> tokens = lexRange(sources, file, begin, end, diagnostics);
  ASSERT_EQ(tokens.size(), 4u);
  EXPECT_EQ(tokens[0].kind, TokenKind::Number);
  EXPECT_TRUE(tokens[0].startsLine);
  EXPECT_EQ(tokens[0].span.begin, begin);
  EXPECT_EQ(tokens[1].kind, TokenKind::Plus);
  EXPECT_FALSE(tokens[1].startsLine);
  EXPECT_EQ(tokens[2].kind, TokenKind::Number);
  EXPECT_EQ(tokens[2].span.end, end);
  EXPECT_EQ(tokens[3].kind, TokenKind::EndOfFile);
  EXPECT_EQ(tokens[3].span.begin, end);
  EXPECT_EQ(tokens[3].span.end, end);
}

TEST(LexRangeTest, ATokenCutByTheEndOfTheRangeStopsThere) {
  SourceManager sources;
  std::string text = "const depth = 2mm\n";
  FileId file = sources.addFile("test.cdl", text);
  DiagnosticEngine diagnostics(0);
  std::uint32_t end = offsetOf(text, "pth");
  std::vector<Token> tokens = lexRange(sources, file, 0, end, diagnostics);
  ASSERT_EQ(tokens.size(), 3u);
  EXPECT_EQ(tokens[1].kind, TokenKind::Identifier);
  EXPECT_EQ(tokens[1].text, "de");
  EXPECT_EQ(tokens[2].span.begin, end);
}

TEST(ParseFileRangeTest, AnItemCutByTheEndOfTheRangeIsReportedAtTheEnd) {
  SourceManager sources;
  FileId file = sources.addFile("test.cdl", threeItems);
  DiagnosticEngine diagnostics(0);
  std::uint32_t end = offsetOf(threeItems, " = 2mm");
  Module module = parseFileRange(sources, file, 0, end, diagnostics);
  ASSERT_EQ(diagnostics.diagnostics().size(), 1u);
  const Diagnostic& diagnostic = diagnostics.diagnostics().front();
  EXPECT_EQ(diagnostic.span.begin, end);
  EXPECT_EQ(diagnostic.message, "expected '=' after the constant's name, found end of file");
  ASSERT_EQ(module.items.size(), 2u);
  EXPECT_EQ(module.items[1]->kind, ItemKind::Const);
}

} // namespace
} // namespace cncc::frontend
