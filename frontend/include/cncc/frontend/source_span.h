// Where something is in the sources: a file's index and a byte range. The
// vocabulary every layer shares (the IR keeps the span of what each
// instruction was lowered from); header-only, so the IR and the backends
// use it without the rest of the front end.
#pragma once

#include <cstdint>

namespace cncc::frontend {

// Index of a file in its SourceManager. Zero is "no file" (locations from
// the command line, for example).
struct FileId {
  std::uint32_t index = 0;
  bool valid() const { return index != 0; }
  friend bool operator==(FileId, FileId) = default;
};

// A half-open byte range [begin, end) in one file.
struct SourceSpan {
  FileId file;
  std::uint32_t begin = 0;
  std::uint32_t end = 0;

  bool valid() const { return file.valid(); }
  // The smallest span covering both (which must be in the same file).
  SourceSpan to(SourceSpan last) const { return {file, begin, last.end > end ? last.end : end}; }
  friend bool operator==(SourceSpan, SourceSpan) = default;
};

// One-based line and column; the column counts bytes.
struct LineColumn {
  std::uint32_t line = 0;
  std::uint32_t column = 0;
};

} // namespace cncc::frontend
