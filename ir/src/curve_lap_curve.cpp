// TEMPORARY (not committed): the helper's branch brings the real one.
#include "cncc/ir/curve_lap.h"

namespace cncc::ir {

std::shared_ptr<const geom::Curve> lapCurve(const Function& function, const Instruction& lap,
                                            const OutsideValue&) {
  const CurveTableEntry& entry = function.curves[lap.index];
  if (!entry.geometry) {
    throw CurveLapError(CurveLapError::Kind::DegenerateCurve, entry.curveSpan, "no geometry");
  }
  return entry.geometry;
}

} // namespace cncc::ir
