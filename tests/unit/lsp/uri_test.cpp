#include "cncc/lsp/uri.h"

#include <gtest/gtest.h>

namespace cncc::lsp {
namespace {

TEST(Uri, DecodesFileUris) {
  EXPECT_EQ(pathFromUri("file:///home/a%20b/x.cdl"), "/home/a b/x.cdl");
  EXPECT_EQ(pathFromUri("file://localhost/tmp/x.cdl"), "/tmp/x.cdl");
  EXPECT_EQ(pathFromUri("file:///C%3A/parts/x.cdl"), "/C:/parts/x.cdl");
}

TEST(Uri, RejectsOtherSchemesHostsAndBadEscapes) {
  EXPECT_EQ(pathFromUri("untitled:Untitled-1"), std::nullopt);
  EXPECT_EQ(pathFromUri("file://server/share/x.cdl"), std::nullopt);
  EXPECT_EQ(pathFromUri("file:///x%2"), std::nullopt);
  EXPECT_EQ(pathFromUri("file:///x%zz"), std::nullopt);
  EXPECT_EQ(pathFromUri("file://"), std::nullopt);
}

TEST(Uri, EncodesPathsAndRoundTrips) {
  EXPECT_EQ(uriFromPath("/a b/c#d.cdl"), "file:///a%20b/c%23d.cdl");
  for (std::string path : {"/plain/x.cdl", "/sp ace/%/ü.cdl", "/a?b&c"}) {
    EXPECT_EQ(pathFromUri(uriFromPath(path)), path);
  }
}

} // namespace
} // namespace cncc::lsp
