// The lowering's entry points.
#include "part_lowering.h"

#include "cncc/geom/geometry_error.h"
#include "cncc/ir/passes.h"

#include <fmt/format.h>

namespace cncc::ir {

using namespace frontend;

std::optional<LoweredPart> lowerPartWithCuts(const CheckedProgram& program, const PartItem& part,
                                             DiagnosticEngine& diagnostics,
                                             const LoweringOptions& options) {
  try {
    lowering::PartLowering lowering(program, part, diagnostics, options);
    LoweredPart lowered = lowering.run();
    if (options.expandCurveLaps) {
      runCurveLegalisation(lowered.function);
    }
    return lowered;
  } catch (const CurveLapError& error) {
    reportCurveLapError(error, diagnostics);
    return std::nullopt;
  } catch (const lowering::LoweringFailed&) {
    return std::nullopt;
  } catch (const geom::GeometryError& error) {
    diagnostics.report(DiagnosticKind::DegenerateCurve, part.nameSpan,
                       fmt::format("cannot lower this part: {}", error.what()));
    return std::nullopt;
  }
}

std::optional<Function> lowerPart(const CheckedProgram& program, const PartItem& part,
                                  DiagnosticEngine& diagnostics, const LoweringOptions& options) {
  std::optional<LoweredPart> lowered = lowerPartWithCuts(program, part, diagnostics, options);
  if (!lowered) {
    return std::nullopt;
  }
  return std::move(lowered->function);
}

void reportCurveLapError(const CurveLapError& error, DiagnosticEngine& diagnostics) {
  DiagnosticKind kind = DiagnosticKind::DegenerateCurve;
  switch (error.kind) {
  case CurveLapError::Kind::ProgramTooLarge:
    kind = DiagnosticKind::ProgramTooLarge;
    break;
  case CurveLapError::Kind::NonFiniteValue:
    kind = DiagnosticKind::NonFiniteValue;
    break;
  case CurveLapError::Kind::TooFewPoints:
    kind = DiagnosticKind::TooFewPoints;
    break;
  case CurveLapError::Kind::DegenerateCurve:
    break;
  }
  diagnostics.report(kind, error.span, error.what());
}

PartUnits partUnits(const PartItem& part) {
  for (const StmtPtr& statement : part.body.statements) {
    if (statement->kind == StmtKind::Units) {
      return as<UnitsStmt>(*statement).unit == "inch" ? PartUnits::Inches : PartUnits::Millimetres;
    }
  }
  return PartUnits::Millimetres;
}

} // namespace cncc::ir
