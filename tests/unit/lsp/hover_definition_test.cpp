// Hovers and go-to-definition.
#include "session.h"

namespace cncc::lsp::testing {
namespace {

constexpr const char* uri = "file:///t/hover.cdl";

const char* source = R"(import "std/curves"
const clearance = 2.5mm
part plate(depth = 3, step = 1) { tool 1 diameter=6 feed=300
  let edge = line((0, 0), (3, 4))
  let bend = arc(center=(0, 0), radius=2, from=0, to=pi)
  let P = [(0, 0), (1, 2), (3, 2), (4, 0)]
  let spline = nurbs(order=3, points=P)
  let flower = rose(10, 3)
  safe z=clearance
  curve circle(0, 0, depth) sweep depth=depth step=step
  curve spline
}
)";

class HoverTest : public ::testing::Test {
protected:
  void SetUp() override {
    session.initialize();
    Json published = session.open(uri, source);
    for (const Json& diagnostic : published["diagnostics"]) {
      EXPECT_NE(diagnostic["severity"], 1) << diagnostic.dump(); // warnings for unused lets only
    }
  }
  std::string hoverText(unsigned line, unsigned character) {
    Json result = session.at("textDocument/hover", uri, line, character);
    return result.is_null() ? "" : result["contents"]["value"].get<std::string>();
  }
  Session session;
};

TEST_F(HoverTest, ConstantShowsItsValue) {
  std::string text = hoverText(8, 10); // clearance in `safe z=clearance`
  EXPECT_NE(text.find("const clearance: num"), std::string::npos) << text;
  EXPECT_NE(text.find("value 2.5"), std::string::npos) << text;
}

TEST_F(HoverTest, PartParameterShowsItsDefault) {
  std::string text = hoverText(9, 22); // depth in `circle(0, 0, depth)`
  EXPECT_NE(text.find("depth: num"), std::string::npos) << text;
  EXPECT_NE(text.find("part parameter"), std::string::npos) << text;
  EXPECT_NE(text.find("default 3"), std::string::npos) << text;
}

TEST_F(HoverTest, BuiltinShowsSignatureAndDescription) {
  std::string text = hoverText(6, 17); // nurbs
  EXPECT_NE(text.find("nurbs(order=k | degree=p, points=L, weights=W?, knots=K?)"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("rational B-spline"), std::string::npos) << text;
}

TEST_F(HoverTest, StdlibFunctionShowsSignatureAndItsComment) {
  std::string text = hoverText(9, 9); // circle
  EXPECT_NE(text.find("fn circle(cx, cy, radius)"), std::string::npos) << text;
  EXPECT_NE(text.find("Full circle of the given radius"), std::string::npos) << text;
  EXPECT_NE(text.find("std/curves.cdl"), std::string::npos) << text;
}

TEST_F(HoverTest, CurvesShowKindDegreePointsAndLength) {
  std::string line = hoverText(3, 7);
  EXPECT_NE(line.find("let edge: curve"), std::string::npos) << line;
  EXPECT_NE(line.find("length 5"), std::string::npos) << line;
  std::string arc = hoverText(4, 7);
  EXPECT_NE(arc.find("arc, radius 2, length 6.28319"), std::string::npos) << arc;
  std::string spline = hoverText(6, 7);
  EXPECT_NE(spline.find("nurbs curve, degree 2, 4 control points, length"), std::string::npos)
      << spline;
  std::string polar = hoverText(7, 7); // rose: a polar curve
  EXPECT_NE(polar.find("length not computed"), std::string::npos) << polar;
}

TEST_F(HoverTest, NothingOnKeywordsAndOutOfRange) {
  EXPECT_EQ(hoverText(2, 1), "");    // `part`
  EXPECT_EQ(hoverText(500, 3), "");  // past the end
  EXPECT_EQ(hoverText(3, 9999), ""); // past the end of the line
}

TEST_F(HoverTest, RangeIsTheName) {
  Json result = session.at("textDocument/hover", uri, 8, 10);
  EXPECT_EQ(result["range"]["start"], (Json{{"line", 8}, {"character", 9}}));
  EXPECT_EQ(result["range"]["end"], (Json{{"line", 8}, {"character", 18}}));
}

TEST_F(HoverTest, DefinitionInTheDocument) {
  Json location = session.at("textDocument/definition", uri, 10, 9); // spline
  EXPECT_EQ(location["uri"], uri);
  EXPECT_EQ(location["range"]["start"], (Json{{"line", 6}, {"character", 6}}));
}

TEST_F(HoverTest, DefinitionIntoTheStdlib) {
  Json location = session.at("textDocument/definition", uri, 9, 9); // circle
  std::string expected = "file://" + std::string(CNCC_STDLIB_DIR) + "/std/curves.cdl";
  EXPECT_EQ(location["uri"], expected);
  unsigned line = location["range"]["start"]["line"];
  std::string stdlib = readSourceFile("stdlib/std/curves.cdl");
  std::istringstream lines(stdlib);
  std::string text;
  for (unsigned i = 0; i <= line; ++i) {
    std::getline(lines, text);
  }
  EXPECT_EQ(text.substr(0, 9), "fn circle");
}

TEST_F(HoverTest, DefinitionOfAnImportIsTheModule) {
  Json location = session.at("textDocument/definition", uri, 0, 10);
  EXPECT_EQ(location["uri"], "file://" + std::string(CNCC_STDLIB_DIR) + "/std/curves.cdl");
}

TEST_F(HoverTest, NoDefinitionForBuiltins) {
  EXPECT_TRUE(session.at("textDocument/definition", uri, 6, 17).is_null());
}

const char* setupSource = R"(part plate() {
  origin G54.1 P3
  tool 2 diameter=6 feed=300 length=12 radius=22
  for i in 1 .. 2 {
    coolant flood
  }
}
)";

class SetupHoverTest : public ::testing::Test {
protected:
  void SetUp() override {
    session.initialize();
    session.open(uri, setupSource);
  }
  Json hoverAt(unsigned line, unsigned character) {
    return session.at("textDocument/hover", uri, line, character);
  }
  std::string hoverText(unsigned line, unsigned character) {
    Json result = hoverAt(line, character);
    return result.is_null() ? "" : result["contents"]["value"].get<std::string>();
  }
  Session session;
};

TEST_F(SetupHoverTest, OriginShowsItsOffsetAndWhatItDoes) {
  std::string text = hoverText(1, 4); // `origin`
  EXPECT_NE(text.find("origin G54.1 P3"), std::string::npos) << text;
  EXPECT_NE(text.find("work offset"), std::string::npos) << text;
  EXPECT_EQ(hoverText(1, 16), text); // on `P3`
  Json result = hoverAt(1, 4);
  EXPECT_EQ(result["range"]["start"], (Json{{"line", 1}, {"character", 2}}));
  EXPECT_EQ(result["range"]["end"], (Json{{"line", 1}, {"character", 17}}));
}

TEST_F(SetupHoverTest, CoolantInALoopNamesItsMCodes) {
  std::string text = hoverText(4, 6);
  EXPECT_NE(text.find("coolant flood"), std::string::npos) << text;
  EXPECT_NE(text.find("M08"), std::string::npos) << text;
  EXPECT_NE(text.find("M09"), std::string::npos) << text;
}

TEST_F(SetupHoverTest, ToolRegistersNameTheirCodes) {
  std::string length = hoverText(2, 30); // `length`
  EXPECT_NE(length.find("G43 H"), std::string::npos) << length;
  std::string radius = hoverText(2, 41); // `radius`
  EXPECT_NE(radius.find("D<radius>"), std::string::npos) << radius;
  EXPECT_EQ(hoverText(2, 12), ""); // `diameter`: nothing to add
  EXPECT_EQ(hoverText(0, 2), "");  // `part`
}

} // namespace
} // namespace cncc::lsp::testing
