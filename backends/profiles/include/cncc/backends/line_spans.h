// Where each printed line of a program comes from, for source maps: the CDL
// span, the written-out sweep pass, and the controller loops around it. A
// printer says where each instruction's lines begin, whatever writes them,
// and the lines between inherit the origin before them.
#pragma once

#include "cncc/frontend/source_span.h"
#include "cncc/ir/ir.h"

#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace cncc::backends {

inline constexpr std::uint32_t noControllerLoop = std::numeric_limits<std::uint32_t>::max();

// A loop the printer wrote (WHILE .. END, o-word while, LBL .. GOTO): the
// statement whose IR loop it prints, and the loop around it.
struct ControllerLoop {
  frontend::SourceSpan span;
  ir::LoopRole role = ir::LoopRole::Statement;
  std::uint32_t outer = noControllerLoop;
};

struct LineOrigin {
  frontend::SourceSpan span; // invalid: the part's own
  ir::SweepPass pass;
  std::uint32_t loop = noControllerLoop; // the innermost loop holding the line
};

// Of every line of a program, and the loops they name.
struct LineOrigins {
  std::vector<LineOrigin> lines;
  std::vector<ControllerLoop> loops;
};

// The origin of what an instruction prints, inside the loop `loop`.
inline LineOrigin originOf(const ir::Instruction& instruction, std::uint32_t loop) {
  return {instruction.span, instruction.pass, loop};
}

class LineSpans {
public:
  // The lines from `firstLine` on come from `origin` (until the next start).
  void start(std::size_t firstLine, LineOrigin origin) { starts_.emplace_back(firstLine, origin); }
  // The origin of each of `lineCount` lines (the part's before the first start).
  std::vector<LineOrigin> origins(std::size_t lineCount) const;
  // The origin of each line that formatting kept (FormattedProgram::printedLine).
  static std::vector<LineOrigin> kept(const std::vector<LineOrigin>& origins,
                                      const std::vector<std::size_t>& printedLine);

private:
  std::vector<std::pair<std::size_t, LineOrigin>> starts_;
};

// Marks an instruction's lines: they start at the current line count, and
// the lines after the instruction (a loop's END) go back to the outer origin.
class InstructionLines {
public:
  InstructionLines(LineSpans& spans, const std::vector<std::string>& lines,
                   const ir::Instruction& instruction, LineOrigin& current)
      : spans_(spans), lines_(lines), current_(current), outer_(current) {
    current_ = originOf(instruction, current.loop);
    spans_.start(lines_.size(), current_);
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
  LineOrigin& current_;
  LineOrigin outer_;
};

// The lines from the next one on are inside a new loop made from
// `instruction` (call before its head line); the InstructionLines of the
// loop's instruction ends it after its last line.
inline void enterLoop(LineSpans& spans, std::vector<ControllerLoop>& loops, std::size_t nextLine,
                      const ir::Instruction& instruction, LineOrigin& current) {
  loops.push_back({instruction.span, static_cast<ir::LoopRole>(instruction.index), current.loop});
  current.loop = static_cast<std::uint32_t>(loops.size() - 1);
  spans.start(nextLine, current);
}

} // namespace cncc::backends
