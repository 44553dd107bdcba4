// The lexer: every token kind, numbers and units, strings, comments, line
// starts, and every diagnostic it can report.
#include "cncc/frontend/lexer.h"

#include <gtest/gtest.h>

#include <charconv>
#include <cmath>
#include <numbers>
#include <set>
#include <string>
#include <vector>

namespace cncc::frontend {
namespace {

class LexerTest : public ::testing::Test {
protected:
  std::vector<Token> lexText(std::string text) {
    FileId file = sources_.addFile("test.cdl", std::move(text));
    return lex(sources_, file, diagnostics_, &comments_);
  }

  // The kinds of `text`'s tokens, without the final EndOfFile.
  std::vector<TokenKind> kindsOf(std::string text) {
    std::vector<Token> tokens = lexText(std::move(text));
    EXPECT_EQ(tokens.back().kind, TokenKind::EndOfFile);
    std::vector<TokenKind> kinds;
    for (std::size_t i = 0; i + 1 < tokens.size(); ++i) {
      kinds.push_back(tokens[i].kind);
    }
    return kinds;
  }

  std::vector<std::string> diagnosticNames() const {
    std::vector<std::string> names;
    for (const Diagnostic& diagnostic : diagnostics_.diagnostics()) {
      names.emplace_back(diagnosticName(diagnostic.kind));
    }
    return names;
  }

  std::string textOf(SourceSpan span) const { return std::string(sources_.text(span)); }
  LineColumn positionOf(SourceSpan span) const {
    return sources_.file(span.file).lineColumn(span.begin);
  }

  SourceManager sources_;
  DiagnosticEngine diagnostics_{0};
  std::vector<SourceSpan> comments_;
};

struct Spelled {
  std::string_view spelling;
  TokenKind kind;
};

constexpr Spelled keywords[] = {
#define CNCC_KEYWORD(identifier, spelling) {spelling, TokenKind::identifier},
#include "cncc/frontend/token_kinds.def"
};

constexpr Spelled punctuators[] = {
#define CNCC_PUNCTUATOR(identifier, spelling) {spelling, TokenKind::identifier},
#include "cncc/frontend/token_kinds.def"
};

constexpr TokenKind allKinds[] = {
#define CNCC_TOKEN(identifier, spelling) TokenKind::identifier,
#include "cncc/frontend/token_kinds.def"
};

// ---------------------------------------------------------------- token kinds

TEST_F(LexerTest, EveryKeywordIsItsOwnKind) {
  for (const Spelled& keyword : keywords) {
    std::vector<Token> tokens = lexText(std::string(keyword.spelling));
    ASSERT_EQ(tokens.size(), 2u) << keyword.spelling;
    EXPECT_EQ(tokens[0].kind, keyword.kind) << keyword.spelling;
    EXPECT_EQ(tokens[0].text, keyword.spelling);
  }
  EXPECT_TRUE(diagnostics_.diagnostics().empty());
}

// Names of a keyword's length and first letter, or a keyword's letters
// with one more or one fewer, are names.
TEST_F(LexerTest, NamesCloseToKeywordsAreNames) {
  for (const Spelled& keyword : keywords) {
    std::string spelling(keyword.spelling);
    std::string lastChanged = spelling.substr(0, spelling.size() - 1) + "x";
    std::string secondChanged = spelling.substr(0, 1) + "x" + spelling.substr(2);
    for (const std::string& name :
         {spelling + "s", spelling.substr(0, spelling.size() - 1), lastChanged, secondChanged,
          "_" + spelling, spelling.substr(0, 1) + "0" + spelling.substr(1)}) {
      std::vector<Token> tokens = lexText(name);
      ASSERT_EQ(tokens.size(), 2u) << name;
      EXPECT_EQ(tokens[0].kind, TokenKind::Identifier) << name;
      EXPECT_EQ(tokens[0].text, name);
    }
  }
  EXPECT_EQ(kindsOf("i f in if fn ff Part PART x"),
            (std::vector<TokenKind>{TokenKind::Identifier, TokenKind::Identifier, TokenKind::KwIn,
                                    TokenKind::KwIf, TokenKind::KwFn, TokenKind::Identifier,
                                    TokenKind::Identifier, TokenKind::Identifier,
                                    TokenKind::Identifier}));
  EXPECT_TRUE(diagnostics_.diagnostics().empty());
}

TEST_F(LexerTest, EveryPunctuatorIsItsOwnKind) {
  for (const Spelled& punctuator : punctuators) {
    std::vector<Token> tokens = lexText(std::string(punctuator.spelling));
    ASSERT_EQ(tokens.size(), 2u) << punctuator.spelling;
    EXPECT_EQ(tokens[0].kind, punctuator.kind) << punctuator.spelling;
    EXPECT_EQ(textOf(tokens[0].span), punctuator.spelling);
  }
  EXPECT_TRUE(diagnostics_.diagnostics().empty());
}

TEST_F(LexerTest, EveryTokenKindIsProduced) {
  std::set<TokenKind> seen;
  for (const Spelled& spelled : keywords) {
    seen.insert(lexText(std::string(spelled.spelling))[0].kind);
  }
  for (const Spelled& spelled : punctuators) {
    seen.insert(lexText(std::string(spelled.spelling))[0].kind);
  }
  for (const Token& token : lexText("name 12 \"text\" @")) {
    seen.insert(token.kind);
  }
  EXPECT_EQ(seen.size(), std::size(allKinds));
}

TEST_F(LexerTest, PunctuatorsNeedNoSpaces) {
  using K = TokenKind;
  EXPECT_EQ(
      kindsOf("a<=b>=c==d!=e&&f||!g"),
      (std::vector<K>{K::Identifier, K::LessEqual, K::Identifier, K::GreaterEqual, K::Identifier,
                      K::EqualEqual, K::Identifier, K::BangEqual, K::Identifier, K::AmpAmp,
                      K::Identifier, K::PipePipe, K::Bang, K::Identifier}));
  EXPECT_EQ(kindsOf("L[i].x"), (std::vector<K>{K::Identifier, K::LeftBracket, K::Identifier,
                                               K::RightBracket, K::Dot, K::Identifier}));
}

TEST_F(LexerTest, IdentifiersAreCaseSensitiveAndContextualWordsAreIdentifiers) {
  std::vector<Token> tokens = lexText("_a1 Part PART sweep depth units tool");
  ASSERT_EQ(tokens.size(), 8u);
  for (std::size_t i = 0; i < 7; ++i) {
    EXPECT_EQ(tokens[i].kind, TokenKind::Identifier) << tokens[i].text;
  }
  EXPECT_EQ(tokens[0].text, "_a1");
  EXPECT_EQ(tokens[1].text, "Part");
}

// ---------------------------------------------------------------- numbers

struct NumberCase {
  const char* text;
  double value;
  UnitSuffix unit;
};

TEST_F(LexerTest, NumbersAndUnitSuffixes) {
  const double pi = std::numbers::pi;
  const NumberCase cases[] = {
      {"12", 12, UnitSuffix::None},           {"0.5", 0.5, UnitSuffix::None},
      {".5", 0.5, UnitSuffix::None},          {"1e-3", 1e-3, UnitSuffix::None},
      {"2E+2", 200, UnitSuffix::None},        {"3.", 3, UnitSuffix::None},
      {"2.5mm", 2.5, UnitSuffix::Millimetre}, {"45deg", 45 * pi / 180, UnitSuffix::Degree},
      {"1in", 25.4, UnitSuffix::Inch},        {"0.5rad", 0.5, UnitSuffix::Radian},
      {"1e1mm", 10, UnitSuffix::Millimetre},
  };
  for (const NumberCase& expected : cases) {
    std::vector<Token> tokens = lexText(expected.text);
    ASSERT_EQ(tokens.size(), 2u) << expected.text;
    EXPECT_EQ(tokens[0].kind, TokenKind::Number) << expected.text;
    EXPECT_DOUBLE_EQ(tokens[0].number, expected.value) << expected.text;
    EXPECT_EQ(tokens[0].unit, expected.unit) << expected.text;
    EXPECT_EQ(textOf(tokens[0].span), expected.text) << "the span includes the unit";
  }
  EXPECT_TRUE(diagnostics_.diagnostics().empty());
}

// Up to 15 digits are converted by the lexer itself, longer numbers by
// from_chars: either way the value is the correctly rounded one.
TEST_F(LexerTest, LongNumbersAreConvertedAsFromChars) {
  const std::string cases[] = {
      "123456789012345",       "1234567890123456",        "0.00000000000001",
      "0.000000000000001",     "0.0000000000000001",      "000000000000000012.5",
      "9007199254740993",      "3.14159265358979",        "3.141592653589793238",
      "0.1234567890123456789", "12345678901234567890123", "100000000000000000000.0",
  };
  for (const std::string& text : cases) {
    double expected = 0;
    std::from_chars(text.data(), text.data() + text.size(), expected);
    std::vector<Token> tokens = lexText(text);
    ASSERT_EQ(tokens.size(), 2u) << text;
    EXPECT_EQ(tokens[0].kind, TokenKind::Number) << text;
    EXPECT_EQ(tokens[0].number, expected) << text;
  }
  EXPECT_TRUE(diagnostics_.diagnostics().empty());
}

TEST_F(LexerTest, TwoDotsAfterANumberMakeARange) {
  std::vector<Token> tokens = lexText("1..5");
  ASSERT_EQ(tokens.size(), 4u);
  EXPECT_EQ(tokens[0].kind, TokenKind::Number);
  EXPECT_EQ(tokens[0].number, 1);
  EXPECT_EQ(tokens[1].kind, TokenKind::DotDot);
  EXPECT_EQ(tokens[2].kind, TokenKind::Number);
  EXPECT_EQ(tokens[2].number, 5);

  using K = TokenKind;
  EXPECT_EQ(kindsOf("0.5..2.5"), (std::vector<K>{K::Number, K::DotDot, K::Number}));
  EXPECT_EQ(kindsOf("0 .. 2*pi"),
            (std::vector<K>{K::Number, K::DotDot, K::Number, K::Star, K::Identifier}));
  EXPECT_EQ(kindsOf("a..b"), (std::vector<K>{K::Identifier, K::DotDot, K::Identifier}));
  EXPECT_TRUE(diagnostics_.diagnostics().empty());
}

TEST_F(LexerTest, ANumberBeforeANameNeedsASpace) {
  using K = TokenKind;
  EXPECT_EQ(kindsOf("2 in"), (std::vector<K>{K::Number, K::KwIn}));
  EXPECT_EQ(kindsOf("2*x"), (std::vector<K>{K::Number, K::Star, K::Identifier}));
  EXPECT_TRUE(diagnostics_.diagnostics().empty());
}

// ---------------------------------------------------------------- strings

TEST_F(LexerTest, StringsWithEscapes) {
  std::vector<Token> tokens = lexText(R"("std/curves" "a \"b\" \\ c" "")");
  ASSERT_EQ(tokens.size(), 4u);
  EXPECT_EQ(tokens[0].kind, TokenKind::String);
  EXPECT_EQ(tokens[0].text, "std/curves");
  EXPECT_EQ(textOf(tokens[0].span), "\"std/curves\"");
  EXPECT_EQ(tokens[1].kind, TokenKind::String);
  EXPECT_EQ(tokens[1].text, R"(a "b" \ c)");
  EXPECT_EQ(tokens[2].kind, TokenKind::String);
  EXPECT_EQ(tokens[2].text, "");
  EXPECT_TRUE(diagnostics_.diagnostics().empty());
}

// ---------------------------------------------------------------- comments

TEST_F(LexerTest, CommentsAreSkippedAndRecorded) {
  std::vector<Token> tokens = lexText("a // line comment\n/* block\n comment */ b/**/c /* x */");
  using K = TokenKind;
  ASSERT_EQ(tokens.size(), 4u);
  EXPECT_EQ(tokens[0].kind, K::Identifier);
  EXPECT_EQ(tokens[1].text, "b");
  EXPECT_EQ(tokens[2].text, "c");
  ASSERT_EQ(comments_.size(), 4u);
  EXPECT_EQ(textOf(comments_[0]), "// line comment");
  EXPECT_EQ(textOf(comments_[1]), "/* block\n comment */");
  EXPECT_EQ(textOf(comments_[2]), "/**/");
  EXPECT_TRUE(diagnostics_.diagnostics().empty());
}

TEST_F(LexerTest, ASlashAloneIsDivision) {
  using K = TokenKind;
  EXPECT_EQ(kindsOf("a / b"), (std::vector<K>{K::Identifier, K::Slash, K::Identifier}));
}

// ---------------------------------------------------------------- line starts

TEST_F(LexerTest, StartsLineMarksTheFirstTokenOfEachLine) {
  std::vector<Token> tokens = lexText("  a b\n c\n\n/* x\n */ d /* y */ e\n// z\nf\n");
  ASSERT_EQ(tokens.size(), 7u);
  EXPECT_TRUE(tokens[0].startsLine);  // a: the first token
  EXPECT_FALSE(tokens[1].startsLine); // b
  EXPECT_TRUE(tokens[2].startsLine);  // c
  EXPECT_TRUE(tokens[3].startsLine);  // d: after a block comment across lines
  EXPECT_FALSE(tokens[4].startsLine); // e: after a one-line block comment
  EXPECT_TRUE(tokens[5].startsLine);  // f: after a line comment
  EXPECT_TRUE(tokens[6].startsLine);  // EndOfFile on a line of its own
}

TEST_F(LexerTest, EmptyInputIsJustEndOfFile) {
  std::vector<Token> tokens = lexText("");
  ASSERT_EQ(tokens.size(), 1u);
  EXPECT_EQ(tokens[0].kind, TokenKind::EndOfFile);
  EXPECT_TRUE(tokens[0].startsLine);
}

TEST_F(LexerTest, SpansGiveLinesAndColumns) {
  std::vector<Token> tokens = lexText("part p {\n  curve c\n}");
  LineColumn curve = positionOf(tokens[3].span);
  EXPECT_EQ(curve.line, 2u);
  EXPECT_EQ(curve.column, 3u);
  LineColumn end = positionOf(tokens.back().span);
  EXPECT_EQ(end.line, 3u);
  EXPECT_EQ(end.column, 2u);
}

// ---------------------------------------------------------------- diagnostics

struct DiagnosticCase {
  const char* text;
  const char* name;
  const char* spanText; // what the diagnostic points at
};

TEST_F(LexerTest, EveryLexerDiagnostic) {
  const DiagnosticCase cases[] = {
      {"a @ b", "unexpected-character", "@"},
      {"a & b", "unexpected-character", "&"},
      {"a | b", "unexpected-character", "|"},
      {"a \x01 b", "unexpected-character", "\x01"},
      {"a \xc3\xa9 b", "unexpected-character", "\xc3\xa9"},
      {"a @#$ b", "unexpected-character", "@#$"},
      {"\"abc\ndef", "unterminated-string", "\"abc"},
      {"\"abc", "unterminated-string", "\"abc"},
      {"a /* never closed", "unterminated-comment", "/*"},
      {R"("a\qb")", "invalid-escape", "\\q"},
      {"2e", "malformed-number", "2e"},
      {"2e+ 1", "malformed-number", "2e+"},
      {"1e999", "malformed-number", "1e999"},
      {"2.5cm", "unknown-unit-suffix", "cm"},
      {"3x", "unknown-unit-suffix", "x"},
  };
  for (const DiagnosticCase& expected : cases) {
    diagnostics_.clear();
    lexText(expected.text);
    ASSERT_EQ(diagnostics_.diagnostics().size(), 1u) << expected.text;
    const Diagnostic& diagnostic = diagnostics_.diagnostics().front();
    EXPECT_EQ(diagnosticName(diagnostic.kind), expected.name) << expected.text;
    EXPECT_EQ(textOf(diagnostic.span), expected.spanText) << expected.text;
    EXPECT_EQ(diagnostic.severity, Severity::Error);
  }
}

TEST_F(LexerTest, ErrorsBecomeErrorTokensAndLexingGoesOn) {
  using K = TokenKind;
  EXPECT_EQ(kindsOf("a @ b"), (std::vector<K>{K::Identifier, K::Error, K::Identifier}));
  EXPECT_EQ(kindsOf("2cm + 1"), (std::vector<K>{K::Error, K::Plus, K::Number}));
  EXPECT_EQ(kindsOf("2e + 1"), (std::vector<K>{K::Error, K::Plus, K::Number}));
  EXPECT_EQ(kindsOf("\"open\nnext"), (std::vector<K>{K::Error, K::Identifier}));
  EXPECT_EQ(kindsOf(R"("a\qb" c)"), (std::vector<K>{K::Error, K::Identifier}));
  EXPECT_EQ(kindsOf("x /* open"), (std::vector<K>{K::Identifier}));
}

TEST_F(LexerTest, ARunOfStrayCharactersIsOneError) {
  std::vector<Token> tokens = lexText("a @@@ ### b");
  EXPECT_EQ(diagnosticNames(),
            (std::vector<std::string>{"unexpected-character", "unexpected-character"}));
  ASSERT_EQ(tokens.size(), 5u);
  EXPECT_EQ(textOf(tokens[1].span), "@@@");
}

} // namespace
} // namespace cncc::frontend
