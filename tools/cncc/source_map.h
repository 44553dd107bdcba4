// Source maps (`--source-map FILE.json`): for every line of a compiled
// program, the CDL file, line and column of what printed it, and the
// parameter values it was compiled with; `cncc where` reads them back.
//
// The JSON (version 1):
//   {"version": 1, "program": "O1000.nc", "programHash": "<FNV-1a 64, hex>",
//    "target": "fanuc", "part": "ring",
//    "parameters": {"radius": 20, ...},
//    "sources": ["ring.cdl", "/.../std/curves.cdl"],
//    "directory": "/home/shop/parts",  (what relative sources are relative to)
//    "loops": [{"source": 0, "line": 10, "column": 3, "statement": "for", "kind": "for"},
//              {"source": 0, "line": 12, "column": 3, "statement": "cut",
//               "kind": "passes"}, ...],                     (when a line names one)
//    "lines": [{"source": 0, "line": 12, "column": 3, "statement": "cut",
//               "loopDepth": 2, "loops": [0, 1]},
//              {..., "statement": "cut", "loopDepth": 0,
//               "pass": {"number": 2, "count": 3}}, ...],
//    "variables": {"6": {"meaning": "work values", "statements":
//                  [{"source": 0, "line": 16, "column": 5}]}, ...},  (macro targets)
//    "unit": "mm",
//    "cuts": [{"source": 0, "line": 12, "column": 3, "blocks": 40, "bytes": 1210,
//              "deviation": 0.0061, "tolerance": 0.01}, ...]}
// "cuts" has one entry per cut statement that printed lines: the blocks
// (lines with code) and bytes of those lines, and when the compile measured
// them (--stats) the largest deviation of its executed path from the curve
// over every time the statement ran, and its tolerance (null: samples= or
// spacing= chose the points), in "unit".
// `lines[i]` is line i + 1 of the program; "statement" is the kind of CDL
// statement (part, tool, cut, for, if, let, origin, coolant, feed, ...),
// "loopDepth" how many controller loops (WHILE, o-word while) hold the line.
// Optional fields of a line (added within version 1; absent in older maps):
// "pass" where the line belongs to one written-out pass of a cut's sweep
// (depth= step=): its "number" from 1 and the sweep's "count", and
// "ramp": true on the entry=ramp lap descending to it; a ramp lap inside a
// pass loop computed on the controller has number 0 and count 0 (the loop
// says the pass). "loops": the controller loops the printer opened around
// the line (WHILE .. END, o-word while, the TNC's LBL .. GOTO; the loop's
// first and last lines count as inside it), outermost first, as indexes
// into the top-level "loops": each the statement whose loop it prints and
// its "kind": "for" (a for statement), "passes" (a cut's pass loop) or
// "curve" (the steps along a cut's curve).
#pragma once

#include "cncc/backends/line_spans.h"
#include "cncc/backends/machine_setup.h"
#include "cncc/backends/macro_program.h"
#include "cncc/frontend/sema.h"
#include "cncc/frontend/source_manager.h"

#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace cncc::driver {

// The largest deviation --stats measured for one cut of the part.
struct MeasuredCutDeviation {
  frontend::SourceSpan statement; // the cut's `curve` statement
  double deviation = 0;           // NaN: no feed move
  double tolerance = 0;           // NaN: samples= or spacing= chose the points
};

struct SourceMapInput {
  std::string programPath;
  std::string_view programText;
  std::string target;
  const frontend::CheckedProgram* program = nullptr; // its selected part
  const frontend::SourceManager* sources = nullptr;
  // Where each program line comes from (an invalid span: the part's own),
  // and the controller loops they name.
  backends::LineOrigins lines;
  // Macro targets: what each variable holds.
  std::map<int, backends::VariableMeaning> variables;
  bool inches = false;
  // Empty unless --stats measured the program.
  std::vector<MeasuredCutDeviation> deviations;
};

// Where a program's lines and variables come from, as its backend said.
struct ProgramOrigins {
  backends::LineOrigins lines;
  std::map<int, backends::VariableMeaning> variables;
  std::vector<MeasuredCutDeviation> deviations;
};

std::string sourceMapJson(const SourceMapInput& input);

// --annotate: a comment `(file.cdl:12)` (`; file.cdl:12` on Sinumerik and
// LinuxCNC) before the first line a cut statement printed, and again where
// another cut's lines came between, and after the header of each Sinumerik
// subprogram; `lines` gets the comments' origins too.
std::string annotatedProgram(std::string_view text, std::vector<backends::LineOrigin>& lines,
                             const frontend::CheckedProgram& program,
                             const frontend::SourceManager& sources,
                             const backends::MachineSetup& setup);

// FNV-1a, 64 bits, in hex: what a map checks its program against.
std::string programHash(std::string_view text);

} // namespace cncc::driver
