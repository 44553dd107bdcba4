// cncc plot: the part compiled for a target (gcode by default), drawn as SVG
// with the true curves, the executed path coloured by deviation and a legend.
#include "atomic_output_file.h"
#include "commands.h"
#include "diagnostic_output.h"
#include "input_checking.h"
#include "stats_measurement.h"

#include "cncc/backends/svg_plot.h"

#include <fmt/format.h>

namespace cncc::driver {

namespace {

std::string plotTitle(const DriverOptions& options, const frontend::PartItem& part) {
  const std::string& input = options.inputs.front();
  std::size_t slash = input.find_last_of('/');
  return fmt::format("{}, part {}, target {}",
                     slash == std::string::npos ? input : input.substr(slash + 1), part.name,
                     options.target);
}

} // namespace

int runPlot(const DriverOptions& options) {
  DiagnosticOutput output(options.diagnosticsFormat, options.colour);
  frontend::SourceManager sources;
  frontend::DiagnosticEngine diagnostics(options.errorLimit);
  std::optional<frontend::CheckedProgram> program =
      checkInput(options.inputs.front(), options, true, sources, diagnostics);
  output.print(diagnostics, sources);
  if (!program || diagnostics.hasErrors() || program->selectedPart == nullptr) {
    return 1;
  }
  std::error_code error;
  std::optional<AtomicOutputFile> file = AtomicOutputFile::create(options.output, error);
  if (!file) {
    output.driverError(fmt::format("cannot write '{}': {}", options.output, error.message()));
    return 1;
  }
  frontend::DiagnosticEngine backendDiagnostics(options.errorLimit);
  std::optional<MeasuredPart> measured =
      measurePart({*program, sources, options, backendDiagnostics, *file});
  output.print(backendDiagnostics, sources);
  if (!measured || backendDiagnostics.hasErrors()) {
    return 1; // the file discards the plot
  }
  backends::PlotOptions plotOptions;
  plotOptions.title = plotTitle(options, *program->selectedPart);
  plotOptions.unit = unitName(measured->inches);
  plotOptions.cutNames = measured->cutNames;
  file->write(backends::plotSvg(measured->program.path, measured->cuts, plotOptions));
  if (!file->commit(error)) {
    output.driverError(fmt::format("cannot write '{}': {}", options.output, error.message()));
    return 1;
  }
  return 0;
}

} // namespace cncc::driver
