// cncc plot: the part compiled for a target (gcode by default), drawn as SVG
// with the true curves, the executed path coloured by deviation and a legend.
#include "atomic_output_file.h"
#include "commands.h"
#include "diagnostic_output.h"
#include "input_checking.h"
#include "stats_measurement.h"

#include "cncc/backends/svg_plot.h"
#include "cncc/geom/deviation.h"

#include <fmt/format.h>

#include <cstdio>
#include <optional>
#include <sys/wait.h>
#include <unistd.h>

namespace cncc::driver {

namespace {

std::string plotTitle(const DriverOptions& options, const frontend::PartItem& part) {
  return fmt::format("{}, part {}, target {}", fileName(options.inputs.front()), part.name,
                     options.target);
}

// The SVG as PNG, drawn by rsvg-convert; nullopt (and `problem` set) when
// it cannot be.
std::optional<std::string> pngOf(const std::string& svg, std::string& problem) {
  char path[] = "/tmp/cncc-plot-XXXXXX";
  int descriptor = ::mkstemp(path);
  if (descriptor < 0) {
    problem = "cannot create a temporary file for the SVG";
    return std::nullopt;
  }
  bool written = ::write(descriptor, svg.data(), svg.size()) == static_cast<ssize_t>(svg.size());
  ::close(descriptor);
  std::string png;
  int status = -1;
  if (written) {
    std::string command = fmt::format("rsvg-convert -f png {} 2>/dev/null", path);
    if (FILE* pipe = ::popen(command.c_str(), "r")) {
      char buffer[65536];
      for (std::size_t read; (read = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;) {
        png.append(buffer, read);
      }
      status = ::pclose(pipe);
    }
  }
  ::unlink(path);
  if (status != 0 || png.empty()) {
    problem = WIFEXITED(status) && WEXITSTATUS(status) == 127
                  ? "--format=png needs rsvg-convert (Debian package librsvg2-bin)"
                  : "rsvg-convert could not draw the plot as PNG";
    return std::nullopt;
  }
  return png;
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
  std::string svg;
  try {
    svg = backends::plotSvg(measured->program.path, measured->cuts, plotOptions);
  } catch (const geom::MeasurementTooLarge& error) {
    output.driverError(fmt::format("{} in one stretch of a cut: too large to plot", error.what()));
    return 1;
  }
  if (options.plotPng) {
    std::string problem;
    std::optional<std::string> png = pngOf(svg, problem);
    if (!png) {
      output.driverError(problem);
      return 1;
    }
    svg = std::move(*png);
  }
  file->write(svg);
  if (!file->commit(error)) {
    output.driverError(fmt::format("cannot write '{}': {}", options.output, error.message()));
    return 1;
  }
  return 0;
}

} // namespace cncc::driver
