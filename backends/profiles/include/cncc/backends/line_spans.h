// Which CDL span each printed line of a program comes from, for source
// maps: a printer says where each instruction's lines begin, whatever
// writes them, and the lines between inherit the span before them.
#pragma once

#include "cncc/frontend/source_span.h"

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace cncc::backends {

class LineSpans {
public:
  // The lines from `firstLine` on come from `span` (until the next start).
  void start(std::size_t firstLine, frontend::SourceSpan span) {
    starts_.emplace_back(firstLine, span);
  }
  // The span of each of `lineCount` lines (invalid before the first start).
  std::vector<frontend::SourceSpan> spans(std::size_t lineCount) const;
  // The span of each line that formatting kept (FormattedProgram::printedLine).
  static std::vector<frontend::SourceSpan> kept(const std::vector<frontend::SourceSpan>& spans,
                                                const std::vector<std::size_t>& printedLine);

private:
  std::vector<std::pair<std::size_t, frontend::SourceSpan>> starts_;
};

// Marks an instruction's lines: they start at the current line count, and
// the lines after the instruction (a loop's END) go back to the outer span.
class InstructionLines {
public:
  InstructionLines(LineSpans& spans, const std::vector<std::string>& lines,
                   frontend::SourceSpan span, frontend::SourceSpan& current)
      : spans_(spans), lines_(lines), current_(current), outer_(current) {
    current_ = span;
    spans_.start(lines_.size(), span);
  }
  ~InstructionLines() {
    current_ = outer_;
    spans_.start(lines_.size(), outer_);
  }
  InstructionLines(const InstructionLines&) = delete;
  InstructionLines& operator=(const InstructionLines&) = delete;

private:
  LineSpans& spans_;
  const std::vector<std::string>& lines_;
  frontend::SourceSpan& current_;
  frontend::SourceSpan outer_;
};

} // namespace cncc::backends
