#include "cncc/lsp/program_map.h"

#include "cncc/lsp/protocol_json.h"
#include "cncc/lsp/uri.h"

#include <fmt/format.h>

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

std::optional<MappedLine> mappedLine(std::string_view uri, std::string_view text,
                                     std::uint32_t line) {
  std::optional<std::string> path = mapPath(uri);
  std::ifstream file(path.value_or(""), std::ios::binary);
  if (!path || !file) {
    return std::nullopt;
  }
  Json map = Json::parse(file, nullptr, false);
  if (!map.is_object() || map.value("version", 0) != 1 ||
      map.value("programHash", std::string()) != programHash(text) || !map.contains("lines") ||
      !map["lines"].is_array() || line >= map["lines"].size() || !map["sources"].is_array()) {
    return std::nullopt;
  }
  const Json& entry = map["lines"][line];
  std::size_t source = entry.value("source", std::size_t{0});
  if (!entry.is_object() || source >= map["sources"].size() ||
      !map["sources"][source].is_string()) {
    return std::nullopt;
  }
  std::filesystem::path sourcePath = map["sources"][source].get<std::string>();
  if (sourcePath.is_relative() && map.contains("directory") && map["directory"].is_string()) {
    sourcePath = std::filesystem::path(map["directory"].get<std::string>()) / sourcePath;
  }
  return MappedLine{sourcePath.string(), entry.value("line", 0u), entry.value("column", 0u),
                    entry.value("statement", std::string("part")), entry.value("loopDepth", 0)};
}

std::string sourceLine(const std::string& path, std::uint32_t line) {
  std::ifstream file(path, std::ios::binary);
  std::string text;
  for (std::uint32_t k = 0; k < line && std::getline(file, text); ++k) {
  }
  return text;
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
