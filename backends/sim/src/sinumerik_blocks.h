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
struct SinumerikWord {
  std::string address;         // upper case: X, G, PW, BSPLINE, SPLINEPATH, ...
  std::optional<double> value; // the number after it, if any
  std::string text;            // T="..." : the string; SPLINEPATH: the list inside ( )
};

struct SinumerikBlock {
  int line = 0; // in the whole text
  std::vector<SinumerikWord> words;
};

struct SinumerikProgramUnit {
  std::string name; // "" for a text without archive headers
  bool subprogram = false;
  std::vector<SinumerikBlock> blocks;
};

// The programs of `text`; the first main program first. Throws ProgramError.
std::vector<SinumerikProgramUnit> readSinumerikText(std::string_view text);

} // namespace cncc::backends::sinumerik
