// Unit tests of the semantic checker: names and scopes, types, calls,
// compile-time evaluation, the geometric checks, imports and parts.
#include "cncc/frontend/sema.h"

#include "checked_source.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <numbers>

namespace cncc::frontend {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

using test_support::check;
using test_support::Checked;
using test_support::part;

TEST(SemaTest, LanguageContractExampleIsClean) {
  auto checked = check(R"(part s_profile(depth = 3, step = 1, w6 = 3) {
  units mm
  tool 1 diameter=10 spindle=3000 feed=300
  safe z=5
  let P = [(25,50), (42.8735,24.1467), (70.5832,72.3597), (86.608,165.3624),
           (112.4532,38.3852), (132.4671,35.1148), (175,150)]
  curve nurbs(order=4, points=P, weights=[1,1,1,1,1,w6,1]) sweep depth=depth step=step tolerance=0.01
})");
  EXPECT_THAT(checked->names(), ElementsAre());
  ASSERT_NE(checked->program.selectedPart, nullptr);
  EXPECT_EQ(checked->program.selectedPart->name, "s_profile");
  const Declaration* points = checked->find("P");
  ASSERT_NE(points, nullptr);
  EXPECT_EQ(points->type, Type::listOf(TypeKind::Point));
  ASSERT_TRUE(points->value.has_value());
  EXPECT_EQ(points->value->list->size(), 7u);
}

TEST(SemaTest, ConstantsAreEvaluatedInAnyOrder) {
  auto checked = check("const b = a * 2\nconst a = 1.5 + 2^3\nconst c = if a > 9 then a else -a\n");
  EXPECT_THAT(checked->names(), ElementsAre());
  EXPECT_DOUBLE_EQ(checked->find("a")->value->number, 9.5);
  EXPECT_DOUBLE_EQ(checked->find("b")->value->number, 19.0);
  EXPECT_DOUBLE_EQ(checked->find("c")->value->number, 9.5);
}

TEST(SemaTest, UnitSuffixesScaleToMillimetresAndRadians) {
  auto checked = check("const a = 90deg\nconst b = 2in\nconst c = 3mm + 1rad\n");
  EXPECT_DOUBLE_EQ(checked->find("a")->value->number, std::numbers::pi / 2);
  EXPECT_DOUBLE_EQ(checked->find("b")->value->number, 50.8);
  EXPECT_DOUBLE_EQ(checked->find("c")->value->number, 4.0);
}

TEST(SemaTest, FunctionsAreInlinedWithTheirArguments) {
  auto checked = check("fn lobes(k, t) = 1 + 0.2*cos(k*t)\nfn mid(p, q) = (p + q) / 2\n"
                       "const a = lobes(2, 0)\nconst m = mid((0, 0), (4, 2)).x\n"
                       "const n = lobes(t = pi, k = 1)\n");
  EXPECT_THAT(checked->names(), ElementsAre());
  EXPECT_DOUBLE_EQ(checked->find("a")->value->number, 1.2);
  EXPECT_DOUBLE_EQ(checked->find("m")->value->number, 2.0);
  EXPECT_DOUBLE_EQ(checked->find("n")->value->number, 0.8);
  EXPECT_EQ(checked->find("lobes")->type, Type::num());
  // Generic: (p + q) / 2 is a number or a point depending on the call.
  EXPECT_EQ(checked->find("mid")->type, Type::any());
}

TEST(SemaTest, GenericFunctionMisuseIsReportedWithTheCall) {
  auto checked = check("fn first_x(p) = p.x\nconst a = first_x(3)\n");
  ASSERT_THAT(checked->names(), ElementsAre("type-mismatch"));
  const Diagnostic& diagnostic = checked->diagnostics.diagnostics().front();
  ASSERT_EQ(diagnostic.notes.size(), 1u);
  EXPECT_EQ(diagnostic.notes[0].message, "in this call");
}

TEST(SemaTest, OperatorTypes) {
  EXPECT_THAT(
      check("const a = (1, 2) + (3, 4)\nconst b = 2 * (1, 1)\nconst c = (4, 4) / 2\n")->names(),
      ElementsAre());
  EXPECT_THAT(check("const a = (1, 2) + 3\n")->names(), ElementsAre("type-mismatch"));
  EXPECT_THAT(check("const a = true + 1\n")->names(), ElementsAre("type-mismatch"));
  EXPECT_THAT(check("const a = 1 && true\n")->names(), ElementsAre("type-mismatch"));
  EXPECT_THAT(check("const a = if 1 then 2 else 3\n")->names(), ElementsAre("type-mismatch"));
  EXPECT_THAT(check("const a = if true then 2 else (1, 1)\n")->names(),
              ElementsAre("type-mismatch"));
}

TEST(SemaTest, OneMistakeGivesOneMessage) {
  // `b` is undefined; everything computed from it stays quiet.
  auto checked = check(part("  let a = b * 2 + sin(b)\n  let c = (a, a)\n"
                            "  curve line((0, 0), c)"));
  EXPECT_THAT(checked->names(), ElementsAre("undefined-name", "undefined-name"));
}

TEST(SemaTest, ScopesOfLetsAndLoops) {
  auto checked =
      check(part("  for i in 1 .. 3 {\n    let y = i * 2\n    curve line((0, y), (10, y))\n"
                 "  }\n  curve line((0, 0), (y, 0))"));
  EXPECT_THAT(checked->names(), ElementsAre("undefined-name"));
}

TEST(SemaTest, LetIsVisibleOnlyAfterItsStatement) {
  auto checked = check(part("  let a = b\n  let b = 1\n  curve line((0, 0), (a, b))"));
  EXPECT_THAT(checked->names(), ElementsAre("undefined-name"));
}

TEST(SemaTest, CurveParameterExistsOnlyInsideAnalyticCurves) {
  EXPECT_THAT(check(part("  curve polar(r = 18 + 4*cos(2*t)*cos(6*t), t = 0 .. 2*pi)"))->names(),
              ElementsAre());
  auto outside = check(part("  let r = t\n  curve polar(r = r, t = 0 .. 1)"));
  ASSERT_THAT(outside->names(), ElementsAre("undefined-name"));
  EXPECT_THAT(outside->diagnostics.diagnostics().front().message, HasSubstr("polar"));
}

TEST(SemaTest, NamedAndPositionalArguments) {
  EXPECT_THAT(check(part("  curve arc((0, 0), 5, 0, pi)"))->names(), ElementsAre());
  EXPECT_THAT(check(part("  curve arc(center=(0, 0), radius=5, from=0, to=pi)"))->names(),
              ElementsAre());
  EXPECT_THAT(check(part("  curve arc((0, 0), 5, to=pi, from=0)"))->names(), ElementsAre());
  EXPECT_THAT(check(part("  curve arc((0, 0), 5, 0, pi, 0 .. -1, 3)"))->names(),
              ElementsAre("too-many-arguments"));
  // z= (a helix) is a range of heights.
  EXPECT_THAT(check(part("  curve arc((0, 0), 5, 0, 4*pi, z=0 .. -2)"))->names(), ElementsAre());
  EXPECT_THAT(check(part("  curve arc((0, 0), 5, 0, pi, 3)"))->names(),
              ElementsAre("type-mismatch"));
  EXPECT_THAT(check(part("  curve arc((0, 0), 5, 0, center=(1, 1))"))->names(),
              ElementsAre("missing-argument", "duplicate-argument"));
  EXPECT_THAT(check(part("  curve arc((0, 0), 5, 0)"))->names(), ElementsAre("missing-argument"));
}

TEST(SemaTest, NurbsNeedsExactlyOneOfOrderAndDegree) {
  std::string points = "points=[(0, 0), (1, 1), (2, 0)]";
  EXPECT_THAT(check(part("  curve nurbs(degree=2, " + points + ")"))->names(), ElementsAre());
  EXPECT_THAT(check(part("  curve nurbs(" + points + ")"))->names(),
              ElementsAre("missing-argument"));
  EXPECT_THAT(check(part("  curve nurbs(order=3, degree=2, " + points + ")"))->names(),
              ElementsAre("order-and-degree"));
}

TEST(SemaTest, ClampedUniformKnotsWhenOmitted) {
  auto checked =
      check("const c = nurbs(order=4, points=[(0,0),(1,1),(2,0),(3,1),(4,0),(5,1),(6,0)])\n");
  ASSERT_THAT(checked->names(), ElementsAre());
  const CurveValue& curve = *checked->find("c")->value->curve;
  EXPECT_EQ(curve.degree, 3);
  EXPECT_THAT(curve.knots, ElementsAre(0, 0, 0, 0, 0.25, 0.5, 0.75, 1, 1, 1, 1));
  EXPECT_THAT(curve.weights, ElementsAre(1, 1, 1, 1, 1, 1, 1));
}

TEST(SemaTest, WeightAndKnotChecksUseParameterDefaultsAndDefines) {
  std::string source =
      part("  curve nurbs(order=2, points=[(0, 0), (1, 1)], weights=[1, w])", "w = 1");
  EXPECT_THAT(check(source)->names(), ElementsAre());
  CheckOptions options;
  options.defines["w"] = -2;
  auto checked = check(source, options);
  ASSERT_THAT(checked->names(), ElementsAre("weight-not-positive"));
  EXPECT_THAT(checked->diagnostics.diagnostics().front().message, HasSubstr("weight 2 is -2"));
  EXPECT_DOUBLE_EQ(checked->find("w")->value->number, -2);
}

TEST(SemaTest, KnotVectorLengthAndDomain) {
  std::string points = "points=[(0, 0), (1, 1), (2, 0)]";
  EXPECT_THAT(
      check(part("  curve bspline(order=2, " + points + ", knots=[0, 0, 1, 2, 2])"))->names(),
      ElementsAre());
  EXPECT_THAT(
      check(part("  curve bspline(order=2, " + points + ", knots=[0, 0, 0, 0, 0])"))->names(),
      ElementsAre("degenerate-curve"));
}

TEST(SemaTest, LoopsAreCheckedForEveryIteration) {
  // Only the third iteration indexes past the end.
  auto checked = check(part("  let P = [(0, 0), (1, 0), (2, 0)]\n  for i in 0 .. 2 {\n"
                            "    curve line(P[i], P[i + 1])\n  }"));
  ASSERT_THAT(checked->names(), ElementsAre("index-out-of-range"));
}

TEST(SemaTest, OnlyTheTakenBranchIsEvaluated) {
  auto checked = check(part("  if n > 0 {\n    curve line((0, 0), (10 / n, 0))\n  } else {\n"
                            "    curve line((0, 0), (1, 1))\n  }",
                            "n = 0"));
  EXPECT_THAT(checked->names(), ElementsAre());
}

TEST(SemaTest, RecursionThroughTwoFunctions) {
  auto checked = check("fn f(x) = g(x) + 1\nfn g(x) = f(x) * 2\nconst a = f(1)\n");
  EXPECT_THAT(checked->names(), ElementsAre("recursive-function"));
}

TEST(SemaTest, BuiltinsCannotBeRedefined) {
  EXPECT_THAT(check("fn sin(x) = x\n")->names(), ElementsAre("redefinition"));
  EXPECT_THAT(check("const pi = 3\n")->names(), ElementsAre("redefinition"));
}

TEST(SemaTest, StandardLibraryImport) {
  auto checked = check("import \"std/curves\"\n" +
                       part("  curve archimedean_spiral(1, 2, 1) tolerance=0.005"));
  EXPECT_THAT(checked->names(), ElementsAre());
  EXPECT_EQ(checked->program.modules.size(), 2u);
}

TEST(SemaTest, ImportsResolveBesideTheImportingFile) {
  std::filesystem::path directory = std::filesystem::temp_directory_path() / "cncc_sema_import";
  std::filesystem::create_directories(directory);
  std::ofstream(directory / "shapes.cdl") << "fn square_side(a) = a * 2\n";
  std::ofstream(directory / "main.cdl")
      << "import \"shapes\"\nconst s = square_side(4)\nconst r = hidden\n";
  SourceManager sources;
  DiagnosticEngine diagnostics;
  FileId file = *sources.loadFile((directory / "main.cdl").string());
  CheckedProgram program = checkProgram(sources, file, {}, diagnostics);
  ASSERT_EQ(diagnostics.diagnostics().size(), 1u);
  EXPECT_EQ(diagnostics.diagnostics().front().kind, DiagnosticKind::UndefinedName);
  const Declaration* side = nullptr;
  for (const Declaration& declaration : program.declarations) {
    if (declaration.name == "s") {
      side = &declaration;
    }
  }
  ASSERT_NE(side, nullptr);
  EXPECT_DOUBLE_EQ(side->value->number, 8);
  std::filesystem::remove_all(directory);
}

TEST(SemaTest, PartSelection) {
  std::string two = "part a() {}\npart b() {}\n";
  CheckOptions compile;
  compile.requirePart = true;
  EXPECT_THAT(check(two, compile)->names(), ElementsAre("ambiguous-part"));
  compile.partName = "b";
  auto chosen = check(two, compile);
  EXPECT_THAT(chosen->names(), ElementsAre());
  EXPECT_EQ(chosen->program.selectedPart->name, "b");
  compile.partName = "c";
  EXPECT_THAT(check(two, compile)->names(), ElementsAre("unknown-part"));
  EXPECT_THAT(check(two)->names(), ElementsAre()); // `check` takes every part
}

TEST(SemaTest, ReferencesLeadToDefinitions) {
  std::string source = "const gap = 5\n" + part("  curve line((0, 0), (gap, 0))");
  auto checked = check(source);
  auto use = static_cast<std::uint32_t>(source.find("gap, 0"));
  const Reference* reference = checked->program.referenceAt(checked->file, use + 1);
  ASSERT_NE(reference, nullptr);
  EXPECT_FALSE(reference->isDefinition);
  EXPECT_EQ(reference->declaration->name, "gap");
  EXPECT_EQ(reference->declaration->span.begin, source.find("gap"));
}

TEST(SemaTest, VisibleNamesFollowScopes) {
  std::string source = part("  let inside = 1\n  curve line((0, 0), (inside, 0))", "depth = 3");
  auto checked = check(source);
  auto names = [&](std::size_t offset) {
    std::vector<std::string> result;
    for (const Declaration* declaration :
         checked->program.visibleAt(checked->file, static_cast<std::uint32_t>(offset))) {
      result.push_back(declaration->name);
    }
    return result;
  };
  std::vector<std::string> inCut = names(source.find("inside, 0"));
  EXPECT_THAT(inCut, ::testing::Contains("inside"));
  EXPECT_THAT(inCut, ::testing::Contains("depth"));
  EXPECT_THAT(inCut, ::testing::Contains("nurbs"));
  EXPECT_THAT(names(0), ::testing::Not(::testing::Contains("inside")));
}

TEST(SemaTest, PathologicalLoopsAreBounded) {
  auto checked = check(part("  for i in 0 .. 1e12 {\n    for j in 0 .. 1e12 {\n"
                            "      curve line((0, 0), (i + j + 1, 0))\n    }\n  }"));
  EXPECT_THAT(checked->names(), ElementsAre());
}

// ---------------------------------------------------------------- machine set-up

TEST(SemaTest, SetUpStatementsCheckAndRunAnywhereInAPart) {
  auto checked = check(part("  origin G55\n  coolant flood\n  curve line((0, 0), (1, 0))\n"
                            "  for i in 1 .. 2 {\n    origin G54.1 P2\n    coolant off\n  }\n"
                            "  if true { coolant mist }"));
  EXPECT_THAT(checked->names(), ElementsAre());
}

TEST(SemaTest, ToolLengthAndRadiusRegisters) {
  auto tool = [](const std::string& settings, const std::string& parameters = "") {
    return check("const H = 7\npart q(" + parameters + ") {\n  tool 1 diameter=6 feed=200 " +
                 settings + "\n}\n");
  };
  EXPECT_THAT(tool("length=12 radius=22")->names(), ElementsAre());
  EXPECT_THAT(tool("length=H radius=H + 1")->names(), ElementsAre());
  EXPECT_THAT(tool("length=999 radius=1")->names(), ElementsAre());
  EXPECT_THAT(tool("length=0")->names(), ElementsAre("value-not-positive"));
  EXPECT_THAT(tool("radius=-3")->names(), ElementsAre("value-not-positive"));
  EXPECT_THAT(tool("length=2.5")->names(), ElementsAre("not-integer"));
  EXPECT_THAT(tool("radius=1000")->names(), ElementsAre("register-out-of-range"));
  EXPECT_THAT(tool("length=true")->names(), ElementsAre("type-mismatch"));
  EXPECT_THAT(tool("length=1 length=2")->names(), ElementsAre("duplicate-argument"));
  EXPECT_THAT(tool("lenght=1")->names(), ElementsAre("unknown-argument"));
}

TEST(SemaTest, AToolRegisterCannotDependOnAPartParameter) {
  // Directly, through a let, and through a loop variable; the value (2.5 by
  // default) is not checked again once reported.
  auto direct = check("part q(p = 2.5) {\n  tool 1 diameter=6 length=p\n}\n");
  ASSERT_THAT(direct->names(), ElementsAre("not-constant"));
  const Diagnostic& diagnostic = direct->diagnostics.diagnostics().front();
  EXPECT_EQ(direct->sources.text(diagnostic.span), "p");
  EXPECT_THAT(diagnostic.message, HasSubstr("part parameter"));
  EXPECT_THAT(check("part q(p = 2) {\n  let h = p + 1\n  tool 1 diameter=6 radius=h\n}\n")->names(),
              ElementsAre("not-constant"));
  EXPECT_THAT(check("part q(n = 2) {\n  for i in 1 .. n {\n    tool i diameter=6 length=i\n"
                    "  }\n}\n")
                  ->names(),
              ElementsAre("not-constant"));
  // A loop over constant bounds and a let of constants are fine.
  EXPECT_THAT(check("part q(p = 2) {\n  let h = 3\n  for i in 1 .. 2 {\n"
                    "    tool i diameter=p length=i radius=h\n  }\n}\n")
                  ->names(),
              ElementsAre());
}

} // namespace
} // namespace cncc::frontend

namespace cncc::frontend {
namespace {

TEST(ExpressionEvaluatorTest, EvaluatesACurveRadiusAtAnyParameter) {
  auto checked = check("const c = polar(r = 18 + 4*cos(2*t)*cos(6*t), t = 0 .. 2*pi)\n");
  ASSERT_THAT(checked->names(), ElementsAre());
  const CurveValue& curve = *checked->find("c")->value->curve;
  ASSERT_NE(curve.radius, nullptr);
  DiagnosticEngine diagnostics;
  ExpressionEvaluator evaluator(checked->program, diagnostics);
  Environment environment = curve.environment;
  for (double t : {0.0, 0.3, 1.7}) {
    environment[curve.parameter] = Value::ofNumber(t);
    Value radius = evaluator.evaluate(*curve.radius, environment);
    ASSERT_EQ(radius.type.kind, TypeKind::Num);
    EXPECT_DOUBLE_EQ(radius.number, 18 + 4 * std::cos(2 * t) * std::cos(6 * t));
  }
  EXPECT_FALSE(diagnostics.hasErrors());
}

} // namespace
} // namespace cncc::frontend
