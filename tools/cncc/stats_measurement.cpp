#include "stats_measurement.h"

#include "commands.h"

#include "cncc/backends/executed_path.h"
#include "cncc/ir/interpreter.h"
#include "cncc/ir/verifier.h"

#include <fmt/format.h>

namespace cncc::driver {

namespace {

struct HostRun {
  ir::ToolPath toolPath;
  std::vector<ir::CutGeometry> cuts;
};

// The part as the gcode and jit backends lower and run it, with its cut table.
std::optional<HostRun> runOnHost(const BackendRequest& request) {
  HostRun run;
  std::optional<ir::ToolPath> path = hostToolPath(request, false, &run.cuts);
  if (!path) {
    return std::nullopt;
  }
  run.toolPath = std::move(*path);
  return run;
}

std::vector<std::string> cutNames(const std::vector<ir::CutGeometry>& cuts,
                                  const frontend::SourceManager& sources) {
  std::vector<std::string> names;
  for (std::size_t i = 0; i < cuts.size(); ++i) {
    const frontend::SourceSpan& span = cuts[i].span;
    if (!span.valid()) {
      names.push_back(fmt::format("cut {}", i + 1));
      continue;
    }
    const frontend::SourceFile& file = sources.file(span.file);
    names.push_back(fmt::format("cut {} ({}:{})", i + 1, fileName(file.path()),
                                file.lineColumn(span.begin).line));
  }
  return names;
}

} // namespace

bool canMeasure(std::string_view name) {
  const backends::TargetInfo* target = backends::findTargetInfo(name);
  return target != nullptr && target->hostProgram != nullptr;
}

std::optional<MeasuredPart> measurePart(const BackendRequest& request) {
  const backends::TargetInfo* target = backends::findTargetInfo(request.options.target);
  if (target == nullptr || target->hostProgram == nullptr) {
    throw InternalError(fmt::format("target '{}' cannot be measured", request.options.target));
  }
  std::optional<HostRun> run = runOnHost(request);
  if (!run) {
    return std::nullopt;
  }
  // The executed path has the arcs as chords within executedArcSagitta at
  // most (the G-code reader's, finer than the CSV's): bounded before it is made.
  if (!(ir::flattenedEventCount(run->toolPath, backends::executedArcSagitta) <=
        backends::maximumMeasuredPoints)) {
    request.diagnostics.report(
        frontend::DiagnosticKind::ProgramTooLarge, request.program.selectedPart->nameSpan,
        fmt::format("the part is too large to measure: its path has more than {:.0f} points (arcs "
                    "as chords within {:g})",
                    backends::maximumMeasuredPoints, backends::executedArcSagitta));
    return std::nullopt;
  }
  MeasuredPart measured;
  try {
    measured.program =
        target->hostProgram(targetSettings(*target, request.options, *request.program.selectedPart,
                                           request.output.path()),
                            run->toolPath);
  } catch (const std::logic_error& mismatch) { // ExecutionMismatch, or arcs off the tool path
    throw InternalError(fmt::format("the {} program does not execute as its tool path: {}",
                                    target->name, mismatch.what()));
  }
  measured.cutNames = cutNames(run->cuts, request.sources);
  measured.cuts = std::move(run->cuts);
  measured.inches = ir::partUnits(*request.program.selectedPart) == ir::PartUnits::Inches;
  return measured;
}

} // namespace cncc::driver
