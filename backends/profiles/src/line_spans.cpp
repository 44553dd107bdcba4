#include "cncc/backends/line_spans.h"

namespace cncc::backends {

std::vector<frontend::SourceSpan> LineSpans::spans(std::size_t lineCount) const {
  std::vector<frontend::SourceSpan> spans(lineCount);
  std::size_t next = 0;
  frontend::SourceSpan span;
  for (std::size_t line = 0; line < lineCount; ++line) {
    while (next < starts_.size() && starts_[next].first <= line) {
      span = starts_[next++].second;
    }
    spans[line] = span;
  }
  return spans;
}

std::vector<frontend::SourceSpan> LineSpans::kept(const std::vector<frontend::SourceSpan>& spans,
                                                  const std::vector<std::size_t>& printedLine) {
  std::vector<frontend::SourceSpan> result;
  for (std::size_t index : printedLine) {
    result.push_back(index < spans.size() ? spans[index] : frontend::SourceSpan{});
  }
  return result;
}

} // namespace cncc::backends
