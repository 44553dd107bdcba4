// Checking a large file on two threads finds exactly what checking it on
// one finds: the same diagnostics in the same order (also past the error
// limit and when the evaluation budget runs out), the same declarations
// with the same values, the same references.
#include "cncc/frontend/ast_printer.h"
#include "cncc/frontend/sema.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <fmt/format.h>
#include <string>
#include <vector>

namespace cncc::frontend {
namespace {

struct Outcome {
  std::vector<std::string> diagnostics;
  std::vector<std::string> declarations;
  std::vector<std::string> references;
  std::size_t scopeExtents = 0;
  std::string syntaxTree;
};

std::string describe(const Declaration& declaration) {
  std::string text = fmt::format("{} {} {}..{}", declarationKindName(declaration.kind),
                                 declaration.name, declaration.span.begin, declaration.span.end);
  if (declaration.value && declaration.value->type.kind == TypeKind::Num) {
    text += fmt::format(" = {}", declaration.value->number);
  } else if (declaration.value) {
    text += fmt::format(" : {}", typeName(declaration.value->type));
  }
  return text;
}

Outcome checkWith(const std::string& text, unsigned threads, std::size_t errorLimit,
                  std::size_t evaluationSteps = CheckOptions().evaluationSteps) {
  SourceManager sources;
  FileId file = sources.addFile("large.cdl", text);
  DiagnosticEngine diagnostics(errorLimit);
  CheckOptions options;
  options.importPaths.push_back(CNCC_STDLIB_DIR);
  options.threads = threads;
  options.evaluationSteps = evaluationSteps;
  CheckedProgram program = checkProgram(sources, file, options, diagnostics);
  Outcome outcome;
  for (const Diagnostic& diagnostic : diagnostics.diagnostics()) {
    outcome.diagnostics.push_back(renderText(diagnostic, sources));
  }
  for (const Declaration& declaration : program.declarations) {
    outcome.declarations.push_back(describe(declaration));
  }
  for (const Reference& reference : program.references) {
    outcome.references.push_back(fmt::format("{}..{} {}", reference.span.begin, reference.span.end,
                                             reference.declaration->name));
  }
  outcome.scopeExtents = program.scopeExtents.size();
  outcome.syntaxTree = dumpAst(program.modules.front(), sources);
  return outcome;
}

void expectSame(const Outcome& oneThread, const Outcome& twoThreads) {
  EXPECT_EQ(oneThread.diagnostics, twoThreads.diagnostics);
  EXPECT_EQ(oneThread.declarations, twoThreads.declarations);
  EXPECT_EQ(oneThread.references, twoThreads.references);
  EXPECT_EQ(oneThread.scopeExtents, twoThreads.scopeExtents);
  EXPECT_EQ(oneThread.syntaxTree, twoThreads.syntaxTree);
}

// Parts of several shapes; every `faultEvery`-th one has mistakes of the
// checker (an unused let, a point where a number belongs) and of evaluation
// (a fn that divides by zero, a shared fn reported once).
std::string manyParts(int count, int faultEvery) {
  std::string text = "import \"std/curves\"\n"
                     "const clearance = 5\n"
                     "fn lobes(k, t) = 1 + 0.2*cos(k*t)\n"
                     "fn pocket(size) = polar(r = size*lobes(5, t), t = 0 .. 2*pi)\n"
                     "fn inverse(x) = 1 / x\n";
  for (int i = 0; i < count; ++i) {
    bool faulty = faultEvery > 0 && i % faultEvery == 0;
    text += fmt::format("part p{}(depth = {}, count = 3) {{\n"
                        "  tool 1 diameter=6 feed=200\n"
                        "  safe z=clearance\n"
                        "  let size = depth * 2\n"
                        "  for j in 0 .. count - 1 {{\n"
                        "    curve rotate(pocket(size + j), j * 30deg) sweep depth=depth step=1\n"
                        "  }}\n"
                        "  curve archimedean_spiral(1, 0.5, 2) tolerance=0.01\n",
                        i, 2 + i % 3);
    if (faulty) {
      text += fmt::format("  let unused{} = 1\n"
                          "  feed (1, 2)\n"
                          "  curve line((0, 0), (1 / (depth - {}), 1))\n"
                          "  curve line((0, 0), (inverse(count - 3), 1))\n",
                          i, 2 + i % 3);
    }
    text += "}\n";
  }
  return text;
}

TEST(ParallelCheckTest, ACleanFileChecksTheSameOnTwoThreads) {
  std::string text = manyParts(60, 0);
  Outcome oneThread = checkWith(text, 1, 50);
  EXPECT_TRUE(oneThread.diagnostics.empty());
  // The parts' polar and param curves declared their `t` on both threads.
  EXPECT_TRUE(std::any_of(
      oneThread.declarations.begin(), oneThread.declarations.end(),
      [](const std::string& declaration) { return declaration.starts_with("curve parameter t"); }));
  expectSame(oneThread, checkWith(text, 2, 50));
}

TEST(ParallelCheckTest, MistakesAreReportedTheSameOnTwoThreads) {
  std::string text = manyParts(60, 7);
  Outcome oneThread = checkWith(text, 1, 0);
  // Nine faulty parts: an unused let, a type mistake and a division by zero
  // each; the shared inverse(count - 3) division once.
  ASSERT_EQ(oneThread.diagnostics.size(), 9u * 3 + 1);
  expectSame(oneThread, checkWith(text, 2, 0));
}

TEST(ParallelCheckTest, TheErrorLimitStopsAtTheSameDiagnostic) {
  std::string text = manyParts(200, 1);
  Outcome oneThread = checkWith(text, 1, 50);
  ASSERT_EQ(oneThread.diagnostics.size(), 50u + 1 + 200); // errors, the note, the warnings
  expectSame(oneThread, checkWith(text, 2, 50));
}

// The file is parsed as two halves split before an item past the middle;
// a problem in a half, or a split that lands in a comment or a part's
// braces, parses the whole file again.
TEST(ParallelCheckTest, ASyntaxErrorInEitherHalfIsReportedOnce) {
  std::string clean = manyParts(40, 0);
  for (std::size_t at : {clean.size() / 4, clean.size() * 3 / 4}) {
    std::string text = clean;
    text.insert(text.find("  safe z=", at), "  let = 4\n");
    Outcome oneThread = checkWith(text, 1, 50);
    ASSERT_EQ(oneThread.diagnostics.size(), 1u);
    expectSame(oneThread, checkWith(text, 2, 50));
  }
}

TEST(ParallelCheckTest, ASplitInsideACommentOrBracesParsesTheWholeFile) {
  // The middle third is a comment, with lines that would start parts; then
  // a part with such a line inside its braces.
  std::string parts = manyParts(60, 0);
  std::size_t third = parts.find("\npart ", parts.size() / 3) + 1;
  std::size_t twoThirds = parts.find("\npart ", parts.size() * 2 / 3) + 1;
  std::string commented = parts.substr(0, third) + "/* the old parts:\n" +
                          parts.substr(third, twoThirds - third) + "*/\n" + parts.substr(twoThirds);
  std::string nested =
      parts.substr(0, parts.size() / 2) + "\npart inner() {}\n" + parts.substr(parts.size() / 2);
  for (const std::string& text : {commented, nested}) {
    Outcome oneThread = checkWith(text, 1, 50);
    expectSame(oneThread, checkWith(text, 2, 50));
  }
  EXPECT_TRUE(checkWith(commented, 1, 50).diagnostics.empty());
  EXPECT_FALSE(checkWith(nested, 1, 50).diagnostics.empty());
}

// The 60 parts take some 55,000 steps. Evaluating in order with a smaller
// budget leaves the lets and parameters of the last parts without values.
void expectBudgetRunsOutAtTheSamePlace(std::size_t budget, std::size_t firstPart,
                                       std::size_t lastPart) {
  std::string text = manyParts(60, 0);
  Outcome unlimited = checkWith(text, 1, 50);
  Outcome oneThread = checkWith(text, 1, 50, budget);
  std::size_t same = 0;
  while (same < unlimited.declarations.size() &&
         oneThread.declarations[same] == unlimited.declarations[same]) {
    ++same;
  }
  ASSERT_LT(same, unlimited.declarations.size());
  // The first declaration without its value is one of the expected parts'.
  std::size_t begin = std::stoul(oneThread.declarations[same].substr(
      oneThread.declarations[same].rfind(' ', oneThread.declarations[same].find(".."))));
  EXPECT_GT(begin, text.find(fmt::format("part p{}(", firstPart)));
  EXPECT_LT(begin, text.find(fmt::format("part p{}(", lastPart)));
  expectSame(oneThread, checkWith(text, 2, 50, budget));
}

TEST(ParallelCheckTest, TheBudgetRunsOutInTheFirstHalfAtTheSamePlace) {
  expectBudgetRunsOutAtTheSamePlace(12'000, 5, 30);
}

TEST(ParallelCheckTest, TheBudgetRunsOutInTheSecondHalfAtTheSamePlace) {
  expectBudgetRunsOutAtTheSamePlace(40'000, 30, 59);
}

} // namespace
} // namespace cncc::frontend
