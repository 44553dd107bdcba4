// The builtin functions of CDL: their parameters, as named arguments take
// them, and a one-line description for hovers and completion.
#include "cncc/frontend/sema.h"

namespace cncc::frontend {

namespace {

BuiltinInfo math1(std::string name, std::string description) {
  return {name, {{"x", true}}, false, name + "(x)", std::move(description)};
}

BuiltinInfo math2(std::string name, std::string first, std::string second,
                  std::string description) {
  return {name,
          {{first, true}, {second, true}},
          false,
          name + "(" + first + ", " + second + ")",
          std::move(description)};
}

std::vector<BuiltinInfo> makeBuiltins() {
  std::vector<BuiltinInfo> builtins = {
      math1("sin", "sine of an angle in radians"),
      math1("cos", "cosine of an angle in radians"),
      math1("tan", "tangent of an angle in radians"),
      math1("asin", "arc sine, in radians"),
      math1("acos", "arc cosine, in radians"),
      math1("atan", "arc tangent, in radians"),
      math2("atan2", "y", "x", "angle of the point (x, y), in radians, -pi .. pi"),
      math1("sqrt", "square root"),
      math1("abs", "absolute value"),
      math2("min", "a", "b", "the smaller of two numbers"),
      math2("max", "a", "b", "the larger of two numbers"),
      math2("pow", "base", "exponent", "base raised to exponent (also written base ^ exponent)"),
      math1("exp", "e raised to x"),
      math1("ln", "natural logarithm"),
      math1("floor", "largest whole number not above x"),
      math1("ceil", "smallest whole number not below x"),
      math1("round", "nearest whole number, halves away from zero"),
      {"len", {{"list", true}}, false, "len(list)", "number of elements of a list"},
      {"nurbs",
       {{"order", false},
        {"degree", false},
        {"points", true},
        {"weights", false},
        {"knots", false}},
       false,
       "nurbs(order=k | degree=p, points=L, weights=W?, knots=K?)",
       "rational B-spline; knots omitted = clamped uniform"},
      {"bspline",
       {{"order", false}, {"degree", false}, {"points", true}, {"knots", false}},
       false,
       "bspline(order=k | degree=p, points=L, knots=K?)",
       "B-spline (a nurbs with unit weights)"},
      {"bezier",
       {{"points", true}},
       false,
       "bezier(points=L)",
       "one Bezier segment of degree len(L)-1"},
      {"polar",
       {{"r", true}, {"t", true}},
       false,
       "polar(r = expr in t, t = a .. b)",
       "curve given by its radius r(t) at polar angle t"},
      {"param",
       {{"x", true}, {"y", true}, {"z", false}, {"t", true}},
       false,
       "param(x = ..., y = ..., z = ...?, t = a .. b)",
       "parametric curve (x(t), y(t), z(t))"},
      {"line", {{"from", true}, {"to", true}}, false, "line(from, to)", "straight segment"},
      {"arc",
       {{"center", true}, {"radius", true}, {"from", true}, {"to", true}, {"z", false}},
       false,
       "arc(center=, radius=, from=, to=, z=?)",
       "circular arc, angles in radians, counter-clockwise when to > from; with z = z0 .. z1 a "
       "helix whose height goes linearly with the angle"},
      {"path", {}, true, "path(c1, c2, ...)", "curves joined end to start"},
      {"translate",
       {{"curve", true}, {"dx", true}, {"dy", true}},
       false,
       "translate(curve, dx, dy)",
       "the curve moved by (dx, dy)"},
      {"rotate",
       {{"curve", true}, {"angle", true}},
       false,
       "rotate(curve, angle)",
       "the curve rotated about the origin by angle (radians, counter-clockwise)"},
      {"scale",
       {{"curve", true}, {"factor", true}},
       false,
       "scale(curve, factor)",
       "the curve scaled about the origin"},
  };
  return builtins;
}

} // namespace

const std::vector<BuiltinInfo>& builtinFunctions() {
  static const std::vector<BuiltinInfo> builtins = makeBuiltins();
  return builtins;
}

const std::vector<std::string>& cutModifierNames() {
  static const std::vector<std::string> names = {"sweep",   "depth",   "step",   "tolerance",
                                                 "samples", "spacing", "method", "feed",
                                                 "entry",   "arcs"};
  return names;
}

} // namespace cncc::frontend
