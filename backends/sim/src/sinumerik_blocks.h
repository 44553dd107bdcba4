// The blocks of a Sinumerik program as the virtual Sinumerik reads them:
// each line without its `;` comment, split into words.
#pragma once

#include "cncc/backends/sinumerik_controller.h"

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace cncc::backends::sinumerik {

// `X12.5`, `X=12.5`, `G1`, `SD=3`, `T="T1"`, `BSPLINE`, `SPLINEPATH(1,X,Y)`,
// or a subprogram's name.
// `X=R1*2` keeps its expression, evaluated when the block runs; `R3=...`
// assigns parameter 3.
struct SinumerikWord {
  std::string address;         // upper case: X, G, PW, BSPLINE, SPLINEPATH, ...
  std::optional<double> value; // the number after it, if any
  std::string text;            // T="..." : the string; SPLINEPATH: the list inside ( )
  std::string expression;      // after `=` when it is not a plain number, upper case
  int parameter = -1;          // R: the parameter an `Rn=` assigns
};

// The control structure a block opens or closes.
enum class Control { None, If, Else, EndIf, For, EndFor, While, EndWhile };

struct SinumerikBlock {
  int line = 0; // in the whole text
  std::vector<SinumerikWord> words;
  Control control = Control::None;
  std::string condition;   // IF, WHILE; FOR: the end value
  SinumerikWord counter;   // FOR: `Rn=start`
  std::size_t partner = 0; // IF: its ELSE or ENDIF; ELSE: ENDIF; FOR/WHILE: the END; END: the start
};

struct SinumerikProgramUnit {
  std::string name; // "" for a text without archive headers
  bool subprogram = false;
  std::vector<SinumerikBlock> blocks;
};

// The programs of `text`; the first main program first. Throws ProgramError.
std::vector<SinumerikProgramUnit> readSinumerikText(std::string_view text);

} // namespace cncc::backends::sinumerik
