// --stats: after the program is written, the statistics of what it executes
// go to standard error, so the program itself can go to standard output.
#include "commands.h"
#include "diagnostic_output.h"
#include "stats_measurement.h"

#include "cncc/backends/path_statistics.h"
#include "cncc/geom/deviation.h"

#include <fmt/format.h>

#include <cstdio>

namespace cncc::driver {

namespace {

constexpr double kMillimetresPerInch = 25.4;

} // namespace

void collectCutDeviations(const backends::PathStatistics& statistics,
                          std::span<const ir::CutGeometry> cuts,
                          std::vector<MeasuredCutDeviation>* measured) {
  if (measured == nullptr) {
    return;
  }
  for (const backends::CutDeviation& cut : statistics.cuts) {
    if (cut.cut < cuts.size()) {
      measured->push_back({cuts[cut.cut].span, cut.maxDeviation, cut.tolerance});
    }
  }
}

int printStatistics(const BackendRequest& request, std::vector<MeasuredCutDeviation>* deviations) {
  const DriverOptions& options = request.options;
  // The compile before --stats printed the warnings.
  DiagnosticOutput output =
      DiagnosticOutput(options.diagnosticsFormat, options.colour).errorsOnly();
  frontend::DiagnosticEngine diagnostics(options.errorLimit);
  BackendRequest measuring{request.program, request.sources, options, diagnostics, request.output};
  std::optional<MeasuredPart> measured = measurePart(measuring);
  output.print(diagnostics, request.sources);
  if (!measured || diagnostics.hasErrors()) {
    return 1;
  }
  backends::StatisticsOptions statisticsOptions;
  statisticsOptions.unit = unitName(measured->inches);
  // --rapid-rate is in mm/min whatever the part's unit.
  statisticsOptions.rapidRate =
      measured->inches ? options.rapidRate / kMillimetresPerInch : options.rapidRate;
  statisticsOptions.cutNames = measured->cutNames;
  backends::PathStatistics statistics;
  try {
    statistics = backends::measureProgram(measured->program, measured->cuts, statisticsOptions);
  } catch (const geom::MeasurementTooLarge& error) {
    output.driverError(
        fmt::format("{} in one stretch of a cut: too large to measure", error.what()));
    return 1;
  }
  collectCutDeviations(statistics, measured->cuts, deviations);
  fmt::print(stderr, "statistics of part {} for target {}:\n{}", request.program.selectedPart->name,
             options.target, backends::formatStatistics(statistics, statisticsOptions));
  return 0;
}

} // namespace cncc::driver
