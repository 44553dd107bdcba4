// The formatter (a front-end library, tested here beside its two users,
// `cncc fmt` and the language server): canonical layout, idempotence, kept
// comments, and a tree that does not change.
#include "session.h"

#include "cncc/frontend/ast_printer.h"
#include "cncc/frontend/formatter.h"
#include "cncc/frontend/parser.h"
#include "cncc/frontend/sema.h"

#include <filesystem>

namespace cncc::lsp::testing {
namespace {

using namespace frontend;

std::optional<std::string> formatText(const std::string& text, int width = 100) {
  SourceManager sources;
  FileId file = sources.addFile("test.cdl", text);
  DiagnosticEngine diagnostics;
  return formatFile(sources, file, diagnostics, {width, 2});
}

std::string formatted(const std::string& text) {
  std::optional<std::string> result = formatText(text);
  EXPECT_TRUE(result.has_value()) << text;
  return result.value_or("");
}

// The checked tree of `text` without positions: what formatting must keep.
std::string checkedTree(const std::string& path, const std::string& text) {
  SourceManager sources;
  FileId file = sources.addFile(path, text);
  DiagnosticEngine diagnostics;
  CheckedProgram program =
      checkProgram(sources, file, {{CNCC_STDLIB_DIR}, {}, "", false}, diagnostics);
  return withoutPositions(dumpAst(program.modules.front(), sources));
}

// The text of each comment, as the lexer finds them, trailing blanks aside.
std::vector<std::string> commentsOf(const std::string& text) {
  SourceManager sources;
  FileId file = sources.addFile("test.cdl", text);
  DiagnosticEngine diagnostics;
  std::vector<SourceSpan> spans;
  lex(sources, file, diagnostics, &spans);
  std::vector<std::string> comments;
  for (SourceSpan span : spans) {
    std::string comment(sources.text(span));
    comments.push_back(comment.substr(0, comment.find_last_not_of(" \t\r") + 1));
  }
  return comments;
}

std::vector<std::string> sampleFiles() {
  std::vector<std::string> files;
  for (const char* folder : {"examples", "stdlib/std"}) {
    for (const auto& entry :
         std::filesystem::directory_iterator(std::string(CNCC_SOURCE_DIR) + "/" + folder)) {
      if (entry.path().extension() == ".cdl") {
        files.push_back(entry.path().lexically_relative(CNCC_SOURCE_DIR).string());
      }
    }
  }
  EXPECT_GE(files.size(), 7u);
  return files;
}

TEST(Formatter, IsIdempotentAndKeepsTheCheckedTreeOfEveryExampleAndStdlibFile) {
  for (const std::string& file : sampleFiles()) {
    std::string source = readSourceFile(file);
    std::string once = formatted(source);
    EXPECT_EQ(formatted(once), once) << file;
    EXPECT_EQ(checkedTree(file, once), checkedTree(file, source)) << file;
  }
}

TEST(Formatter, KeepsEveryComment) {
  for (const std::string& file : sampleFiles()) {
    std::string source = readSourceFile(file);
    std::string once = formatted(source);
    EXPECT_EQ(commentsOf(once), commentsOf(source)) << file;
  }
}

TEST(Formatter, CanonicalSpacing) {
  EXPECT_EQ(formatted("const a=1+2*3-(4-5)/6^-2"), "const a = 1 + 2*3 - (4 - 5)/6^-2\n");
  EXPECT_EQ(formatted("const b = ((1))   ..  2*pi"), "const b = 1 .. 2*pi\n");
  EXPECT_EQ(formatted("const c = -(2^2)+(-2)^2"), "const c = -2^2 + (-2)^2\n");
  EXPECT_EQ(formatted("const d = (if a then 1 else 2)+1"), "const d = (if a then 1 else 2) + 1\n");
  EXPECT_EQ(formatted("const e = (1,2).x+[1,2,][0]+(1).x"),
            "const e = (1, 2).x + [1, 2][0] + (1).x\n");
  EXPECT_EQ(formatted("fn f(a,b)=polar(r=a+b*t,t=0..2*pi)"),
            "fn f(a, b) = polar(r = a + b*t, t = 0 .. 2*pi)\n");
  EXPECT_EQ(formatted("const g = arc(center = (0,0), radius = 1, from = 0, to = pi)"),
            "const g = arc(center=(0, 0), radius=1, from=0, to=pi)\n");
}

TEST(Formatter, StatementsOnePerLineInsideBlocks) {
  EXPECT_EQ(formatted("part p(a=1,b=2){units mm;tool 1 diameter = 3 feed=1\n"
                      "curve line((0,0),(a,b)) sweep depth = 2 step=1\n"
                      "for i in 0..3{let x=i}if a>b{}else if b{units inch}else{feed 3}}"),
            "part p(a = 1, b = 2) {\n"
            "  units mm\n"
            "  tool 1 diameter=3 feed=1\n"
            "  curve line((0, 0), (a, b)) sweep depth=2 step=1\n"
            "  for i in 0 .. 3 {\n"
            "    let x = i\n"
            "  }\n"
            "  if a > b {} else if b {\n"
            "    units inch\n"
            "  } else {\n"
            "    feed 3\n"
            "  }\n"
            "}\n");
}

TEST(Formatter, MachineSetUpStatementsAreCanonical) {
  EXPECT_EQ(formatted("part p(){origin   G55;coolant    flood\n"
                      "origin G54.1    P03 // fixture 3\n"
                      "tool 2 diameter=6 length = 12 radius=22\n"
                      "for i in 1..2{coolant off}}"),
            "part p() {\n"
            "  origin G55\n"
            "  coolant flood\n"
            "  origin G54.1 P3 // fixture 3\n"
            "  tool 2 diameter=6 length=12 radius=22\n"
            "  for i in 1 .. 2 {\n"
            "    coolant off\n"
            "  }\n"
            "}\n");
  // A comment between the offset and its P number stays between them.
  EXPECT_EQ(formatted("part p() {\n  origin G54.1 /* pallet */ P12\n}\n"),
            "part p() {\n  origin G54.1 /* pallet */ P12\n}\n");
  EXPECT_EQ(formatText("part p() { origin G60 }"), std::nullopt);
  EXPECT_EQ(formatText("part p() { coolant on }"), std::nullopt);
}

TEST(Formatter, CommentsStayWhereTheyWere) {
  std::string source = "/* head */ import \"std/curves\"   // trailing\n"
                       "// own line\n\n\n"
                       "const a = [ // list\n  1, 2, // two\n  // alone\n  3\n]\n"
                       "part p() { // brace\n\n  // first\n  let b = a;   // after ;\n"
                       "  curve line((0,0),(1,1)) // after the curve\n    tolerance=0.1\n}\n";
  std::string expected = "/* head */ import \"std/curves\" // trailing\n"
                         "// own line\n\n"
                         "const a = [ // list\n  1, 2, // two\n  // alone\n  3\n]\n\n"
                         "part p() { // brace\n  // first\n  let b = a // after ;\n"
                         "  curve line((0, 0), (1, 1)) // after the curve\n    tolerance=0.1\n}\n";
  EXPECT_EQ(formatted(source), expected);
  EXPECT_EQ(formatted(expected), expected);
}

TEST(Formatter, BreaksLongLinesWhereTheParserAllows) {
  std::string source =
      "part p() {\n  curve nurbs(order=4, points=[(0, 0), (1, 1), (2, 0), (3, 1)]) "
      "sweep depth=1 step=1 tolerance=0.01 method=nurbs entry=ramp\n}\n";
  std::string result = formatted(source);
  EXPECT_EQ(result, "part p() {\n  curve nurbs(order=4, points=[(0, 0), (1, 1), (2, 0), (3, 1)]) "
                    "sweep depth=1 step=1 tolerance=0.01\n    method=nurbs entry=ramp\n}\n");
  // Nine points: eight fill the first line (97 columns), the ninth goes on the next.
  std::string points;
  for (int i = 0; i < 9; ++i) {
    points += i == 0 ? "(100, 200)" : ",(100,200)";
  }
  std::string firstLine;
  for (int i = 0; i < 8; ++i) {
    firstLine += i == 0 ? "(100, 200)," : " (100, 200),";
  }
  EXPECT_EQ(formatted("const P = [" + points + "]"),
            "const P = [\n  " + firstLine + "\n  (100, 200)\n]\n");
  std::istringstream lines(formatted(readSourceFile("stdlib/std/curves.cdl")));
  for (std::string line; std::getline(lines, line);) {
    EXPECT_LE(line.size(), 100u) << line;
  }
}

TEST(Formatter, RefusesFilesWithSyntaxErrors) {
  EXPECT_EQ(formatText("part p() { curve }"), std::nullopt);
  EXPECT_EQ(formatText("const a = \"unterminated"), std::nullopt);
  EXPECT_EQ(formatText("const a = 1 @ 2"), std::nullopt);
  // Semantic errors do not stop it.
  EXPECT_EQ(formatText("const a = undefined_name"), "const a = undefined_name\n");
}

TEST(Formatter, EmptyAndCommentOnlyFiles) {
  EXPECT_EQ(formatted(""), "");
  EXPECT_EQ(formatted("\n\n  \n"), "");
  EXPECT_EQ(formatted("// only\r\n"), "// only\n");
}

} // namespace
} // namespace cncc::lsp::testing
