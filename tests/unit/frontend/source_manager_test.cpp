#include "cncc/frontend/source_manager.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

namespace cncc::frontend {
namespace {

// Line and column of every offset, counted one byte at a time.
std::vector<LineColumn> countedLineColumns(const std::string& text) {
  std::vector<LineColumn> positions;
  std::uint32_t line = 1;
  std::uint32_t column = 1;
  for (char c : text) {
    positions.push_back({line, column});
    if (c == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  positions.push_back({line, column});
  return positions;
}

void expectLinesAsCounted(const std::string& text) {
  SourceFile file("text.cdl", text);
  std::vector<LineColumn> expected = countedLineColumns(text);
  ASSERT_EQ(file.lineCount(), expected.back().line);
  for (std::size_t offset = 0; offset < expected.size(); ++offset) {
    LineColumn found = file.lineColumn(static_cast<std::uint32_t>(offset));
    ASSERT_EQ(found.line, expected[offset].line) << "offset " << offset;
    ASSERT_EQ(found.column, expected[offset].column) << "offset " << offset;
  }
}

TEST(SourceFileLines, LineBreaksAtEveryPositionOfAWord) {
  // The line table reads eight bytes at a time: a break at each position
  // within a word, runs of breaks, and a tail shorter than a word.
  for (std::size_t length = 0; length < 40; ++length) {
    for (std::size_t gap = 1; gap < 11; ++gap) {
      std::string text(length, 'a');
      for (std::size_t i = gap - 1; i < length; i += gap) {
        text[i] = '\n';
      }
      expectLinesAsCounted(text);
    }
  }
}

TEST(SourceFileLines, BytesNearALineBreakAreNotLineBreaks) {
  // 0x0b and 0x8a differ from '\n' in one bit; 0x00 and 0xff are the
  // extremes a word-at-a-time search gets wrong first.
  for (char neighbour : {'\x0b', '\x8a', '\x09', '\x00', '\xff', '\x0a'}) {
    std::string text;
    for (int i = 0; i < 64; ++i) {
      text += (i % 3 == 0) ? '\n' : neighbour;
    }
    expectLinesAsCounted(text);
  }
}

TEST(SourceFileLines, LineTextWithoutItsBreak) {
  SourceFile file("text.cdl", "part p() {\r\n  units mm\n}");
  EXPECT_EQ(file.lineCount(), 3u);
  EXPECT_EQ(file.lineText(1), "part p() {");
  EXPECT_EQ(file.lineText(2), "  units mm");
  EXPECT_EQ(file.lineText(3), "}");
  EXPECT_EQ(file.lineText(4), "");
}

TEST(SourceFileLines, FoundOnceWhenTwoThreadsAskFirst) {
  // The line table is built on first use; two threads asking at once must
  // both see the whole of it.
  std::string text;
  for (int i = 0; i < 20000; ++i) {
    text += "curve line((0, 0), (" + std::to_string(i) + ", 0))\n";
  }
  SourceFile file("text.cdl", text);
  auto last = static_cast<std::uint32_t>(text.size() - 1);
  LineColumn seenByOther{};
  std::thread other([&] { seenByOther = file.lineColumn(last); });
  LineColumn seenHere = file.lineColumn(last);
  other.join();
  EXPECT_EQ(seenHere.line, 20000u);
  EXPECT_EQ(seenByOther.line, 20000u);
  EXPECT_EQ(seenHere.column, seenByOther.column);
  EXPECT_EQ(file.lineCount(), 20001u);
}

TEST(SourceManagerLoading, ReadsTheWholeFile) {
  std::filesystem::path path =
      std::filesystem::temp_directory_path() / "cncc_source_manager_test.cdl";
  std::string text;
  for (int i = 0; i < 5000; ++i) {
    text += "let a" + std::to_string(i) + " = " + std::to_string(i) + "\n";
  }
  {
    std::ofstream out(path, std::ios::binary);
    out << text;
  }
  SourceManager sources;
  std::optional<FileId> file = sources.loadFile(path.string());
  std::filesystem::remove(path);
  ASSERT_TRUE(file.has_value());
  EXPECT_EQ(sources.file(*file).text(), text);
  EXPECT_EQ(sources.file(*file).lineCount(), 5001u);
}

TEST(SourceManagerLoading, AMissingFileIsNotLoaded) {
  SourceManager sources;
  EXPECT_FALSE(sources.loadFile("/nonexistent/directory/part.cdl").has_value());
}

} // namespace
} // namespace cncc::frontend
