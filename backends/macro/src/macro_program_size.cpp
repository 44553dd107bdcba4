#include "cncc/backends/macro_program.h"

#include <string_view>

namespace cncc::backends {

namespace {

bool isCommentLine(std::string_view line) {
  return line.starts_with("(");
}

} // namespace

MacroProgramStatistics measureMacroProgram(const std::string& text) {
  MacroProgramStatistics statistics;
  statistics.bytes = text.size();
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) {
      end = text.size();
    }
    std::string_view line(text.data() + start, end - start);
    if (line != "%") {
      ++statistics.blocks;
    }
    std::string bare;
    int depth = 0;
    for (char c : line) {
      if (c == ';' && depth == 0) {
        break; // LinuxCNC's comment to the end of the line
      }
      depth += c == '(' ? 1 : 0;
      if (depth == 0) {
        bare += c;
      }
      depth -= (c == ')' && depth > 0) ? 1 : 0;
    }
    while (!bare.empty() && bare.back() == ' ') {
      bare.pop_back();
    }
    if (!bare.empty() && !isCommentLine(line)) {
      statistics.bytesWithoutComments += bare.size() + 1;
    }
    start = end + 1;
  }
  return statistics;
}

} // namespace cncc::backends
