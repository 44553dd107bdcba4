// Code lenses on a CDL file's cuts: blocks, bytes and deviation of the last
// compile, from the source maps of the programs compiled from it.
#include "session.h"

#include "cncc/lsp/cut_lenses.h"
#include "cncc/lsp/program_map.h"
#include "cncc/lsp/uri.h"

#include <filesystem>

#include <fstream>
#include <unistd.h>

namespace cncc::lsp {
namespace {

class CutLenses : public ::testing::Test {
protected:
  void SetUp() override {
    folder_ = std::filesystem::temp_directory_path() /
              // Each test's own folder: ctest runs the tests of a fixture in parallel.
              ("cncc-cut-lenses-" + std::to_string(::getpid()) + "-" +
               ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(folder_ / "programs");
    source_ = "part ring {\n  units mm\n  curve circle(0, 0, 5)\n  curve circle(0, 0, 8)\n}\n";
    write(folder_ / "ring.cdl", source_);
    writeProgram("O1000.nc", "fanuc", true);
    writeProgram("O2000.nc", "m80", false);
    uri_ = uriFromPath((folder_ / "ring.cdl").string());
    session_.initialize();
  }
  void TearDown() override { std::filesystem::remove_all(folder_); }

  // A program in programs/ and its map: two cuts, measured or not.
  void writeProgram(const std::string& name, const std::string& target, bool measured) {
    std::string program = "%\nO1000\nG3 X5. Y0. I-5. J0.\nG3 X8. Y0. I-8. J0.\nM30\n%\n";
    write(folder_ / "programs" / name, program);
    Json first = {{"source", 0}, {"line", 3}, {"column", 3}, {"blocks", 2}, {"bytes", 40}};
    Json second = {{"source", 0}, {"line", 4}, {"column", 3}, {"blocks", 1}, {"bytes", 20}};
    if (measured) {
      first["deviation"] = 0.0042;
      first["tolerance"] = 0.01;
      second["deviation"] = nullptr; // no feed move
      second["tolerance"] = 0.01;
    }
    Json map = {{"version", 1},
                {"program", "programs/" + name},
                {"programHash", programHash(program)},
                {"target", target},
                {"unit", "mm"},
                {"sources", {"ring.cdl"}},
                {"directory", folder_.string()},
                {"cuts", {first, second}},
                {"lines", Json::array()}};
    write(folder_ / "programs" / (name + ".map.json"), map.dump());
  }
  static void write(const std::filesystem::path& path, const std::string& text) {
    std::ofstream(path, std::ios::binary) << text;
  }
  static std::vector<std::string> titles(const Json& lenses) {
    std::vector<std::string> result;
    for (const Json& lens : lenses) {
      result.push_back(lens["command"]["title"]);
    }
    return result;
  }

  std::filesystem::path folder_;
  std::string source_;
  std::string uri_;
  testing::Session session_;
};

TEST_F(CutLenses, EachCutShowsWhatEachCurrentProgramMadeOfIt) {
  session_.open(uri_, source_);
  Json lenses = session_.on("textDocument/codeLens", uri_);
  ASSERT_EQ(lenses.size(), 4u) << lenses;
  EXPECT_EQ(lenses[0]["range"]["start"]["line"], 2);
  EXPECT_EQ(lenses[0]["range"]["start"]["character"], 2);
  EXPECT_THAT(titles(lenses),
              ::testing::ElementsAre(
                  "O1000.nc (fanuc): 2 blocks, 40 bytes, largest deviation 0.0042 mm "
                  "(tolerance 0.01)",
                  "O1000.nc (fanuc): 1 block, 20 bytes, no feed move",
                  "O2000.nc (m80): 2 blocks, 40 bytes", "O2000.nc (m80): 1 block, 20 bytes"));
}

TEST_F(CutLenses, AProgramChangedSinceItsMapHasNoLens) {
  write(folder_ / "programs" / "O2000.nc", "%\nO2000\nM30\n%\n"); // edited at the machine
  Json lenses = session_.on("textDocument/codeLens", uri_);
  for (const std::string& title : titles(lenses)) {
    EXPECT_THAT(title, ::testing::StartsWith("O1000.nc")) << lenses;
  }
  EXPECT_EQ(lenses.size(), 2u);
}

TEST_F(CutLenses, AnotherSourceHasNoLens) {
  write(folder_ / "other.cdl", "part other {\n  units mm\n}\n");
  EXPECT_EQ(session_.on("textDocument/codeLens", uriFromPath((folder_ / "other.cdl").string())),
            Json::array());
}

TEST_F(CutLenses, TheServerSaysItGivesLenses) {
  testing::Session fresh;
  Json response = fresh.initialize();
  EXPECT_EQ(response["result"]["capabilities"]["codeLensProvider"]["resolveProvider"], false);
}

TEST_F(CutLenses, TheSearchStopsAtItsBounds) {
  CutLensSearch search;
  search.directories = {folder_.string()};
  search.maximumMaps = 1;
  CutLensIndex index(search);
  EXPECT_EQ(index.lenses(uri_).size(), 2u) << "one map read, two cuts";
  search.maximumDepth = 0; // the maps are one level down
  CutLensIndex shallow(search);
  EXPECT_EQ(shallow.lenses(uri_), Json::array());
  search.maximumDepth = 3;
  search.maximumMapBytes = 10;
  CutLensIndex small(search);
  EXPECT_EQ(small.lenses(uri_), Json::array());
}

TEST_F(CutLenses, AMapRewrittenIsReadAgain) {
  CutLensIndex index(CutLensSearch{{folder_.string()}});
  ASSERT_EQ(index.lenses(uri_).size(), 4u);
  std::filesystem::remove(folder_ / "programs" / "O2000.nc.map.json");
  writeProgram("O3000.nc", "linuxcnc", true);
  Json lenses = index.lenses(uri_);
  EXPECT_THAT(titles(lenses), ::testing::Contains(::testing::StartsWith("O3000.nc (linuxcnc)")));
  EXPECT_EQ(lenses.size(), 4u);
}

TEST(SummariseMap, RefusesWhatIsNotAVersionOneMap) {
  EXPECT_FALSE(summariseMap(Json::array()));
  EXPECT_FALSE(summariseMap({{"version", 2}, {"program", "a"}, {"sources", Json::array()}}));
  EXPECT_FALSE(summariseMap({{"version", 1}, {"sources", Json::array()}}));
  std::optional<MapSummary> summary =
      summariseMap({{"version", 1},
                    {"program", "/p/O1.nc"},
                    {"sources", {"/p/a.cdl"}},
                    {"cuts", {{{"source", 3}, {"line", 1}}, {{"source", 0}, {"line", 2}}}}});
  ASSERT_TRUE(summary);
  ASSERT_EQ(summary->cuts.size(), 1u) << "a cut naming no source is left out";
  EXPECT_EQ(summary->cuts[0].line, 2u);
  EXPECT_FALSE(summary->cuts[0].measured);
}

} // namespace
} // namespace cncc::lsp
