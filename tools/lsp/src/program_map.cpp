#include "cncc/lsp/program_map.h"

#include "cncc/lsp/protocol_json.h"
#include "cncc/lsp/uri.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>

namespace cncc::lsp {

namespace {

struct MappedLine {
  std::string source; // absolute where the map says where relative ones are
  std::uint32_t line = 0;
  std::uint32_t column = 0;
  std::string statement;
  int loopDepth = 0;
};

std::optional<std::string> mapPath(std::string_view uri) {
  std::optional<std::string> path = pathFromUri(uri);
  if (!path || path->ends_with(".cdl")) {
    return std::nullopt;
  }
  return *path + ".map.json";
}

std::string sourceLine(const std::string& path, std::uint32_t line) {
  std::ifstream file(path, std::ios::binary);
  std::string text;
  for (std::uint32_t k = 0; k < line && std::getline(file, text); ++k) {
  }
  return text;
}

// The map beside the program, if it is this text's.
std::optional<Json> mapOf(std::string_view uri, std::string_view text) {
  std::optional<std::string> path = mapPath(uri);
  std::ifstream file(path.value_or(""), std::ios::binary);
  if (!path || !file) {
    return std::nullopt;
  }
  Json map = Json::parse(file, nullptr, false);
  if (!map.is_object() || map.value("version", 0) != 1 ||
      map.value("programHash", std::string()) != programHash(text) || !map.contains("lines") ||
      !map["lines"].is_array() || !map.contains("sources") || !map["sources"].is_array()) {
    return std::nullopt;
  }
  return map;
}

// A {"source", "line", "column", ...} entry of the map, its source resolved.
std::optional<MappedLine> mappedEntry(const Json& map, const Json& entry) {
  std::size_t source = entry.is_object() ? entry.value("source", std::size_t{0}) : 0;
  if (!entry.is_object() || source >= map["sources"].size() ||
      !map["sources"][source].is_string()) {
    return std::nullopt;
  }
  return MappedLine{resolvedSourcePath(map, map["sources"][source].get<std::string>()),
                    entry.value("line", 0u), entry.value("column", 0u),
                    entry.value("statement", std::string("part")), entry.value("loopDepth", 0)};
}

std::optional<MappedLine> mappedLine(std::string_view uri, std::string_view text,
                                     std::uint32_t line) {
  std::optional<Json> map = mapOf(uri, text);
  if (!map || line >= (*map)["lines"].size()) {
    return std::nullopt;
  }
  return mappedEntry(*map, (*map)["lines"][line]);
}

// The `#n` under the cursor on `line` of the program, if any.
std::optional<int> variableAt(std::string_view text, Position position) {
  for (std::uint32_t k = 0; k < position.line && !text.empty(); ++k) {
    std::size_t newline = text.find('\n');
    text = newline == std::string_view::npos ? std::string_view() : text.substr(newline + 1);
  }
  std::string_view line = text.substr(0, text.find('\n'));
  std::size_t at = std::min<std::size_t>(position.character, line.size());
  std::size_t begin = at;
  while (begin > 0 && std::isdigit(static_cast<unsigned char>(line[begin - 1])) != 0) {
    --begin;
  }
  if (begin < line.size() && line[begin] == '#') {
    ++begin; // the cursor on the '#'
  } else if (begin == 0 || line[begin - 1] != '#') {
    return std::nullopt;
  }
  std::size_t end = begin;
  while (end < line.size() && end - begin < 6 &&
         std::isdigit(static_cast<unsigned char>(line[end])) != 0) {
    ++end;
  }
  if (end == begin) {
    return std::nullopt;
  }
  return std::stoi(std::string(line.substr(begin, end - begin)));
}

// The hover of `#variable`: what it holds and the statements it comes from.
Json variableHover(const Json& map, int variable) {
  if (!map.contains("variables") || !map["variables"].is_object() ||
      !map["variables"].contains(std::to_string(variable))) {
    return nullptr;
  }
  const Json& held = map["variables"][std::to_string(variable)];
  std::string value = fmt::format("`#{}`: {}", variable, held.value("meaning", std::string("?")));
  if (held.contains("statements") && held["statements"].is_array()) {
    for (const Json& statement : held["statements"]) {
      if (std::optional<MappedLine> from = mappedEntry(map, statement)) {
        value +=
            fmt::format("\n\n{}:{}: `{}`", std::filesystem::path(from->source).filename().string(),
                        from->line, sourceLine(from->source, from->line));
      }
    }
  }
  return {{"contents", {{"kind", "markdown"}, {"value", value}}}};
}

} // namespace

std::string programHash(std::string_view text) {
  std::uint64_t hash = 14695981039346656037ull;
  for (char c : text) {
    hash ^= static_cast<unsigned char>(c);
    hash *= 1099511628211ull;
  }
  return fmt::format("{:016x}", hash);
}

std::string resolvedSourcePath(const Json& map, const std::string& source) {
  std::filesystem::path path = source;
  auto directory = map.find("directory");
  if (path.is_relative() && directory != map.end() && directory->is_string()) {
    path = std::filesystem::path(directory->get<std::string>()) / path;
  }
  return path.string();
}

bool isMappedProgram(std::string_view uri) {
  std::optional<std::string> path = mapPath(uri);
  std::error_code error;
  return path && std::filesystem::exists(*path, error);
}

Json programDefinition(std::string_view uri, std::string_view text, Position position) {
  std::optional<MappedLine> mapped = mappedLine(uri, text, position.line);
  if (!mapped || mapped->line == 0) {
    return nullptr;
  }
  Position at{mapped->line - 1, mapped->column > 0 ? mapped->column - 1 : 0};
  return toJson(Location{uriFromPath(mapped->source), Range{at, at}});
}

Json programHover(std::string_view uri, std::string_view text, Position position) {
  if (std::optional<int> variable = variableAt(text, position)) {
    std::optional<Json> map = mapOf(uri, text);
    return map ? variableHover(*map, *variable) : Json(nullptr);
  }
  std::optional<MappedLine> mapped = mappedLine(uri, text, position.line);
  if (!mapped || mapped->line == 0) {
    return nullptr;
  }
  std::string name = std::filesystem::path(mapped->source).filename().string();
  std::string value = fmt::format("printed by the {} statement at {}:{}:{}", mapped->statement,
                                  name, mapped->line, mapped->column);
  if (mapped->loopDepth > 0) {
    value += fmt::format(", inside {} controller loop{}", mapped->loopDepth,
                         mapped->loopDepth == 1 ? "" : "s");
  }
  value += fmt::format("\n\n```cdl\n{}\n```", sourceLine(mapped->source, mapped->line));
  return {{"contents", {{"kind", "markdown"}, {"value", value}}}};
}

} // namespace cncc::lsp
