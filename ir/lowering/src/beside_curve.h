// What a cut beside its curve (side=) is planned with: the lead arcs of
// comp=controller and lead=, why an offset cannot be built, how a path's
// offset pieces join, how the laps of an offset the host computes are cut,
// and the offset the controller computes (offset_cuts.cpp, offset_laps.cpp,
// compensated_cuts.cpp, controller_offset_cuts.cpp,
// controller_offset_laps.cpp).
#pragma once

#include "lowering_values.h"

#include "cncc/geom/arc_fitting.h"
#include "cncc/geom/deviation.h"
#include "cncc/geom/evaluation_budget.h"
#include "cncc/geom/offset_curve.h"
#include "cncc/ir/cut_geometry.h"

#include <Eigen/Core>

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace cncc::ir::lowering {

// The moves around a comp=controller cut's curve (compensated_cuts.cpp),
// as programmed: the start-up line from `startUp` to the lead-in arc's
// start, the lead-in arc onto the curve, the lead-out arc off it, the cancel
// line to `cancel`. The arcs' radius is the lead's plus the tool's, so the
// tool's centre runs on an arc of the lead's radius. A comp=host cut's leads
// (offset_cuts.cpp) are the tool centre's own arcs, of the lead's radius,
// and have no start-up or cancel line.
struct CompensatedLeads {
  Eigen::Vector3d startUp = Eigen::Vector3d::Zero();
  geom::ArcSegment leadIn;
  geom::ArcSegment leadOut;
  // A straight run along the curve's end tangent before the lead-out
  // (compensated_cuts.cpp, withRunOut), which then starts at its end.
  bool runOut = false;
  Eigen::Vector3d cancel = Eigen::Vector3d::Zero();
  double offset = 0; // the tool's, left of the direction of travel positive
  std::uint32_t offsetRegister = 0;
};

// Why the tool cannot run beside a curve at a distance (offset_cuts.cpp):
// a concave bend or an arc tighter than its radius, offsets that do not
// cross at a concave corner, an offset crossing itself, or a curve with no
// offset at all.
// A tool centre nearer than the tool's radius to the curve (TooNear: an
// open end run into another piece), or a check past its limit (TooMuchWork).
struct OffsetTrouble {
  enum Kind { Bend, InsideArc, Corner, SelfCrossing, TooNear, Degenerate, TooMuchWork } kind = Bend;
  Eigen::Vector3d place = Eigen::Vector3d::Zero();
  double radius = 0; // the radius found there (Bend, InsideArc); the distance (TooNear)
  std::string message;
  std::size_t limit = 0; // TooMuchWork
};

// How the offsets of two pieces of a path join where the pieces meet, as
// geom::offsetOfPieces joins them: directly (the pieces meet tangentially),
// by an arc of the tool's radius about a convex corner, or cut back to
// their crossing at a concave one.
struct PieceJoin {
  enum Kind { Direct, CornerArc, Crossing } kind = Direct;
  Eigen::Vector3d corner = Eigen::Vector3d::Zero();
  // The left unit normals of the piece ending and the piece starting there.
  Eigen::Vector2d before = Eigen::Vector2d::Zero();
  Eigen::Vector2d after = Eigen::Vector2d::Zero();
  double turn = 0; // from the one tangent to the other, counter-clockwise positive
};

// How the offsets of `before` and `after` join (as geom::offsetOfPieces).
PieceJoin pieceJoin(const geom::Curve& before, const geom::Curve& after, double distance);
// The joins of a path's pieces: joins[p] from piece p's end to piece p + 1's
// start, and for a closed path (`closed` set) the last from its end to its
// start.
std::vector<PieceJoin> pieceJoins(const std::vector<std::shared_ptr<const geom::Curve>>& pieces,
                                  double distance, bool& closed);

// A cut beside its curve whose offset the controller computes
// (controller_offset_cuts.cpp): its tool radius a parameter the controller
// knows only when it runs, or a number.
struct RuntimeOffset {
  Scalar distance; // left of the direction of travel positive
  Scalar radius;   // |distance|
  double compiledDistance = 0;
  std::shared_ptr<const geom::Curve> compiled; // the offset at compiledDistance
  // The largest radius the tool fits the curve with (infinite: any).
  double largestRadius = 0;
  std::vector<std::shared_ptr<const geom::Curve>> pieces; // the drawn pieces, moved
  // joins[p]: piece p's end to piece p + 1's start; for a closed path the
  // last is its end to its start.
  std::vector<PieceJoin> joins;
  bool closed = false;
  // A number's radius: the part of the compiled offset beside each drawn
  // piece (null for none), whose range (in the piece's own parameter, cut
  // back at concave corners) and ends the laps keep.
  std::vector<const geom::Curve*> keptParts;
};

// G39 after chord `after` (0-based), towards the next move's direction.
struct ChordCorner {
  std::size_t after = 0;
  Eigen::Vector3d nextTangent = Eigen::Vector3d::Zero();
};

// How a host offset's laps are cut: its own arcs, or level laps asking for
// fitted arcs (their table), else its points (their lap's table).
struct HostOffsetLaps {
  std::optional<std::vector<geom::ArcSegment>> arcs;
  CutArcs arcMoves = CutArcs::None;
  std::optional<std::uint32_t> arcsTable;
  std::optional<std::uint32_t> pointsTable;
  // The laps' tables ask for the target's curve blocks (choose-curve-blocks).
  bool blocksAsked = false;
};

// Whether a curve is a line or an arc (geom's LineCurve, ArcCurve).
bool isLineCurve(const geom::Curve& curve);
bool isArcCurve(const geom::Curve& curve);

// The cut's pieces in part coordinates, lines and arcs kept as such.
std::vector<std::shared_ptr<const geom::Curve>> movedPieces(const CutCurve& curve);
// The pieces as one curve: the piece itself, or a path of them joined as
// the cut's curve joins them (pathJoinTolerance).
std::shared_ptr<const geom::Curve>
joinedPieces(const std::vector<std::shared_ptr<const geom::Curve>>& pieces);
// A curve of lines and arcs as line and arc moves; nullopt for other curves.
std::optional<std::vector<geom::ArcSegment>> exactSegments(const geom::Curve& curve);
// The drawn curve a tool runs beside, sampled once for the clearance
// checks of its offsets (offsetOrTrouble) within a quarter of `slack`, the
// depth the tool may cut past it unreported (the cut's tolerance). Its
// sampling asks at most maximumCurveEvaluations points (then throws
// geom::EvaluationBudgetExceeded).
struct DrawnClearance {
  DrawnClearance(const std::vector<std::shared_ptr<const geom::Curve>>& pieces, double slack);
  std::shared_ptr<const geom::Curve> drawn;
  std::unique_ptr<geom::BudgetedCurve> budgeted;
  std::unique_ptr<geom::CurveProximity> proximity;
  double slack = 0;
};

// The offset of the pieces at `distance` and where each of its parts comes
// from (geom::offsetOfPiecesWithOrigins), or why the tool cannot run there
// (offset_cuts.cpp); with `drawn`, also where the tool centre comes nearer
// than its radius to the curve.
std::variant<geom::PiecesOffset, OffsetTrouble>
offsetOrTrouble(const std::vector<std::shared_ptr<const geom::Curve>>& pieces, double distance,
                const DrawnClearance* drawn = nullptr);
// Tangent lead arcs of `radius` onto the start of `path` and off its end
// (both on the printed grid), their centres on the side of `offset` (> 0:
// left): the start-up and cancel lines run that radius further along the
// normal (compensated_cuts.cpp).
CompensatedLeads tangentLeads(const geom::Curve& path, double offset, double radius,
                              double increment);

} // namespace cncc::ir::lowering
