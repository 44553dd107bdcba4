// The geometry of cutter radius compensation (G41/G42) in the XY plane:
// lines and arcs offset by a signed distance (positive: to the left of the
// direction of travel, G41), and how two offset blocks are joined at a
// corner the way Fanuc's compensation C joins them (sim_compensation.cpp
// runs the blocks through it).
#pragma once

#include <optional>
#include <vector>

namespace cncc::backends::sim {

struct Vector2 {
  double x = 0, y = 0;

  friend Vector2 operator+(Vector2 a, Vector2 b) { return {a.x + b.x, a.y + b.y}; }
  friend Vector2 operator-(Vector2 a, Vector2 b) { return {a.x - b.x, a.y - b.y}; }
  friend Vector2 operator*(double s, Vector2 a) { return {s * a.x, s * a.y}; }
};

double dot(Vector2 a, Vector2 b);
double cross(Vector2 a, Vector2 b);
double length(Vector2 a);
// `a` turned 90 degrees counterclockwise.
Vector2 leftNormal(Vector2 a);

// One programmed block in the plane: a line, or an arc around `centre`
// (start == end: a full circle).
struct PlaneElement {
  bool arc = false;
  bool clockwise = false;
  Vector2 start, end, centre;

  double radius() const { return length(start - centre); }
};

// The unit direction of travel at the start and at the end.
Vector2 startTangent(const PlaneElement& element);
Vector2 endTangent(const PlaneElement& element);

// The radius of the arc `element` offset by `offset` (left positive): the
// left of a counterclockwise arc is its inside.
double offsetArcRadius(const PlaneElement& element, double offset);

// How the offset path goes round the corner at the end of `before` (where
// `after` starts): `points[0]` is where the offset `before` ends, the last
// point where the offset `after` starts, straight lines join the points in
// between. Inner corners and outer corners up to 90 degrees meet at the
// intersection of the two offset blocks; sharper outer corners go round two
// points `|offset|` beyond the corner along each block (Fanuc's type A).
// nullopt when the offset blocks do not intersect (an alarm on the control).
std::optional<std::vector<Vector2>> offsetCorner(const PlaneElement& before,
                                                 const PlaneElement& after, double offset);

// The Heidenhain TNC goes round an outside corner on an arc of radius
// `|offset|` about the programmed corner, from where the offset `before`
// ends to where the offset `after` starts (the TNC's transition arc, as
// geom::offsetOfPieces joins a convex corner). nullopt at an inner or a
// tangent corner, which meet as offsetCorner says.
struct TransitionArc {
  Vector2 start, end, centre;
  bool clockwise = false;
};
std::optional<TransitionArc> transitionArc(const PlaneElement& before, const PlaneElement& after,
                                           double offset);

// The sweep of an arc from `start` to `end` around `centre` in its direction,
// in degrees, in [0, 360).
double arcSweep(Vector2 start, Vector2 end, Vector2 centre, bool clockwise);

} // namespace cncc::backends::sim
