// What a part makes the machine do, in order: the output of the IR
// interpreter and the JIT, and the input of the numeric backends.
#pragma once

#include <string>
#include <vector>

namespace cncc::ir {

struct MachineEvent {
  enum class Kind { Rapid, Feed, Spindle, Tool, Comment, CutBegin };
  Kind kind = Kind::Rapid;
  double x = 0, y = 0, z = 0; // Rapid, Feed: the target
  double feed = 0;            // Feed: mm/min
  double number = 0;          // Spindle: rpm; Tool: the tool number; CutBegin: the cut index
  double diameter = 0;        // Tool
  std::string text;           // Comment
};

struct ToolPath {
  std::vector<MachineEvent> events;
};

} // namespace cncc::ir
