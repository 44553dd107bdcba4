// The `jit` target: the part run on the host (natively by the LLVM JIT
// when it is built) and its tool path printed as CSV rows x,y,z,feed,rapid.
#include "registered_targets.h"

#include "cncc/backends/tool_path_csv.h"

#include <fmt/format.h>

#include <array>
#include <charconv>
#include <cmath>

namespace cncc::backends {

namespace {

// The CSV has 6 decimals: the chords leave that rounding room inside the
// tolerance.
ir::LoweringOptions jitLowering(const TargetSettings&) {
  ir::LoweringOptions options;
  options.coordinateIncrement = std::pow(10.0, -toolPathCsvDecimals);
  options.fittedArcs = false; // arcs=true: the path is points either way
  options.keepLoops = true;   // written out by unroll-host-control
  return options;
}

PrintedProgram printToolPathCsv(const PrintInput& input) {
  PrintedProgram printed;
  try {
    printed.text = writeToolPathCsv(*input.hostPath);
  } catch (const ToolPathTooLarge& tooLarge) {
    printed.problems.push_back(fmt::format("the part is too large to print: {}", tooLarge.what()));
  }
  return printed;
}

// The program is the tool path as CSV; a block is a row, and what runs is
// its rows (arcs in the CSV's chords). Throws ToolPathTooLarge.
ExecutedProgram jitProgram(const TargetSettings&, const ir::ToolPath& path) {
  std::string text = writeToolPathCsv(path);
  std::size_t rows = countProgramBlocks(text) - 1; // without the header
  return {std::move(text), rows, executedPathOfToolPath(path, toolPathCsvArcSagitta)};
}

std::optional<double> csvNumber(std::string_view text) {
  double value = 0;
  auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || error != std::errc() || end != text.data() + text.size()) {
    return std::nullopt;
  }
  return value;
}

// One `x,y,z,feed,rapid` row; nullopt when it is not one.
std::optional<ir::MachineEvent> csvMove(std::string_view row) {
  std::array<double, 5> fields{};
  for (std::size_t i = 0; i < fields.size(); ++i) {
    std::size_t comma = row.find(',');
    if ((comma == std::string_view::npos) != (i + 1 == fields.size())) {
      return std::nullopt;
    }
    std::optional<double> value = csvNumber(row.substr(0, comma));
    if (!value) {
      return std::nullopt;
    }
    fields[i] = *value;
    row = comma == std::string_view::npos ? "" : row.substr(comma + 1);
  }
  ir::MachineEvent event;
  event.kind = fields[4] != 0 ? ir::MachineEvent::Kind::Rapid : ir::MachineEvent::Kind::Feed;
  event.x = fields[0];
  event.y = fields[1];
  event.z = fields[2];
  event.feed = fields[3];
  return event;
}

// The jit target's program is its tool path as CSV: read back, it is the path.
ProgramExecution runJit(const ExecutionRequest& request) {
  ProgramExecution execution;
  execution.text = request.text;
  execution.increment = 1e-6; // the CSV's 6 decimals
  ir::ToolPath toolPath;
  std::string_view text = request.text;
  int line = 0;
  while (!text.empty()) {
    std::size_t newline = text.find('\n');
    std::string_view row = text.substr(0, newline);
    text = newline == std::string_view::npos ? "" : text.substr(newline + 1);
    if (++line == 1 || row.empty()) {
      continue; // the header
    }
    std::optional<ir::MachineEvent> event = csvMove(row);
    if (!event) {
      return failedExecution(request.text, line, "not a row x,y,z,feed,rapid");
    }
    toolPath.events.push_back(*event);
  }
  execution.path = executedPathOfToolPath(toolPath);
  return execution;
}

} // namespace

const TargetInfo jitTarget = {
    .name = "jit",
    .description = "run the part on the host and print the tool path",
    .lowering = jitLowering,
    .print = printToolPathCsv,
    .hostRun = HostRun::Native,
    .fittedArcs = false,
    .machineSetup = "gcode",
    .hostProgram = jitProgram,
    .execute = runJit,
};

} // namespace cncc::backends
