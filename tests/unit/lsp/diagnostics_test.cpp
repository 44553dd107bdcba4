// Published diagnostics carry the front end's messages, names and spans.
#include "session.h"

#include "cncc/frontend/diagnostics.h"
#include "cncc/frontend/sema.h"

namespace cncc::lsp::testing {
namespace {

constexpr const char* uri = "file:///t/part.cdl";

TEST(Diagnostics, MatchTheCommandLine) {
  std::string text = "part p(w = 1) {\n  let P = [(0, 0), (1, 1), (2, 0)]\n"
                     "  curve nurbs(order=3, points=P, weights=[1, w]) tolerance=0.01\n}\n";
  // What `cncc check` reports for the same text.
  frontend::SourceManager sources;
  frontend::FileId file = sources.addFile("/t/part.cdl", text);
  frontend::DiagnosticEngine engine;
  frontend::checkProgram(sources, file, {{CNCC_STDLIB_DIR}, {}, "", false}, engine);
  ASSERT_FALSE(engine.diagnostics().empty());
  const frontend::Diagnostic& expected = engine.diagnostics().front();

  Session session;
  session.initialize();
  Json published = session.open(uri, text);
  EXPECT_EQ(published["uri"], uri);
  EXPECT_EQ(published["version"], 1);
  ASSERT_EQ(published["diagnostics"].size(), engine.diagnostics().size());
  const Json& first = published["diagnostics"][0];
  EXPECT_EQ(first["message"], expected.message);
  EXPECT_EQ(first["code"], std::string(frontend::diagnosticName(expected.kind)));
  EXPECT_EQ(first["source"], "cncc");
  EXPECT_EQ(first["severity"], 1);
  frontend::LineColumn begin = sources.file(file).lineColumn(expected.span.begin);
  frontend::LineColumn end = sources.file(file).lineColumn(expected.span.end);
  EXPECT_EQ(first["range"]["start"]["line"], begin.line - 1);
  EXPECT_EQ(first["range"]["start"]["character"], begin.column - 1);
  EXPECT_EQ(first["range"]["end"]["line"], end.line - 1);
  EXPECT_EQ(first["range"]["end"]["character"], end.column - 1);
}

TEST(Diagnostics, FollowEditsAndClearWhenFixed) {
  Session session;
  session.initialize();
  Json broken = session.open(uri, "part p() { tool 1 diameter=2 feed=9 safe z=1\n  let a = \n}\n");
  ASSERT_EQ(broken["diagnostics"].size(), 1u);
  EXPECT_EQ(broken["diagnostics"][0]["code"], "expected-expression");
  Json fixed = Session::publishedDiagnostics(session.notify(
      "textDocument/didChange", {{"textDocument", {{"uri", uri}, {"version", 2}}},
                                 {"contentChanges",
                                  {{{"range",
                                     {{"start", {{"line", 1}, {"character", 10}}},
                                      {"end", {{"line", 1}, {"character", 10}}}}},
                                    {"text", "2\n  curve line((0, 0), (a, 1))"}}}}}));
  EXPECT_EQ(fixed["version"], 2);
  EXPECT_TRUE(fixed["diagnostics"].empty()) << fixed.dump();
}

TEST(Diagnostics, NotesBecomeRelatedInformation) {
  Session session;
  session.initialize();
  Json published = session.open(uri, "const a = 1\nconst a = 2\n");
  ASSERT_EQ(published["diagnostics"].size(), 1u);
  const Json& redefinition = published["diagnostics"][0];
  EXPECT_EQ(redefinition["code"], "redefinition");
  ASSERT_EQ(redefinition["relatedInformation"].size(), 1u);
  EXPECT_EQ(redefinition["relatedInformation"][0]["location"]["uri"], uri);
  EXPECT_EQ(redefinition["relatedInformation"][0]["location"]["range"]["start"]["line"], 0);
}

TEST(Diagnostics, ProblemsInAnImportedFileAreShownOnTheImport) {
  std::string directory = ::testing::TempDir() + "cncc_lsp_import";
  std::filesystem::create_directories(directory);
  std::ofstream(directory + "/broken.cdl") << "fn f(x) = x +\n";
  Session session;
  session.initialize();
  std::string mainUri = "file://" + directory + "/main.cdl";
  Json published = session.open(mainUri, "import \"broken\"\npart p() {}\n");
  ASSERT_FALSE(published["diagnostics"].empty());
  const Json& shown = published["diagnostics"][0];
  EXPECT_EQ(shown["range"]["start"]["line"], 0);
  EXPECT_EQ(shown["range"]["start"]["character"], 7);
  EXPECT_NE(shown["message"].get<std::string>().find("broken.cdl:2:1"), std::string::npos)
      << shown.dump();
  EXPECT_EQ(shown["relatedInformation"][0]["location"]["uri"],
            "file://" + directory + "/broken.cdl");
}

} // namespace
} // namespace cncc::lsp::testing
