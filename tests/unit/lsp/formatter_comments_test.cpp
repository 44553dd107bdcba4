// The formatter against comments and line breaks anywhere: each is inserted
// in turn at every token boundary of a sample, and wherever the result still
// parses, formatting must keep the comment, be idempotent and keep the tree.
#include "session.h"

#include "cncc/frontend/ast_printer.h"
#include "cncc/frontend/formatter.h"
#include "cncc/frontend/parser.h"

namespace cncc::lsp::testing {
namespace {

using namespace frontend;

struct Formatted {
  bool parses = false;
  std::optional<std::string> text;
  std::string tree; // without positions and without `;` (Error) statements
};

Formatted formatAndDump(const std::string& source) {
  SourceManager sources;
  FileId file = sources.addFile("sample.cdl", source);
  DiagnosticEngine diagnostics;
  Formatted result;
  result.text = formatFile(sources, file, diagnostics);
  result.parses = result.text.has_value();
  if (result.parses) {
    DiagnosticEngine ignored;
    result.tree = withoutPositions(dumpAst(parseFile(sources, file, ignored), sources));
  }
  return result;
}

// The offsets between tokens, where a comment or a line break may go.
std::vector<std::uint32_t> tokenBoundaries(const std::string& source) {
  SourceManager sources;
  FileId file = sources.addFile("sample.cdl", source);
  DiagnosticEngine diagnostics;
  std::vector<std::uint32_t> boundaries;
  for (const Token& token : lex(sources, file, diagnostics)) {
    boundaries.push_back(token.span.begin);
  }
  return boundaries;
}

// `stride` > 1 tries every stride-th boundary (the long samples).
void checkInsertions(const std::string& source, const std::string& name, std::size_t stride = 1) {
  Formatted original = formatAndDump(source);
  ASSERT_TRUE(original.parses) << name;
  int formatted = 0;
  std::vector<std::uint32_t> boundaries = tokenBoundaries(source);
  for (std::size_t b = 0; b < boundaries.size(); b += stride) {
    std::uint32_t offset = boundaries[b];
    for (std::string insertion : {" /* mark */ ", " // mark\n", "\n// mark\n", "\n\n"}) {
      std::string edited = source.substr(0, offset) + insertion + source.substr(offset);
      Formatted once = formatAndDump(edited);
      if (!once.parses) {
        continue; // e.g. a line comment splitting a statement the parser reads by lines
      }
      ++formatted;
      Formatted twice = formatAndDump(*once.text);
      ASSERT_TRUE(twice.parses) << name << " at " << offset << ":\n" << *once.text;
      EXPECT_EQ(*twice.text, *once.text) << name << " at " << offset << " with " << insertion;
      EXPECT_EQ(twice.tree, once.tree) << name << " at " << offset << ":\n" << *once.text;
      if (insertion.find("mark") != std::string::npos) {
        EXPECT_NE(once.text->find("mark"), std::string::npos) << name << " at " << offset;
      }
    }
  }
  EXPECT_GT(formatted, 100) << name;
}

TEST(FormatterComments, AnywhereInAnExample) {
  checkInsertions(readSourceFile("examples/cam_profile.cdl"), "cam_profile", 2);
}

TEST(FormatterComments, AnywhereInTheStdlib) {
  checkInsertions(readSourceFile("stdlib/std/curves.cdl"), "curves", 5);
}

TEST(FormatterComments, AnywhereInExpressionsAndBlocks) {
  checkInsertions("const a = -(1 + 2)^2*[1, (2, 3).x][0] + (if a then 1 else 2)\n"
                  "fn f(x, y) = x*y .. 2\n"
                  "part p(q = 1) {\n  tool 1 diameter=2 feed=3\n  safe z=1; units mm\n"
                  "  if q > 1 { feed 2 } else if q < 0 {} else { spindle 3 }\n"
                  "  for i in 0 .. 2 { curve line((0, 0), (i, 1)) sweep depth=1 step=1 }\n}\n",
                  "constructs");
}

} // namespace
} // namespace cncc::lsp::testing
