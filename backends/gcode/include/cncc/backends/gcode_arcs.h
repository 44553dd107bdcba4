// Arc output (arcs=true, --arcs): each planar cut is fitted once with
// tangent-continuous arcs (geom/arc_fitting.h) within its tolerance, and
// every lap of the cut at each pass is printed as G02/G03 blocks with I J
// centres at the lap's Z instead of the tool path's G01 chords. Plunges,
// ramp laps and rapids stay as the tool path has them.
#pragma once

#include "cncc/geom/arc_fitting.h"
#include "cncc/ir/lowering.h"
#include "cncc/ir/tool_path.h"

#include <Eigen/Core>

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace cncc::backends {

// The arcs each cut is printed with, indexed by the cut index of CutBegin;
// nullopt keeps the cut's chords.
using CutArcFits = std::vector<std::optional<geom::ArcFit>>;

// How far the printed arcs may stray from the fitted ones when every number
// is rounded to `decimals` decimals: the start, the end and the I J centre
// offsets each move by up to half an increment per axis. The fit is made
// within the cut's tolerance less this.
double arcRoundingAllowance(int decimals);

// A cut whose arcs are wanted (its arcs= modifier, or else `allCuts`) but
// that cannot have them, and why.
struct ArcProblem {
  std::size_t cut = 0;
  std::string reason;
};

struct CutArcFitting {
  CutArcFits fits;
  std::vector<ArcProblem> problems; // these cuts keep their chords
};

// One cut's arcs within its tolerance less arcRoundingAllowance(decimals),
// or the problem that keeps its chords (the fit is empty then).
struct OneCutArcFit {
  std::optional<geom::ArcFit> fit;
  std::string problem;
};
OneCutArcFit fitCutArc(const ir::CutGeometry& cut, int decimals);

// Fits the cuts that want arcs: those with arcs=true, and with `allCuts`
// (--arcs) those without arcs=false. A cut without a tolerance (samples=,
// spacing=) or whose curve leaves its plane keeps its chords, with a problem.
CutArcFitting fitCutArcs(std::span<const ir::CutGeometry> cuts, bool allCuts, int decimals);

// One lap of an arc cut in a tool path: events `first` to `last` are the feed
// moves along the curve at height `z`, which the arcs replace.
struct ArcLap {
  std::size_t first = 0;
  std::size_t last = 0;
  std::size_t cut = 0;
  double z = 0;
  double feed = 0;
};

// The laps of the cuts that have fits. Each pass of a cut is a plunge (or a
// ramp lap) followed by one lap of the curve at the pass depth; a lap must
// start and end where the fitted curve does. Throws std::logic_error when a
// pass of a fitted cut does not have that shape (a lowering bug).
std::vector<ArcLap> findArcLaps(const ir::ToolPath& path, const CutArcFits& fits);

// The tool path with each lap's feed moves replaced by feed moves to the
// ends of its arcs and lines: the points the printed program reaches.
ir::ToolPath arcEndPoints(const ir::ToolPath& path, const CutArcFits& fits);

// Printing one lap, for every G-code printer (gcode, linuxcnc).
struct ArcBlockFormat {
  int decimals = 4;
  std::string feedWord; // " F300." on the first block, or empty
  // The printed (rounded) position the lap starts from; I J are taken from
  // it so that the centre the controller computes is the fitted one.
  Eigen::Vector2d start = Eigen::Vector2d::Zero();
  // G01 G02 G03, or G1 G2 G3 as the macro and LinuxCNC programs write them.
  bool leadingZero = true;
};

// One block of a lap: its motion word and the rest (" X.. Y.. I.. J..").
struct ArcMotion {
  std::string motion;
  std::string words;
};

// The blocks of arcBlocks, each split after its motion word, for a printer
// that leaves out a motion word already in force.
std::vector<ArcMotion> arcMotions(std::span<const geom::ArcSegment> segments,
                                  const ArcBlockFormat& format);

// `G02 X.. Y.. I.. J..` / `G03 ...` for arcs, `G01 X.. Y..` for lines, at the
// current Z; a move that rounds to no movement is left out.
std::vector<std::string> arcBlocks(std::span<const geom::ArcSegment> segments,
                                   const ArcBlockFormat& format);

} // namespace cncc::backends
