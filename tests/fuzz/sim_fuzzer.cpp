// libFuzzer entry point for the virtual controller: the program reader and
// the executor run on arbitrary bytes, then the executed path is flattened.
//
// The contract under test: no program, however malformed, crashes the
// simulator or runs forever; every error names a line of the input (or
// none); every point of the path is finite and an arc's polyline ends at the
// arc's end point; the operations counted per point come from blocks that
// ran, and the loop feed moves are feed moves of the path. The first byte
// picks the profile and whether the program runs as a G65 call with
// arguments; with its top bit set the program is read in another dialect
// under the same contract: a Heidenhain TNC program (heidenhain_controller.h)
// when the next bit is set too, else LinuxCNC's (linuxcnc_controller.h).
#include "cncc/backends/controller_profile.h"
#include "cncc/backends/heidenhain_controller.h"
#include "cncc/backends/linuxcnc_controller.h"
#include "cncc/backends/sim_operation_count.h"
#include "cncc/backends/virtual_controller.h"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string_view>

namespace {

using namespace cncc::backends;

[[noreturn]] void fail(const char* what) {
  std::fprintf(stderr, "sim_fuzzer: invariant broken: %s\n", what);
  std::abort();
}

int lineCount(std::string_view text) {
  int lines = 1;
  for (char c : text) {
    lines += c == '\n' ? 1 : 0;
  }
  return lines;
}

void checkPath(const sim::ExecutedPath& path) {
  // Enough to flatten every arc of a small path finely, without letting a
  // long loop of huge arcs exhaust the memory.
  if (path.events.size() > 500) {
    return;
  }
  cncc::ir::ToolPath flat = sim::flattenPath(path, 0.1);
  for (const cncc::ir::MachineEvent& event : flat.events) {
    if (!std::isfinite(event.x) || !std::isfinite(event.y) || !std::isfinite(event.z)) {
      fail("a point of the flattened path is not finite");
    }
  }
  if (!path.events.empty() &&
      (path.events.back().kind == sim::ExecutedEvent::Kind::ClockwiseArc ||
       path.events.back().kind == sim::ExecutedEvent::Kind::CounterclockwiseArc)) {
    const cncc::ir::MachineEvent& last = flat.events.back();
    if (last.x != path.events.back().end.x || last.y != path.events.back().end.y) {
      fail("an arc's polyline does not end at the arc's end point");
    }
  }
}

void checkOperationCounts(std::string_view text, const ControllerProfile& profile,
                          const sim::SimulationOptions& options,
                          const sim::SimulationResult& result) {
  sim::ProgramText program = sim::readProgram(text, profile, options.reading);
  if (result.blockExecutions.size() != program.blocks.size()) {
    fail("the execution counts do not cover the program's blocks");
  }
  std::size_t executed = 0;
  for (std::size_t count : result.blockExecutions) {
    executed += count;
  }
  if (executed != result.blocksExecuted) {
    fail("the execution counts do not add up to the blocks executed");
  }
  sim::LoopOperationCounts counts = sim::countLoopOperations(program, result);
  if (counts.feedMoves > result.path.events.size()) {
    fail("more loop feed moves than moves");
  }
  if (counts.feedMoves == 0 && counts.totalPerFeedMove() != 0) {
    fail("operations per point without points");
  }
}

void runLinuxcnc(std::string_view text) {
  sim::LinuxcncRunOptions options;
  options.stepLimit = 20000;
  sim::LinuxcncRun run = sim::runLinuxcncProgram(text, options);
  if (run.error && (run.error->line() < 0 || run.error->line() > lineCount(text))) {
    fail("a LinuxCNC error names a line outside the program");
  }
  if (run.blocksExecuted > options.stepLimit + 1) {
    fail("the step limit was not enforced on a LinuxCNC program");
  }
  if (run.moves.size() <= 500) { // each arc may be up to 1000 turns
    checkPath(sim::executedPathOf(run));
  }
}

// The virtual TNC: errors name a line of the program, the step limit
// holds, every point is finite, loop feed moves are moves of the path.
void runHeidenhain(std::uint8_t selector, std::string_view text) {
  namespace hh = cncc::backends::heidenhain;
  hh::TncRunOptions options;
  const TncProfile* profile = findTncProfile(selector & 1 ? "itnc530" : "tnc640");
  if (profile == nullptr) {
    fail("a built-in TNC profile is missing");
  }
  options.profile = *profile;
  options.stepLimit = 20000;
  options.toolRadii[1] = 2; // RL/RR with tool 1 run the compensation
  hh::TncRun run = hh::runTncProgram(text, options);
  if (run.error && (run.error->line < 1 || run.error->line > lineCount(text))) {
    fail("a TNC error names a line outside the program");
  }
  if (run.blocksExecuted > options.stepLimit + 1) {
    fail("the TNC step limit was not enforced");
  }
  for (const cncc::ir::MachineEvent& event : run.path.events) {
    if (!std::isfinite(event.x) || !std::isfinite(event.y) || !std::isfinite(event.z)) {
      fail("a point of the TNC path is not finite");
    }
  }
  if (run.loopOperations.feedMoves > run.path.events.size()) {
    fail("more TNC loop feed moves than moves");
  }
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) {
    return 0;
  }
  if (data[0] & 0x80) {
    std::string_view text(reinterpret_cast<const char*>(data + 1), size - 1);
    if (data[0] & 0x40) {
      runHeidenhain(data[0], text);
    } else {
      runLinuxcnc(text);
    }
    return 0;
  }
  static const char* const profileNames[] = {"fanuc", "m80", "fanuc-0i-small"};
  const ControllerProfile* builtin = findControllerProfile(profileNames[data[0] % 3]);
  if (builtin == nullptr) {
    fail("a built-in profile is missing");
  }
  ControllerProfile reading = *builtin;
  const ControllerProfile* profile = &reading;
  sim::SimulationOptions options;
  options.stepLimit = 20000;
  if (data[0] & 0x10) {
    options.runAsMacroCall = true;
    options.arguments = {{'A', 1.5}, {'B', -2}, {'X', 10}};
  }
  if (data[0] & 0x20) {
    // A shop's program: `;`, lower-case comments, abbreviations, and the
    // settings compensation and peck drilling need.
    options.reading.strict = false;
    options.reading.family =
        data[0] & 0x40 ? sim::ControllerFamily::Mitsubishi : sim::ControllerFamily::Fanuc;
    // A machine file that says the control reads WH, SI, ... (on Fanuc).
    reading.macroWordAbbreviations = !(data[0] & 0x40);
    options.toolRadii = {{1, 2.5}, {2, -1}};
    options.peckRetract = 0.2;
    options.peckClearance = 0.5;
  }
  std::string_view text(reinterpret_cast<const char*>(data + 1), size - 1);
  sim::SimulationResult result = sim::simulateProgram(text, *profile, options);
  if (result.error && (result.error->line() < 0 || result.error->line() > lineCount(text))) {
    fail("an error names a line outside the program");
  }
  if (result.blocksExecuted > options.stepLimit + 1) {
    fail("the step limit was not enforced");
  }
  checkPath(result.path);
  if (!result.error) {
    checkOperationCounts(text, *profile, options, result);
  }
  return 0;
}
