// An IR text parsed back, for the tests of each operation's text: what it
// parses to must print as the same text.
#pragma once

#include "cncc/ir/printer.h"

#include <gtest/gtest.h>

#include <optional>
#include <string>

namespace cncc::ir::test_support {

// `text` (a function as printed) parsed; a failure where it does not parse
// or does not print back as `text`. The parsed function, for more checks.
inline std::optional<Function> parsedBack(const std::string& text) {
  ParseError error;
  std::optional<Function> parsed = parseFunction(text, error);
  EXPECT_TRUE(parsed) << error.line << ": " << error.message;
  if (parsed) {
    EXPECT_EQ(printFunction(*parsed), text);
  }
  return parsed;
}

} // namespace cncc::ir::test_support
