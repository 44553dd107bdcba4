// The editor files in lang/: the TextMate grammar knows every keyword,
// builtin and modifier of the front end, and the VS Code extension's
// manifest points at files that exist and starts `cncc lsp`.
// GCC 12 warns about std::regex's own code under the sanitizers
// (-Wmaybe-uninitialized, a false positive); the test needs a regex engine.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif

#include "session.h"

#include "cncc/frontend/ast.h"
#include "cncc/frontend/lexer.h"
#include "cncc/frontend/sema.h"

#include <filesystem>
#include <regex>

namespace cncc::lsp::testing {
namespace {

const std::string extensionFolder = "lang/vscode";

Json grammar() {
  return Json::parse(readSourceFile(extensionFolder + "/syntaxes/cdl.tmLanguage.json"));
}

// The `match` regexes of one repository entry (its own and its patterns').
std::vector<std::regex> matchesOf(const Json& entry) {
  std::vector<std::regex> result;
  if (entry.contains("match")) {
    result.emplace_back(entry["match"].get<std::string>());
  }
  if (entry.contains("patterns")) {
    for (const Json& pattern : entry["patterns"]) {
      for (std::regex& regex : matchesOf(pattern)) {
        result.push_back(std::move(regex));
      }
    }
  }
  return result;
}

// Whether some regex of `entries` matches `text` starting at its first
// character and covering at least `word`.
bool highlights(const Json& repository, std::initializer_list<const char*> entries,
                const std::string& text, const std::string& word) {
  for (const char* entry : entries) {
    for (const std::regex& regex : matchesOf(repository[entry])) {
      std::smatch match;
      if (std::regex_search(text, match, regex) && match.position(0) <= 2 &&
          match.position(0) + match.length(0) >= static_cast<long>(word.size())) {
        return true;
      }
    }
  }
  return false;
}

TEST(EditorGrammar, EveryRegexCompilesAndTheScopeIsCdl) {
  Json loaded = grammar();
  EXPECT_EQ(loaded["scopeName"], "source.cdl");
  for (const auto& [name, entry] : loaded["repository"].items()) {
    EXPECT_NO_THROW(matchesOf(entry)) << name;
  }
}

TEST(EditorGrammar, KnowsEveryKeyword) {
  Json repository = grammar()["repository"];
  for (auto kind = static_cast<int>(frontend::TokenKind::KwPart);
       kind <= static_cast<int>(frontend::TokenKind::KwFalse); ++kind) {
    std::string keyword(frontend::tokenSpelling(static_cast<frontend::TokenKind>(kind)));
    EXPECT_TRUE(highlights(repository, {"declarations", "statements", "keywords", "constants"},
                           keyword + " x", keyword))
        << keyword;
  }
  for (const char* word : {"units", "tool", "feed", "spindle", "safe", "origin", "coolant"}) {
    EXPECT_TRUE(highlights(repository, {"statements"}, std::string("  ") + word + " 1", word))
        << word;
  }
}

TEST(EditorGrammar, KnowsEveryBuiltinAndModifier) {
  Json repository = grammar()["repository"];
  for (const frontend::BuiltinInfo& builtin : frontend::builtinFunctions()) {
    EXPECT_TRUE(highlights(repository, {"builtins"}, builtin.name + "(x)", builtin.name))
        << builtin.name;
  }
  for (const std::string& modifier : frontend::cutModifierNames()) {
    std::string text = modifier == "sweep" ? modifier : modifier + "=1";
    EXPECT_TRUE(highlights(repository, {"modifiers"}, text, modifier)) << modifier;
  }
}

TEST(VsCodeExtension, ManifestPointsAtItsFilesAndStartsTheServer) {
  Json manifest = Json::parse(readSourceFile(extensionFolder + "/package.json"));
  std::filesystem::path folder = std::filesystem::path(CNCC_SOURCE_DIR) / extensionFolder;
  const Json& language = manifest["contributes"]["languages"][0];
  EXPECT_EQ(language["id"], "cdl");
  EXPECT_EQ(language["extensions"], Json::array({".cdl"}));
  EXPECT_TRUE(std::filesystem::exists(folder / language["configuration"].get<std::string>()));
  EXPECT_TRUE(std::filesystem::exists(
      folder / manifest["contributes"]["grammars"][0]["path"].get<std::string>()));
  ASSERT_TRUE(std::filesystem::exists(folder / manifest["main"].get<std::string>()));
  std::string client = readSourceFile(extensionFolder + "/extension.js");
  EXPECT_NE(client.find("['lsp'"), std::string::npos);
  EXPECT_NO_THROW(EXPECT_TRUE(
      Json::parse(readSourceFile(extensionFolder + "/language-configuration.json")).is_object()));
}

} // namespace
} // namespace cncc::lsp::testing
