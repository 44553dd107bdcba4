#include "cncc/frontend/source_manager.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace cncc::frontend {

SourceFile::SourceFile(std::string path, std::string text)
    : path_(std::move(path)), text_(std::move(text)) {}

const std::vector<std::uint32_t>& SourceFile::lineStarts() const {
  std::call_once(lineStartsFound_, [this] {
    lineStarts_.reserve(text_.size() / 32 + 1); // a guess: lines are rarely shorter
    lineStarts_.push_back(0);
    // find() is memchr: many bytes per step.
    std::string_view contents = text_;
    for (std::size_t lineEnd = contents.find('\n'); lineEnd != std::string_view::npos;
         lineEnd = contents.find('\n', lineEnd + 1)) {
      lineStarts_.push_back(static_cast<std::uint32_t>(lineEnd + 1));
    }
  });
  return lineStarts_;
}

LineColumn SourceFile::lineColumn(std::uint32_t offset) const {
  const std::vector<std::uint32_t>& starts = lineStarts();
  offset = std::min<std::uint32_t>(offset, static_cast<std::uint32_t>(text_.size()));
  auto next = std::upper_bound(starts.begin(), starts.end(), offset);
  auto lineIndex = static_cast<std::uint32_t>(next - starts.begin()) - 1;
  return {lineIndex + 1, offset - starts[lineIndex] + 1};
}

std::string_view SourceFile::lineText(std::uint32_t line) const {
  const std::vector<std::uint32_t>& starts = lineStarts();
  if (line == 0 || line > starts.size()) {
    return {};
  }
  std::uint32_t begin = starts[line - 1];
  std::uint32_t end =
      line < starts.size() ? starts[line] : static_cast<std::uint32_t>(text_.size());
  std::string_view result(text_.data() + begin, end - begin);
  while (!result.empty() && (result.back() == '\n' || result.back() == '\r')) {
    result.remove_suffix(1);
  }
  return result;
}

std::uint32_t SourceFile::offsetOf(std::uint32_t zeroBasedLine,
                                   std::uint32_t zeroBasedColumn) const {
  const std::vector<std::uint32_t>& starts = lineStarts();
  if (zeroBasedLine >= starts.size()) {
    return static_cast<std::uint32_t>(text_.size());
  }
  auto lineLength = static_cast<std::uint32_t>(lineText(zeroBasedLine + 1).size());
  return starts[zeroBasedLine] + std::min(zeroBasedColumn, lineLength);
}

std::string_view SourceFile::keepUnescaped(std::uint32_t offset, std::string unescaped) const {
  std::lock_guard lock(unescapedMutex_);
  return unescaped_.try_emplace(offset, std::move(unescaped)).first->second;
}

FileId SourceManager::addFile(std::string path, std::string text) {
  files_.push_back(std::make_unique<SourceFile>(std::move(path), std::move(text)));
  return FileId{static_cast<std::uint32_t>(files_.size())};
}

std::optional<FileId> SourceManager::findFile(const std::string& path) const {
  for (std::size_t i = 0; i < files_.size(); ++i) {
    if (files_[i]->path() == path) {
      return FileId{static_cast<std::uint32_t>(i + 1)};
    }
  }
  return std::nullopt;
}

std::vector<std::string> SourceManager::paths() const {
  std::vector<std::string> paths;
  for (const std::unique_ptr<SourceFile>& file : files_) {
    paths.push_back(file->path());
  }
  return paths;
}

std::optional<FileId> SourceManager::loadFile(const std::string& path) {
  if (auto existing = findFile(path)) {
    return existing;
  }
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) {
    return std::nullopt;
  }
  std::ifstream stream(path, std::ios::binary);
  if (!stream) {
    return std::nullopt;
  }
  // Read at once into a string of the file's size; the size is only a hint
  // (the file may change meanwhile), so whatever is left is read after it.
  std::uintmax_t size = std::filesystem::file_size(path, error);
  std::string contents(error ? 0 : static_cast<std::size_t>(size), '\0');
  stream.read(contents.data(), static_cast<std::streamsize>(contents.size()));
  contents.resize(static_cast<std::size_t>(stream.gcount()));
  if (stream.eof()) {
    stream.clear();
  } else {
    std::ostringstream rest;
    rest << stream.rdbuf();
    contents += rest.str();
  }
  if (stream.bad()) {
    return std::nullopt;
  }
  return addFile(path, std::move(contents));
}

std::string_view SourceManager::text(SourceSpan span) const {
  if (!span.valid()) {
    return {};
  }
  std::string_view all = file(span.file).text();
  std::uint32_t begin = std::min<std::uint32_t>(span.begin, static_cast<std::uint32_t>(all.size()));
  std::uint32_t end = std::min<std::uint32_t>(span.end, static_cast<std::uint32_t>(all.size()));
  return all.substr(begin, end > begin ? end - begin : 0);
}

} // namespace cncc::frontend
