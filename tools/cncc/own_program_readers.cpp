// The programs `sim` runs in a reader of their target's own (Sinumerik,
// LinuxCNC, Heidenhain TNC): each run's tool path written as CSV, a
// problem reported at the program's line. The target table names them.
#include "own_program_readers.h"

#include "cncc/backends/controller_profile.h"
#include "cncc/backends/heidenhain_controller.h"
#include "cncc/backends/linuxcnc_controller.h"
#include "cncc/backends/sinumerik_controller.h"

#include <fmt/format.h>

namespace cncc::driver {

// The virtual Sinumerik's run as a tool path: a rapid to where every axis
// is first known, then its moves (splines and arcs already in chords).
int simulateSinumerikProgram(const DriverOptions& options, const std::string& path,
                             const std::string& text) {
  backends::sinumerik::SinumerikRunOptions settings;
  settings.sampleTolerance = options.chordError;
  settings.toolRadii = options.toolRadii; // --tool-radius: by tool number
  backends::sinumerik::SinumerikRun run = backends::sinumerik::runSinumerikProgram(text, settings);
  if (run.error) {
    // The message starts "[NAME, ]line N: ", which the location says already.
    std::string message = run.error->what();
    std::size_t after = message.find(": ");
    fmt::print(stderr, "{}:{}: error: {}\n", path, run.error->line(),
               after == std::string::npos ? message : message.substr(after + 2));
    return 1;
  }
  ir::ToolPath toolPath;
  ir::MachineEvent start;
  start.x = run.start.x();
  start.y = run.start.y();
  start.z = run.start.z();
  toolPath.events.push_back(start);
  for (const backends::sinumerik::ExecutedSinumerikMove& move : run.moves) {
    ir::MachineEvent event;
    bool rapid = move.kind == backends::sinumerik::MotionKind::Rapid;
    event.kind = rapid ? ir::MachineEvent::Kind::Rapid : ir::MachineEvent::Kind::Feed;
    event.x = move.end.x();
    event.y = move.end.y();
    event.z = move.end.z();
    event.feed = rapid ? 0 : move.feed;
    toolPath.events.push_back(event);
  }
  return writeSimulatedPath(options, toolPath);
}

int simulateLinuxcncProgram(const DriverOptions& options, const std::string& path,
                            const std::string& text) {
  backends::sim::LinuxcncRunOptions settings;
  settings.toolRadii = options.toolRadii; // --tool-radius: by tool number (G41/G42 D<tool>)
  backends::sim::LinuxcncRun run = backends::sim::runLinuxcncProgram(text, settings);
  if (run.error) {
    return reportSimulationError(path, run.error->line(), run.error->what(), run.error->lineText());
  }
  return writeSimulatedPath(options,
                            backends::sim::executedToolPath(backends::sim::executedPathOf(run)));
}

// The virtual TNC's run.
int simulateTncProgram(const DriverOptions& options, const std::string& path,
                       const std::string& text) {
  backends::heidenhain::TncRunOptions settings;
  if (!options.profile.empty()) {
    const backends::TncProfile* profile = backends::findTncProfile(options.profile);
    if (profile == nullptr) {
      return simulateUsageError(
          fmt::format("--profile {}: the TNC profiles are tnc640 and itnc530", options.profile));
    }
    settings.profile = *profile;
  }
  settings.toolRadii = options.toolRadii;
  backends::heidenhain::TncRun run = backends::heidenhain::runTncProgram(text, settings);
  if (run.error) {
    return reportSimulationError(path, run.error->line, run.error->message, run.error->lineText);
  }
  return writeSimulatedPath(options, run.path);
}

} // namespace cncc::driver
