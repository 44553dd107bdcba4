#include "cncc/lsp/text_positions.h"

#include <gtest/gtest.h>

namespace cncc::lsp {
namespace {

TEST(TextPositions, AsciiRoundTrips) {
  TextPositions positions("ab\ncd\n");
  EXPECT_EQ(positions.offsetOf({1, 1}), 4u);
  EXPECT_EQ(positions.positionOf(4), (Position{1, 1}));
  EXPECT_EQ(positions.positionOf(6), (Position{2, 0}));
  EXPECT_EQ(positions.lineCount(), 3u);
}

TEST(TextPositions, CountsUtf16CodeUnits) {
  // "é" is 2 bytes and 1 unit; "😀" is 4 bytes and 2 units.
  std::string text = "\"\xC3\xA9\xF0\x9F\x98\x80\" x";
  TextPositions positions(text);
  EXPECT_EQ(positions.positionOf(3), (Position{0, 2})); // after é
  EXPECT_EQ(positions.positionOf(7), (Position{0, 4})); // after the emoji
  EXPECT_EQ(positions.offsetOf({0, 4}), 7u);
  EXPECT_EQ(positions.offsetOf({0, 6}), 9u); // the x
  // Inside the surrogate pair: the start of the emoji.
  EXPECT_EQ(positions.offsetOf({0, 3}), 3u);
}

TEST(TextPositions, ClampsPositionsOutOfRange) {
  TextPositions positions("abc\r\nde");
  EXPECT_EQ(positions.offsetOf({0, 99}), 3u); // before "\r\n"
  EXPECT_EQ(positions.offsetOf({1, 99}), 7u);
  EXPECT_EQ(positions.offsetOf({42, 0}), 7u);
  EXPECT_EQ(positions.positionOf(1000), (Position{1, 2}));
}

TEST(TextPositions, EmptyText) {
  TextPositions positions("");
  EXPECT_EQ(positions.offsetOf({0, 5}), 0u);
  EXPECT_EQ(positions.positionOf(0), (Position{0, 0}));
}

TEST(TextPositions, InvalidUtf8CountsOneUnitPerByte) {
  std::string text = "\xFF\xFEz";
  TextPositions positions(text);
  EXPECT_EQ(positions.positionOf(2), (Position{0, 2}));
  EXPECT_EQ(positions.offsetOf({0, 2}), 2u);
}

} // namespace
} // namespace cncc::lsp
