// Go to definition and hover on a compiled program with a source map beside
// it: the CDL statement that printed the line.
#include "session.h"

#include "cncc/lsp/program_map.h"
#include "cncc/lsp/uri.h"

#include <filesystem>

#include <unistd.h>

namespace cncc::lsp {
namespace {

class ProgramWithMap : public ::testing::Test {
protected:
  void SetUp() override {
    folder_ = std::filesystem::temp_directory_path() /
              // Each test's own folder: ctest runs the tests of a fixture in parallel.
              ("cncc-program-map-" + std::to_string(::getpid()) + "-" +
               ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(folder_);
    write(folder_ / "ring.cdl", "part ring {\n  units mm\n  curve circle(0, 0, 5)\n}\n");
    program_ = "%\nO1000\n#6=5.\nG3 X#6 Y0. I-#6 J0.\nM30\n%\n";
    write(folder_ / "O1000.nc", program_);
    Json map = {{"version", 1},
                {"programHash", programHash(program_)},
                {"sources", {"ring.cdl"}},
                {"directory", folder_.string()},
                {"lines",
                 {line(1, 6, "part"), line(1, 6, "part"), line(3, 3, "cut"), line(3, 3, "cut"),
                  line(1, 6, "part"), line(1, 6, "part")}},
                {"variables",
                 {{"6",
                   {{"meaning", "work value"},
                    {"statements", {{{"source", 0}, {"line", 3}, {"column", 3}}}}}}}}};
    write(folder_ / "O1000.nc.map.json", map.dump());
    uri_ = uriFromPath((folder_ / "O1000.nc").string());
    session_.initialize();
  }
  void TearDown() override { std::filesystem::remove_all(folder_); }

  static Json line(int number, int column, const char* statement) {
    return {{"source", 0},
            {"line", number},
            {"column", column},
            {"statement", statement},
            {"loopDepth", 0}};
  }
  static void write(const std::filesystem::path& path, const std::string& text) {
    std::ofstream(path, std::ios::binary) << text;
  }

  std::filesystem::path folder_;
  std::string program_;
  std::string uri_;
  testing::Session session_;
};

TEST_F(ProgramWithMap, DefinitionOfAProgramLineIsItsCdlStatement) {
  Json diagnostics = session_.open(uri_, program_);
  EXPECT_TRUE(diagnostics.is_null()) << "a program is not checked as CDL: " << diagnostics;
  Json location = session_.at("textDocument/definition", uri_, 3, 0);
  ASSERT_TRUE(location.is_object()) << location;
  EXPECT_EQ(location["uri"], uriFromPath((folder_ / "ring.cdl").string()));
  EXPECT_EQ(location["range"]["start"]["line"], 2);
  EXPECT_EQ(location["range"]["start"]["character"], 2);
}

TEST_F(ProgramWithMap, HoverNamesTheStatementAndQuotesIt) {
  session_.open(uri_, program_);
  std::string hover = session_.at("textDocument/hover", uri_, 3, 0)["contents"]["value"];
  EXPECT_THAT(hover, ::testing::HasSubstr("cut statement at ring.cdl:3:3"));
  EXPECT_THAT(hover, ::testing::HasSubstr("curve circle(0, 0, 5)"));
}

// On a macro variable: what it holds and the statement its values come from.
TEST_F(ProgramWithMap, HoverOnAVariableSaysWhatItHolds) {
  session_.open(uri_, program_);
  for (unsigned character : {4u, 5u, 6u}) { // on '#', on '6', just after it
    Json hover = session_.at("textDocument/hover", uri_, 3, character);
    ASSERT_TRUE(hover.is_object()) << character;
    std::string value = hover["contents"]["value"];
    EXPECT_THAT(value, ::testing::HasSubstr("`#6`: work value"));
    EXPECT_THAT(value, ::testing::HasSubstr("ring.cdl:3: `  curve circle(0, 0, 5)`"));
  }
  // On `Y0.`: the line's statement, not a variable.
  std::string line = session_.at("textDocument/hover", uri_, 3, 8)["contents"]["value"];
  EXPECT_THAT(line, ::testing::HasSubstr("cut statement"));
}

TEST_F(ProgramWithMap, AnEditedProgramOrALinePastTheMapHasNoDefinition) {
  session_.open(uri_, program_);
  EXPECT_TRUE(session_.at("textDocument/definition", uri_, 9, 0).is_null());
  session_.replace(uri_, "%\nO1000\n#6=5.\nG2 X#6 Y0. I-#6 J0.\nM30\n%\n", 2);
  EXPECT_TRUE(session_.at("textDocument/definition", uri_, 2, 0).is_null());
}

} // namespace
} // namespace cncc::lsp
