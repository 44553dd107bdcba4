#include "cncc/backends/line_spans.h"

namespace cncc::backends {

std::vector<LineOrigin> LineSpans::origins(std::size_t lineCount) const {
  std::vector<LineOrigin> origins(lineCount);
  std::size_t next = 0;
  LineOrigin origin;
  for (std::size_t line = 0; line < lineCount; ++line) {
    while (next < starts_.size() && starts_[next].first <= line) {
      origin = starts_[next++].second;
    }
    origins[line] = origin;
  }
  return origins;
}

std::vector<LineOrigin> LineSpans::kept(const std::vector<LineOrigin>& origins,
                                        const std::vector<std::size_t>& printedLine) {
  std::vector<LineOrigin> result;
  result.reserve(printedLine.size());
  for (std::size_t index : printedLine) {
    result.push_back(index < origins.size() ? origins[index] : LineOrigin{});
  }
  return result;
}

} // namespace cncc::backends
