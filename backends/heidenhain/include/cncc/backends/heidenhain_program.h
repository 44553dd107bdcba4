// Heidenhain TNC conversational (Klartext) programs that evaluate the part
// on the control: IR values become Q parameters (ir::allocateVariables
// onto the profile's QL/Q ranges) or formulas, loops and ifs become labels
// and FN 9..12 jumps, the part parameters Q1.. set by `FN 0` at the top,
// where the operator edits them.
//
// Layout: `0 BEGIN PGM NAME MM`, comments naming the source, the part and
// the parameter of each part parameter with its default, `BLK FORM` from
// the part's extent, the parameters, `TOOL CALL n Z S..`, the moves (`L`,
// `CC` + `C DR+/DR-`, helices with `IZ`), `n END PGM NAME MM`; every block
// numbered from 0. A loop is
//
//   QL3 = +1                         ; the index
//   LBL 1
//   FN 11: IF +QL3 GT +QL2 GOTO LBL 2
//   ...                              ; the body
//   QL3 = QL3 + 1
//   FN 9: IF +0 EQU +0 GOTO LBL 1
//   LBL 2
//
// A program the control cannot take (more part parameters than the
// profile's range, more values than its Q ranges, labels or blocks over
// its limits, a number beyond its format) is refused with the limit named.
#pragma once

#include "cncc/backends/line_spans.h"
#include "cncc/backends/tnc_profile.h"
#include "cncc/frontend/source_manager.h"
#include "cncc/ir/ir.h"
#include "cncc/ir/lowering_options.h"
#include "cncc/ir/machine_event_sink.h"
#include "cncc/ir/tool_path.h"

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace cncc::backends {

// The blank of `BLK FORM`: its least and greatest corner.
struct HeidenhainBlank {
  double minX = 0, minY = 0, minZ = 0;
  double maxX = 0, maxY = 0, maxZ = 0;
};

struct HeidenhainProgramOptions {
  std::string sourceName; // for the header comment, e.g. "s_profile.cdl"
  std::string partName;   // the program's name too
  bool inches = false;
  TncProfile profile = *findTncProfile("tnc640");
  std::optional<HeidenhainBlank> blank; // no BLK FORM without one
};

struct HeidenhainProgram {
  std::string text;                // empty when errors is not
  std::vector<std::string> errors; // each names the limit and the count
  // Where each line of `text` was printed from (an invalid span: the header).
  LineOrigins lineOrigins;
};

// The Q parameter of each part parameter: Q1, Q2, ... in order. More
// parameters than the profile's range is reported in `errors`.
std::vector<int> heidenhainParameterVariables(std::size_t parameterCount, const TncProfile& profile,
                                              std::vector<std::string>& errors);

// How to lower a part for the TNC: loops on the control, the input
// resolution counted in each cut's tolerance, native and fitted arcs.
ir::LoweringOptions heidenhainLoweringOptions(const TncProfile& profile, bool inches);

// The blank around the feed moves of a run of the part (arcs included),
// its top at Z 0 or the highest feed move; nullopt without feed moves.
std::optional<HeidenhainBlank> heidenhainBlank(const ir::ToolPath& path);

// The same, from the run's events one at a time (ir::interpret with a sink).
class HeidenhainBlankFinder : public ir::MachineEventSink {
public:
  void event(const ir::MachineEvent& event) override;
  std::optional<HeidenhainBlank> blank() const;

private:
  std::optional<HeidenhainBlank> blank_;
  std::array<double, 3> position_{0, 0, 0};
  std::vector<ir::MachineEvent> chords_;
};

HeidenhainProgram writeHeidenhainProgram(const ir::Function& function,
                                         const HeidenhainProgramOptions& options);

} // namespace cncc::backends
