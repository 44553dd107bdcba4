// Completion in each context.
#include "session.h"

#include <algorithm>

namespace cncc::lsp::testing {
namespace {

using ::testing::Contains;
using ::testing::Not;

constexpr const char* uri = "file:///t/complete.cdl";

const Json* item(const Json& list, const std::string& label) {
  for (const Json& candidate : list["items"]) {
    if (candidate["label"] == label) {
      return &candidate;
    }
  }
  return nullptr;
}

class CompletionTest : public ::testing::Test {
protected:
  // Opens `text` and completes at the `|` it contains (removed first).
  Json completeAt(std::string text, Json capabilities = Json::object()) {
    std::size_t cursor = text.find('|');
    text.erase(cursor, 1);
    unsigned line = static_cast<unsigned>(std::count(text.begin(), text.begin() + cursor, '\n'));
    std::size_t lineStart = text.rfind('\n', cursor == 0 ? 0 : cursor - 1);
    unsigned character =
        static_cast<unsigned>(lineStart == std::string::npos ? cursor : cursor - lineStart - 1);
    Session session;
    session.initialize(std::move(capabilities));
    session.open(uri, text);
    return session.at("textDocument/completion", uri, line, character);
  }
};

TEST_F(CompletionTest, StdlibModulesAfterImport) {
  Json list = completeAt("import \"st|\n");
  EXPECT_THAT(labels(list), Contains("std/curves"));
  const Json* curves = item(list, "std/curves");
  ASSERT_NE(curves, nullptr);
  EXPECT_EQ((*curves)["textEdit"]["range"]["start"]["character"], 8);
  EXPECT_EQ((*curves)["textEdit"]["newText"], "std/curves");
  Json bare = completeAt("import |\n");
  EXPECT_EQ((*item(bare, "std/curves"))["textEdit"]["newText"], "\"std/curves\"");
}

TEST_F(CompletionTest, ModifiersAfterTheCurve) {
  std::vector<std::string> found =
      labels(completeAt("part p() {\n  curve line((0, 0), (1, 1)) sweep depth=2 |\n}\n"));
  EXPECT_THAT(found, Contains("tolerance"));
  EXPECT_THAT(found, Contains("method"));
  EXPECT_THAT(found, Not(Contains("sweep"))); // already there
  EXPECT_THAT(found, Not(Contains("depth")));
  EXPECT_THAT(found, Not(Contains("line"))); // not an expression position
}

TEST_F(CompletionTest, ModifierChoices) {
  std::vector<std::string> methods =
      labels(completeAt("part p() {\n  curve line((0, 0), (1, 1)) method=|\n}\n"));
  EXPECT_EQ(methods,
            (std::vector<std::string>{"linear", "aspline", "bspline", "cspline", "nurbs"}));
  std::vector<std::string> entries =
      labels(completeAt("part p() {\n  curve line((0, 0), (1, 1)) entry=pl|\n}\n"));
  EXPECT_EQ(entries, (std::vector<std::string>{"plunge", "ramp"}));
}

TEST_F(CompletionTest, InsideTheCurveExpressionOffersNames) {
  std::vector<std::string> found = labels(completeAt("part p() {\n  curve circ|\n}\n"));
  EXPECT_THAT(found, Contains("nurbs"));
  EXPECT_THAT(found, Not(Contains("tolerance")));
  std::vector<std::string> inArguments =
      labels(completeAt("part p(w = 1) {\n  curve line((0, 0), (w, |\n}\n"));
  EXPECT_THAT(inArguments, Contains("w"));
}

TEST_F(CompletionTest, StatementKeywordsAtTheStartOfAStatement) {
  std::vector<std::string> found = labels(completeAt("part p() {\n  units mm\n  |\n}\n"));
  for (const char* keyword : {"units", "tool", "feed", "spindle", "safe", "origin", "coolant",
                              "let", "curve", "for", "if"}) {
    EXPECT_THAT(found, Contains(keyword));
  }
  EXPECT_THAT(found, Not(Contains("part")));
}

TEST_F(CompletionTest, WorkOffsetsAfterOrigin) {
  EXPECT_EQ(labels(completeAt("part p() {\n  origin |\n}\n")),
            (std::vector<std::string>{"G54", "G55", "G56", "G57", "G58", "G59", "G54.1 P1"}));
  EXPECT_EQ(labels(completeAt("part p() {\n  origin G5|\n}\n")).size(), 7u);
}

TEST_F(CompletionTest, CoolantModesAfterCoolant) {
  Json list = completeAt("part p() {\n  coolant |\n}\n");
  EXPECT_EQ(labels(list), (std::vector<std::string>{"flood", "mist", "through", "off"}));
  EXPECT_EQ((*item(list, "flood"))["detail"], "M08: flood coolant");
}

TEST_F(CompletionTest, ToolSettingsAfterTheToolNumber) {
  Json list = completeAt("part p() {\n  tool 1 diameter=6 |\n}\n");
  EXPECT_EQ(labels(list), (std::vector<std::string>{"length", "radius", "spindle", "feed"}));
  EXPECT_NE((*item(list, "length"))["documentation"]["value"].get<std::string>().find("G43 H"),
            std::string::npos);
  // The tool number is an expression: names, not settings.
  EXPECT_THAT(labels(completeAt("part p() {\n  tool |\n}\n")), Not(Contains("diameter")));
  EXPECT_THAT(labels(completeAt("part p() {\n  tool 1 diameter=|\n}\n")), Not(Contains("length")));
}

TEST_F(CompletionTest, NothingInCommentsAndStrings) {
  EXPECT_TRUE(labels(completeAt("part p() {\n  units mm // a no|\n}\n")).empty());
  EXPECT_TRUE(labels(completeAt("const s = \"a \\\" b|\"\n")).empty());
  EXPECT_FALSE(labels(completeAt("const s = \"a\" + |\n")).empty());
}

TEST_F(CompletionTest, ItemKeywordsAtTopLevel) {
  std::vector<std::string> found = labels(completeAt("const a = 1\n|"));
  EXPECT_EQ(found, (std::vector<std::string>{"part", "fn", "const", "import"}));
}

TEST_F(CompletionTest, NamesInScope) {
  std::string text = "import \"std/curves\"\nconst outer = 1\nfn twice(x) = 2*x\n"
                     "part p(depth = 3) {\n  let inner = 2\n  for i in 0 .. 3 {\n"
                     "    let deeper = i\n    curve circle(0, 0, |)\n  }\n  let later = 4\n}\n";
  Json list = completeAt(text);
  std::vector<std::string> found = labels(list);
  for (const char* name :
       {"outer", "twice", "depth", "inner", "i", "deeper", "circle", "sin", "pi", "if", "true"}) {
    EXPECT_THAT(found, Contains(name));
  }
  EXPECT_THAT(found, Not(Contains("later")));
  EXPECT_THAT(found, Not(Contains("x")));
  EXPECT_EQ((*item(list, "depth"))["kind"], 6);
  EXPECT_EQ((*item(list, "outer"))["kind"], 21);
  EXPECT_EQ((*item(list, "twice"))["kind"], 3);
}

TEST_F(CompletionTest, BuiltinsWithNamedArgumentSnippets) {
  Json capabilities = {
      {"textDocument", {{"completion", {{"completionItem", {{"snippetSupport", true}}}}}}}};
  Json list = completeAt("part p() {\n  curve n|\n}\n", capabilities);
  const Json* nurbs = item(list, "nurbs");
  ASSERT_NE(nurbs, nullptr);
  EXPECT_EQ((*nurbs)["insertText"], "nurbs(order=${1:order}, points=${2:points})");
  EXPECT_EQ((*nurbs)["insertTextFormat"], 2);
  EXPECT_EQ((*item(list, "arc"))["insertText"],
            "arc(center=${1:center}, radius=${2:radius}, from=${3:from}, to=${4:to})");
  EXPECT_EQ((*item(list, "atan2"))["insertText"], "atan2(${1:y}, ${2:x})");
  EXPECT_EQ((*nurbs)["detail"], "nurbs(order=k | degree=p, points=L, weights=W?, knots=K?)");
  // Without snippet support: the plain name.
  Json plain = completeAt("part p() {\n  curve n|\n}\n");
  EXPECT_EQ((*item(plain, "nurbs"))["insertText"], "nurbs");
  EXPECT_EQ((*item(plain, "nurbs"))["insertTextFormat"], 1);
}

} // namespace
} // namespace cncc::lsp::testing
