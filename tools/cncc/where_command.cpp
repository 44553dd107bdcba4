// `cncc where PROGRAM LINE|Nnnnn [--source-map FILE.json]`: which CDL
// statement printed a line of a compiled program (source_map.h).
#include "commands.h"
#include "source_map.h"

#include "cncc/lsp/program_map.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <cctype>
#include <charconv>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace cncc::driver {

namespace {

// A problem `where` reports as `cncc: error: ...`, exit 1.
class WhereError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

std::string readFile(const std::string& path, std::string_view what) {
  std::error_code error;
  std::ifstream file(path, std::ios::binary);
  if (!std::filesystem::is_regular_file(path, error) || !file) { // a folder opens, reads nothing
    throw WhereError(fmt::format("cannot read {} '{}'", what, path));
  }
  std::ostringstream text;
  text << file.rdbuf();
  return text.str();
}

std::vector<std::string> linesOf(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream stream(text);
  for (std::string line; std::getline(stream, line);) {
    lines.push_back(line);
  }
  return lines;
}

nlohmann::json readMap(const std::string& path, const std::string& programText) {
  nlohmann::json map;
  try {
    map = nlohmann::json::parse(readFile(path, "the source map"));
  } catch (const nlohmann::json::exception& error) {
    throw WhereError(fmt::format("the source map '{}' is not valid JSON: {}", path, error.what()));
  }
  if (!map.is_object() || map.value("version", 0) != 1 || !map["lines"].is_array() ||
      !map["sources"].is_array() || !map["programHash"].is_string()) {
    throw WhereError(fmt::format("'{}' is not a cncc source map (version 1)", path));
  }
  if (map["programHash"].get<std::string>() != programHash(programText)) {
    throw WhereError(fmt::format("the source map '{}' is for another program than this one (or "
                                 "the program was changed since)",
                                 path));
  }
  return map;
}

// The 1-based program line `location` names: a line number, or the first
// block numbered Nnnnn.
std::size_t programLine(const std::string& location, const std::vector<std::string>& lines,
                        const std::string& programPath) {
  bool blockNumber = !location.empty() && (location[0] == 'N' || location[0] == 'n');
  std::string digits = blockNumber ? location.substr(1) : location;
  std::size_t number = 0;
  auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), number);
  if (digits.empty() || error != std::errc() || end != digits.data() + digits.size()) {
    throw WhereError(
        fmt::format("'{}' is neither a line number nor a block number Nnnnn", location));
  }
  if (!blockNumber) {
    if (number < 1 || number > lines.size()) {
      throw WhereError(
          fmt::format("{} has {} lines; there is no line {}", programPath, lines.size(), number));
    }
    return number;
  }
  std::string word = fmt::format("N{}", number);
  for (std::size_t i = 0; i < lines.size(); ++i) {
    std::string_view code = lines[i];
    code.remove_prefix(std::min(code.find_first_not_of(" \t"), code.size()));
    if (code.starts_with(word) && (code.size() == word.size() ||
                                   !std::isdigit(static_cast<unsigned char>(code[word.size()])))) {
      return i + 1;
    }
  }
  throw WhereError(fmt::format("{} has no block {}", programPath, word));
}

// The entry's object `field`, or null.
const nlohmann::json* optionalObject(const nlohmann::json& entry, const char* field) {
  auto found = entry.find(field);
  return found != entry.end() && found->is_object() ? &*found : nullptr;
}

std::string describe(const nlohmann::json& entry, const nlohmann::json& map) {
  std::string statement = entry.value("statement", "part");
  std::string text = statement == "part" ? fmt::format("printed for part {} itself (its set-up)",
                                                       map.value("part", ""))
                                         : fmt::format("printed from this {} statement of part {}",
                                                       statement, map.value("part", ""));
  if (const nlohmann::json* pass = optionalObject(entry, "pass")) {
    std::size_t number = pass->value("number", std::size_t{0});
    if (number > 0) {
      text += fmt::format(", pass {} of {}", number, pass->value("count", std::size_t{0}));
    }
    if (pass->value("ramp", false)) {
      text += number > 0 ? " (its ramp lap)" : ", the ramp lap of each pass";
    }
  }
  int depth = entry.value("loopDepth", 0);
  if (depth > 0) {
    text += fmt::format(", inside {} controller loop{}", depth, depth == 1 ? "" : "s");
  }
  return text;
}

// "the passes of the cut at ring.cdl:12:3": one loop of the map's "loops".
std::string describeLoop(const nlohmann::json& loop, const nlohmann::json& map) {
  std::string kind = loop.value("kind", "");
  std::string statement = loop.value("statement", "statement");
  std::string what = kind == "passes"  ? fmt::format("the passes of the {}", statement)
                     : kind == "curve" ? fmt::format("the steps along the {}", statement)
                                       : fmt::format("the {} statement", statement);
  std::size_t source = loop.value("source", std::size_t{0});
  std::string path = source < map["sources"].size() && map["sources"][source].is_string()
                         ? map["sources"][source].get<std::string>()
                         : "?";
  return fmt::format("{} at {}:{}:{}", what, path, loop.value("line", 0), loop.value("column", 0));
}

// The controller loops holding the line, outermost first, as notes.
void printLoops(const nlohmann::json& entry, const nlohmann::json& map) {
  auto loops = entry.find("loops");
  auto table = map.find("loops");
  if (loops == entry.end() || !loops->is_array() || table == map.end() || !table->is_array()) {
    return;
  }
  for (const nlohmann::json& index : *loops) {
    if (index.is_number_unsigned() && index.get<std::size_t>() < table->size()) {
      fmt::print("  in a controller loop made by {}\n",
                 describeLoop((*table)[index.get<std::size_t>()], map));
    }
  }
}

// A position the map's entry gives: a whole number from 1 on.
std::size_t positionOf(const nlohmann::json& entry, const char* field, std::size_t programLine,
                       const std::string& mapPath) {
  auto found = entry.find(field);
  if (found == entry.end() || !found->is_number_unsigned() || found->get<std::size_t>() == 0) {
    throw WhereError(fmt::format("the source map '{}' gives no valid {} for line {}", mapPath,
                                 field, programLine));
  }
  return found->get<std::size_t>();
}

// The source's lines, or nothing when it cannot be read (moved since).
std::optional<std::vector<std::string>> sourceLines(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) {
    return std::nullopt;
  }
  std::ostringstream text;
  text << file.rdbuf();
  return linesOf(text.str());
}

void printSourceLine(const std::string& text, std::size_t column) {
  std::string indent;
  for (std::size_t k = 0; k + 1 < column && k < text.size(); ++k) {
    indent += text[k] == '\t' ? '\t' : ' ';
  }
  fmt::print("  {}\n  {}^\n", text, indent);
}

void printParameters(const nlohmann::json& parameters) {
  if (!parameters.is_object() || parameters.empty()) {
    return;
  }
  std::string list;
  for (const auto& [name, value] : parameters.items()) {
    std::string shown = value.is_number() ? fmt::format("{:g}", value.get<double>()) : value.dump();
    list += fmt::format("{}{}={}", list.empty() ? "" : ", ", name, shown);
  }
  fmt::print("compiled with {}\n", list);
}

} // namespace

int runWhere(const DriverOptions& options) {
  const std::string& programPath = options.inputs.front();
  try {
    std::string programText = readFile(programPath, "the program");
    nlohmann::json map = readMap(options.sourceMap, programText);
    std::vector<std::string> lines = linesOf(programText);
    std::size_t line = programLine(options.whereLocation, lines, programPath);
    const nlohmann::json& entries = map["lines"];
    if (line > entries.size()) {
      throw WhereError(
          fmt::format("the source map '{}' has no entry for line {}", options.sourceMap, line));
    }
    const nlohmann::json& entry = entries[line - 1];
    std::size_t source = entry.value("source", std::size_t{0});
    if (source >= map["sources"].size() || !map["sources"][source].is_string()) {
      throw WhereError(
          fmt::format("the source map '{}' names no source for line {}", options.sourceMap, line));
    }
    std::string sourcePath = map["sources"][source].get<std::string>();
    std::size_t sourceLine = positionOf(entry, "line", line, options.sourceMap);
    std::size_t column = positionOf(entry, "column", line, options.sourceMap);
    std::optional<std::vector<std::string>> quoted =
        sourceLines(lsp::resolvedSourcePath(map, sourcePath));
    if (quoted && sourceLine > quoted->size()) {
      throw WhereError(fmt::format("the source map '{}' maps line {} to {}:{}, but that file has "
                                   "{} lines (it changed since the map was written)",
                                   options.sourceMap, line, sourcePath, sourceLine,
                                   quoted->size()));
    }
    fmt::print("{}:{}: {}\n", programPath, line, lines[line - 1]);
    fmt::print("{}:{}:{}: note: {}\n", sourcePath, sourceLine, column, describe(entry, map));
    if (quoted) {
      printSourceLine((*quoted)[sourceLine - 1], column);
    }
    printLoops(entry, map);
    printParameters(map["parameters"]);
    return 0;
  } catch (const WhereError& error) {
    std::fflush(stdout);
    fmt::print(stderr, "cncc: error: {}\n", error.what());
    return 1;
  } catch (const nlohmann::json::exception& error) {
    fmt::print(stderr, "cncc: error: the source map '{}' is malformed: {}\n", options.sourceMap,
               error.what());
    return 1;
  }
}

} // namespace cncc::driver
