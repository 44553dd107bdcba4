// The builtin functions of CDL: their parameters, as named arguments take
// them, and a one-line description for hovers and completion.
#include "cncc/frontend/sema.h"

#include "cncc/geom/math_functions.h"

namespace cncc::frontend {

namespace {

// The math functions, from the one table the IR computes them by too.
void addMathFunctions(std::vector<BuiltinInfo>& builtins) {
  for (const geom::MathFunctionInfo& info : geom::mathFunctions) {
    if (info.function == geom::MathFunction::Rem) { // the `%` operator
      continue;
    }
    std::string name(info.name);
    std::vector<BuiltinParameter> parameters;
    std::string signature = name + "(";
    for (int i = 0; i < info.arity; ++i) {
      parameters.push_back({std::string(info.parameters[i]), true});
      signature += (i > 0 ? ", " : "") + std::string(info.parameters[i]);
    }
    builtins.push_back(
        {name, std::move(parameters), false, signature + ")", std::string(info.description)});
  }
}

std::vector<BuiltinInfo> makeBuiltins() {
  std::vector<BuiltinInfo> builtins;
  addMathFunctions(builtins);
  std::vector<BuiltinInfo> others = {
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
  builtins.insert(builtins.end(), others.begin(), others.end());
  return builtins;
}

} // namespace

const std::vector<BuiltinInfo>& builtinFunctions() {
  static const std::vector<BuiltinInfo> builtins = makeBuiltins();
  return builtins;
}

const std::vector<std::string>& cutModifierNames() {
  static const std::vector<std::string> names = {
      "sweep", "depth", "step", "tolerance", "samples", "spacing", "method",
      "feed",  "entry", "arcs", "side",      "comp",    "lead"};
  return names;
}

} // namespace cncc::frontend
