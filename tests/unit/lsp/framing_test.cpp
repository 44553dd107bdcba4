#include "cncc/lsp/framing.h"

#include <gtest/gtest.h>

#include <sstream>

namespace cncc::lsp {
namespace {

TEST(Framing, ReadsConsecutiveMessages) {
  std::istringstream input(
      "Content-Length: 2\r\n\r\n{}Content-Type: x\r\ncontent-length:3\r\n\r\n[1]");
  ReadResult first = readMessage(input);
  ASSERT_EQ(first.status, ReadStatus::Message);
  EXPECT_EQ(first.body, "{}");
  ReadResult second = readMessage(input);
  ASSERT_EQ(second.status, ReadStatus::Message);
  EXPECT_EQ(second.body, "[1]");
  EXPECT_EQ(readMessage(input).status, ReadStatus::EndOfInput);
}

TEST(Framing, SkipsAHeaderBlockWithoutLengthAndCarriesOn) {
  std::istringstream input("X-Junk: 1\r\n\r\nContent-Length: 1\r\n\r\n7");
  ReadResult bad = readMessage(input);
  EXPECT_EQ(bad.status, ReadStatus::BadHeader);
  EXPECT_EQ(bad.problem, "no Content-Length header");
  ReadResult good = readMessage(input);
  ASSERT_EQ(good.status, ReadStatus::Message);
  EXPECT_EQ(good.body, "7");
}

TEST(Framing, RejectsUnusableLengths) {
  for (std::string header : {"Content-Length: abc", "Content-Length: -1",
                             "Content-Length: 99999999999999999999", "no colon here"}) {
    std::istringstream input(header + "\r\n\r\n");
    EXPECT_EQ(readMessage(input).status, ReadStatus::BadHeader) << header;
  }
  std::istringstream huge("Content-Length: 100000000000\r\n\r\n");
  EXPECT_EQ(readMessage(huge).problem, "Content-Length is too large");
}

TEST(Framing, ATruncatedBodyEndsTheInput) {
  std::istringstream input("Content-Length: 10\r\n\r\n{\"a\"");
  EXPECT_EQ(readMessage(input).status, ReadStatus::EndOfInput);
}

TEST(Framing, WritesHeaderAndBody) {
  std::ostringstream output;
  writeMessage(output, "{\"x\":\"\xC3\xA9\"}");
  EXPECT_EQ(output.str(), "Content-Length: 10\r\n\r\n{\"x\":\"\xC3\xA9\"}");
}

} // namespace
} // namespace cncc::lsp
