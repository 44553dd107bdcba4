// A virtual Sinumerik 840D: reads a program (G0/G1, G2/G3, BSPLINE with
// SD/PW/PL, CSPLINE and ASPLINE with their transitions, subprogram calls,
// G41/G42 tool radius compensation with G450 corners) and runs it,
// building each spline as geom's models say the controller does, and
// records the executed path with the splines sampled densely. What it does
// not know is an error naming the line, never a guess.
//
// The B spline model: a BSPLINE group's control points are the position
// before its first block followed by one point per block; with degree p
// (SD, default 3) and n programmed points the knots are clamped: p + 1
// zeros, then u_{i+1} = u_i + PL_i for the blocks i = 1..n, then p more
// copies of the last. The first p - 1 intervals lie inside the clamped
// start and must be 0 (an omitted PL is 0 there and 1 elsewhere). The
// weight of the start point is 1; PW (0..3, default 1) is the weight of the
// block's point.
#pragma once

#include "cncc/backends/executed_path.h"
#include "cncc/geom/controller_bspline.h"
#include "cncc/geom/curve.h"
#include "cncc/geom/geometry_error.h"
#include "cncc/geom/interpolating_splines.h"
#include "cncc/geom/nurbs_curve.h"

#include <Eigen/Core>

#include <cstddef>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace cncc::backends::sinumerik {

// A program the model cannot run, at `line` of program `program`.
class ProgramError : public std::runtime_error {
public:
  ProgramError(std::string program, int line, const std::string& message);
  const std::string& program() const { return program_; }
  int line() const { return line_; }

private:
  std::string program_;
  int line_;
};

// The clamped B spline of a BSPLINE group, as described above (geom's
// model, which the IR's move.spline builds too).
using geom::bsplineOfBlocks;

enum class MotionKind { Rapid, Linear, BSpline, CSpline, ASpline };

struct ExecutedSinumerikMove {
  MotionKind kind = MotionKind::Rapid;
  Eigen::Vector3d end = Eigen::Vector3d::Zero();
  double feed = 0;
  int line = 0;     // the block in its program
  int mainLine = 0; // the block of the main program (the call, inside a subprogram)
};

// One spline the program made the controller cut.
struct ExecutedSpline {
  MotionKind kind = MotionKind::BSpline;
  std::shared_ptr<const geom::Curve> curve;
  std::size_t points = 0; // programmed blocks
  int mainLine = 0;       // of its first block
};

struct SinumerikRunOptions {
  // The largest distance between a spline and the chords its samples make.
  double sampleTolerance = 1e-6;
  int cubicSplineWindow = geom::kDefaultCubicSplineWindow; // $MC_CUBIC_SPLINE_BLOCKS
  std::size_t stepLimit = 10'000'000;                      // blocks executed in all
  // Points of the sampled path in all (arcs and splines as chords): past it
  // the run stops with an error naming the limit, before sampling the arc
  // or spline that would pass it.
  std::size_t pointLimit = 4'000'000;
  // The radius of each tool's cutting edges, by tool number (`T5`, `T=5` or
  // a name ending in it, `T="T5"`): what G41/G42 offset the path by.
  std::map<int, double> toolRadii;
};

struct SinumerikRun {
  // Where the first move starts (moves before every axis is known are dropped).
  Eigen::Vector3d start = Eigen::Vector3d::Zero();
  std::vector<ExecutedSinumerikMove> moves;
  std::vector<ExecutedSpline> splines;
  std::size_t blocksExecuted = 0;
  bool inches = false;
  std::optional<ProgramError> error; // the first error; the path runs up to it
};

// Runs the main program of `text`: the text itself, or, in archive form,
// the part after `%_N_NAME_MPF`, with the `%_N_NAME_SPF` parts as its
// subprograms. Never throws for a bad program.
SinumerikRun runSinumerikProgram(std::string_view text, const SinumerikRunOptions& options = {});

// The run as an ExecutedPath, the moves given the cut of their main-program
// line (`cutOfLine[line - 1]`).
ExecutedPath executedPathOf(const SinumerikRun& run,
                            std::span<const std::optional<std::size_t>> cutOfLine);

} // namespace cncc::backends::sinumerik
