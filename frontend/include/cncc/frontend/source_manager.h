// Source files loaded into memory, and the mapping from byte offsets to
// line and column that diagnostics, the language server and the AST use.
#pragma once

#include "cncc/frontend/source_span.h"

#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace cncc::frontend {

class SourceFile {
public:
  SourceFile(std::string path, std::string text);

  const std::string& path() const { return path_; }
  std::string_view text() const { return text_; }
  LineColumn lineColumn(std::uint32_t offset) const;
  // The text of a one-based line, without its line break.
  std::string_view lineText(std::uint32_t line) const;
  std::uint32_t lineCount() const { return static_cast<std::uint32_t>(lineStarts().size()); }
  // Byte offset of a zero-based line and a zero-based UTF-16-agnostic byte
  // column, clamped into the file (used by the language server).
  std::uint32_t offsetOf(std::uint32_t zeroBasedLine, std::uint32_t zeroBasedColumn) const;
  // The unescaped text of the string literal at `offset`, kept for as long as
  // the file so tokens can view it like the rest of the text (`unescaped` is
  // computed the first time only; lexing the file again finds it).
  std::string_view keepUnescaped(std::uint32_t offset, std::string unescaped) const;

private:
  // Where each line begins, found the first time it is asked for (from any
  // thread): a check that reports nothing never needs it.
  const std::vector<std::uint32_t>& lineStarts() const;

  std::string path_;
  std::string text_;
  mutable std::once_flag lineStartsFound_;
  mutable std::vector<std::uint32_t> lineStarts_;
  mutable std::mutex unescapedMutex_;
  mutable std::unordered_map<std::uint32_t, std::string> unescaped_;
};

class SourceManager {
public:
  // Adds a file held in memory (used for editor buffers and tests).
  FileId addFile(std::string path, std::string text);
  // Reads a file from disk; nullopt if it cannot be read. A file already
  // loaded under the same path is returned again.
  std::optional<FileId> loadFile(const std::string& path);
  std::optional<FileId> findFile(const std::string& path) const;

  const SourceFile& file(FileId id) const { return *files_.at(id.index - 1); }
  // The path of every file added or loaded, in that order.
  std::vector<std::string> paths() const;
  std::string_view text(SourceSpan span) const;

private:
  std::vector<std::unique_ptr<SourceFile>> files_;
};

} // namespace cncc::frontend
