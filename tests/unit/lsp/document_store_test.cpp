#include "cncc/lsp/document_store.h"

#include <gtest/gtest.h>

namespace cncc::lsp {
namespace {

TEST(DocumentStore, AppliesIncrementalChangesInOrder) {
  DocumentStore store;
  store.open("u", "let a = 1\nlet b = 2\n", 1);
  std::vector<TextChange> changes = {
      {Range{{0, 8}, {0, 9}}, "10"},       // a = 10
      {Range{{1, 4}, {1, 5}}, "bee"},      // rename b
      {Range{{0, 10}, {1, 0}}, " // x\n"}, // across the line break
  };
  ASSERT_TRUE(store.change("u", changes, 2));
  EXPECT_EQ(store.find("u")->text, "let a = 10 // x\nlet bee = 2\n");
  EXPECT_EQ(store.find("u")->version, 2);
}

TEST(DocumentStore, WholeReplacementAndUnknownDocuments) {
  DocumentStore store;
  EXPECT_FALSE(store.change("nope", {{std::nullopt, "x"}}, 1));
  store.open("u", "old", 1);
  ASSERT_TRUE(store.change("u", {{std::nullopt, "new"}}, 2));
  EXPECT_EQ(store.find("u")->text, "new");
  store.close("u");
  EXPECT_EQ(store.find("u"), nullptr);
}

TEST(DocumentStore, RangesCountUtf16AndClamp) {
  std::string text = "// \xF0\x9F\x98\x80!\nx";
  applyChange(text, {Range{{0, 5}, {0, 6}}, "?"}); // the '!' after a 2-unit emoji
  EXPECT_EQ(text, "// \xF0\x9F\x98\x80?\nx");
  applyChange(text, {Range{{7, 0}, {9, 9}}, "y"}); // past the end: appended
  EXPECT_EQ(text, "// \xF0\x9F\x98\x80?\nxy");
  applyChange(text, {Range{{1, 1}, {0, 0}}, "z"}); // reversed: inserted at the start
  EXPECT_EQ(text, "// \xF0\x9F\x98\x80?\nxzy");
}

} // namespace
} // namespace cncc::lsp
