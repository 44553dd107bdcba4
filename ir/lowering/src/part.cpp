// The lowering's entry points.
#include "part_lowering.h"

#include "cncc/geom/geometry_error.h"
#include "cncc/ir/passes.h"
#include "cncc/lowering/literal_rounding.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace cncc::ir {

using namespace frontend;

namespace {

// What rounds: a number in the program, a parameter's default, or the
// factor that turns an angle into the controller's degrees.
std::string roundedNumber(const Function& function, const Instruction& source, int digits) {
  auto reading = [&](double value) {
    return fmt::format("{} to {:.{}g}", value, controllerReading(value, digits), digits + 1);
  };
  switch (source.opcode) {
  case Opcode::Const:
    return fmt::format("round {}", reading(source.number));
  case Opcode::Param: {
    const Parameter& parameter = function.parameters[source.index];
    return fmt::format("round parameter '{}' = {}", parameter.name,
                       reading(parameter.defaultValue));
  }
  case Opcode::TableLoad:
    return "round the numbers of a table";
  default:
    return "round the factor that turns this angle into degrees";
  }
}

// The cut's tolerance, the default where samples= or spacing= chose its points.
double cutTolerance(const LoweredPart& lowered, std::uint32_t cut) {
  return cut < lowered.function.cuts.size()
             ? lowered.function.cuts[cut].budget().toleranceOrDefault()
             : defaultTolerance;
}

// Refuses a program whose rounded numbers move a cut's points, through sin,
// cos or tan, by more than a quarter of the cut's tolerance (the share
// PartLowering::spanLiteralsFit allows a NURBS span's coefficients), once
// for each statement whose number does, at its worst: true when none does.
bool trigonometricLiteralsFit(const LoweredPart& lowered, DiagnosticEngine& diagnostics,
                              const LoweringOptions& options) {
  const Function& function = lowered.function;
  int digits = options.literalSignificantDigits;
  std::vector<lowering::LiteralRoundingMove> refused;
  for (const lowering::LiteralRoundingMove& move :
       lowering::trigonometricRoundingMoves(function, digits)) {
    double tolerance = cutTolerance(lowered, move.cut);
    if (move.movement <= tolerance / 4) {
      continue;
    }
    auto same = std::find_if(refused.begin(), refused.end(), [&](const auto& other) {
      return function.instructions[other.source].span == function.instructions[move.source].span;
    });
    if (same == refused.end()) {
      refused.push_back(move);
    } else if (move.movement / tolerance > same->movement / cutTolerance(lowered, same->cut)) {
      *same = move;
    }
  }
  std::string controller = options.targetName.empty()
                               ? std::string("the controller's")
                               : fmt::format("the {} controller's", options.targetName);
  for (const lowering::LiteralRoundingMove& move : refused) {
    const Instruction& source = function.instructions[move.source];
    Diagnostic* diagnostic = diagnostics.report(
        DiagnosticKind::LiteralRounding, source.span,
        fmt::format("{} {} significant digits {}, which through sin, cos or tan moves the "
                    "points of a cut by up to {:.3g} mm, more than a quarter of its tolerance "
                    "{:g} mm",
                    controller, digits, roundedNumber(function, source, digits), move.movement,
                    cutTolerance(lowered, move.cut)));
    if (move.cut < lowered.function.cuts.size() &&
        !(lowered.function.cuts[move.cut].span == source.span)) {
      diagnostics.addNote(diagnostic, lowered.function.cuts[move.cut].span, "the cut");
    }
  }
  return refused.empty();
}

} // namespace

std::optional<LoweredPart> lowerPartWithCuts(const CheckedProgram& program, const PartItem& part,
                                             DiagnosticEngine& diagnostics,
                                             const LoweringOptions& options) {
  try {
    lowering::PartLowering lowering(program, part, diagnostics, options);
    LoweredPart lowered = lowering.run();
    if (options.expandCurveLaps &&
        !legaliseCurves(lowered.function, diagnostics, {}, options.reportSplineAsChords)) {
      return std::nullopt;
    }
    if (options.literalSignificantDigits > 0 &&
        !trigonometricLiteralsFit(lowered, diagnostics, options)) {
      return std::nullopt;
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
  case CurveLapError::Kind::InvalidTolerance:
    kind = DiagnosticKind::InvalidTolerance;
    break;
  case CurveLapError::Kind::LiteralRounding:
    kind = DiagnosticKind::LiteralRounding;
    break;
  case CurveLapError::Kind::DegenerateCurve:
    break;
  }
  diagnostics.report(kind, error.span, error.what());
}

void reportLegalisationWarnings(Function& function, DiagnosticEngine& diagnostics,
                                bool reportSplineAsChords) {
  for (const LegalisationWarning& warning : function.warnings) {
    switch (warning.kind) {
    case LegalisationWarning::Kind::SplineExactStop:
      diagnostics.report(DiagnosticKind::SplineExactStop, warning.span, warning.message);
      break;
    case LegalisationWarning::Kind::ArcsAsChords:
      diagnostics.report(DiagnosticKind::ArcsAsChords, warning.span, warning.message);
      break;
    case LegalisationWarning::Kind::ParameterFixed:
      diagnostics.report(DiagnosticKind::ParameterFixed, warning.span, warning.message);
      break;
    case LegalisationWarning::Kind::SplineAsChords:
      if (reportSplineAsChords) {
        diagnostics.report(DiagnosticKind::SplineAsChords, warning.span, warning.message);
      }
      break;
    }
  }
  function.warnings.clear();
}

bool legaliseCurves(Function& function, DiagnosticEngine& diagnostics,
                    const AfterPassCallback& afterPass, bool reportSplineAsChords) {
  try {
    runCurveLegalisation(function, afterPass);
  } catch (const CurveLapError& error) {
    reportLegalisationWarnings(function, diagnostics, reportSplineAsChords);
    reportCurveLapError(error, diagnostics);
    return false;
  }
  reportLegalisationWarnings(function, diagnostics, reportSplineAsChords);
  return true;
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
