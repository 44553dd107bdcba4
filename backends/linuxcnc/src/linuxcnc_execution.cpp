// Running a LinuxCNC program in LinuxCNC's own interpreter, for `verify`.
#include "linuxcnc_execution.h"

#include "cncc/backends/linuxcnc_canon.h"
#include "cncc/backends/linuxcnc_program.h"
#include "cncc/backends/rs274.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>

namespace cncc::backends {

namespace {

constexpr int kLinuxcncSeconds = 60;

// The path from LinuxCNC's canonical calls, `increment` the least increment
// of what was read.
ProgramExecution linuxcncPath(const ExecutionRequest& request, std::string_view canon,
                              double increment, std::string_view reader) {
  ProgramExecution execution;
  execution.text = request.text;
  execution.increment = increment;
  try {
    execution.path = readLinuxcncCanon(canon, controllerArcSagitta, maximumMeasuredPoints);
  } catch (const ExecutionMismatch& error) {
    return failedExecution(request.text, 0, fmt::format("{}'s output: {}", reader, error.what()));
  } catch (const PathTooLargeToMeasure& error) {
    return failedExecution(request.text, 0, error.what());
  }
  return execution;
}

// A LinuxCNC program through LinuxCNC's interpreter as a library (the
// Python module `gcode`): every coordinate as the double it computed. The
// path is read within the program's own decimals.
ProgramExecution runGcodeModuleExecution(const ExecutionRequest& request, const GcodeModuleRun& run,
                                         bool inches) {
  if (run.tooManyCalls) {
    return failedExecution(
        request.text, 0, PathTooLargeToMeasure(maximumMeasuredPoints, controllerArcSagitta).what());
  }
  if (run.exitCode < 0) {
    return failedExecution(
        request.text, 0,
        fmt::format("LinuxCNC's interpreter did not finish within {} s", kLinuxcncSeconds));
  }
  std::string_view errors = run.errors;
  errors = errors.substr(0, errors.find('\n'));
  if (run.exitCode == 1) {
    // `line N: message`, N the program's line the interpreter stopped at.
    int line = 0;
    std::string_view message = errors;
    if (errors.rfind("line ", 0) == 0) {
      std::size_t colon = errors.find(": ");
      std::from_chars(errors.data() + 5, errors.data() + std::min(colon, errors.size()), line);
      message = colon == std::string_view::npos ? errors : errors.substr(colon + 2);
    }
    ProgramExecution execution =
        failedExecution(request.text, line, fmt::format("LinuxCNC's interpreter: {}", message));
    execution.failure->lineText = line > 0 ? programLine(request.text, line) : "";
    return execution;
  }
  if (run.exitCode != 0) {
    return failedExecution(request.text, 0,
                           fmt::format("LinuxCNC's gcode module stopped (status {}): {}",
                                       run.exitCode, errors.empty() ? "no message" : errors));
  }
  return linuxcncPath(request, run.canon, std::pow(10.0, -linuxcncCoordinateDecimals(inches)),
                      "LinuxCNC's interpreter");
}

// What rs274 says on standard error, after its `executing`: the message,
// then the block it stopped at.
std::string rs274Error(std::string_view errors) {
  std::vector<std::string_view> lines;
  while (!errors.empty()) {
    std::size_t newline = errors.find('\n');
    std::string_view line = errors.substr(0, newline);
    errors = newline == std::string_view::npos ? std::string_view() : errors.substr(newline + 1);
    if (!line.empty() && line != "executing") {
      lines.push_back(line);
    }
  }
  if (lines.empty()) {
    return "it stopped with an error and no message";
  }
  return lines.size() == 1 ? std::string(lines[0])
                           : fmt::format("{}, at the block `{}`", lines[0], lines[1]);
}

// A LinuxCNC program through LinuxCNC's standalone interpreter, rs274,
// which prints 4 decimals.
ProgramExecution runRs274Execution(const ExecutionRequest& request, const std::string& toolTable) {
  std::optional<std::string> rs274 = findRs274();
  if (!rs274) {
    return failedExecution(
        request.text, 0,
        "verifying a LinuxCNC program needs LinuxCNC's interpreter rs274 on the PATH "
        "(Debian package linuxcnc-uspace)");
  }
  Rs274Run run = runRs274(*rs274, request.text, toolTable, kLinuxcncSeconds);
  if (run.exitCode != 0) {
    std::string message = run.exitCode < 0
                              ? fmt::format("rs274 did not finish within {} s", kLinuxcncSeconds)
                              : rs274Error(run.errors);
    return failedExecution(request.text, 0, "rs274: " + message);
  }
  return linuxcncPath(request, run.canon, 1e-4, "rs274");
}

// Whether a block compensates with a diameter from the tool table (`G41
// D5`, `G42 D5`; not G41.1/G42.1, which give it). The module, run with the
// tool table as here, comes out with such moves uncompensated, so these
// programs run in rs274.
bool compensatesFromToolTable(std::string_view text) {
  while (!text.empty()) {
    std::size_t newline = text.find('\n');
    std::string block;
    bool comment = false;
    for (char c : text.substr(0, newline)) {
      comment = c == '(' || (comment && c != ')');
      if (c == ';') {
        break;
      }
      if (!comment && c != ' ' && c != '\t') {
        block += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
      }
    }
    text = newline == std::string_view::npos ? std::string_view() : text.substr(newline + 1);
    for (std::size_t at = block.find("G4"); at != std::string::npos;
         at = block.find("G4", at + 2)) {
      bool compensation = at + 2 < block.size() && (block[at + 2] == '1' || block[at + 2] == '2');
      bool whole =
          at + 3 >= block.size() ||
          (block[at + 3] != '.' && !std::isdigit(static_cast<unsigned char>(block[at + 3])));
      if (compensation && whole && block.find('D') != std::string::npos) {
        return true;
      }
    }
  }
  return false;
}

} // namespace

// A LinuxCNC program through LinuxCNC's own interpreter: its Python module
// `gcode` where the Python that runs it can import it, else the program
// rs274, whose 4 decimals the output then notes. The program's parameters
// are the values it sets.
ProgramExecution runLinuxcnc(const ExecutionRequest& request) {
  // The tool table holds the diameters that `G41 D<n>` reads.
  bool inches = request.text.find("G20") != std::string::npos;
  std::string toolTable = rs274ToolTable(request.text, request.toolRadii, inches);
  if (compensatesFromToolTable(request.text)) {
    ProgramExecution execution = runRs274Execution(request, toolTable);
    execution.notes.push_back("the program compensates with the tool table's diameters (G41/G42 "
                              "D), which LinuxCNC's Python module gcode is not given: the path is "
                              "read from rs274, which prints 4 decimals");
    return execution;
  }
  GcodeModuleRun module = runGcodeModule(request.text, toolTable, inches, kLinuxcncSeconds,
                                         static_cast<std::size_t>(maximumMeasuredPoints));
  if (!module.missing) {
    return runGcodeModuleExecution(request, module, inches);
  }
  std::string_view why = module.errors;
  why = why.substr(0, why.find('\n'));
  ProgramExecution execution = runRs274Execution(request, toolTable);
  execution.notes.push_back(
      fmt::format("{} cannot import LinuxCNC's Python module gcode ({}): the path is read from "
                  "rs274, which prints 4 decimals",
                  gcodeModulePython(), why));
  return execution;
}
} // namespace cncc::backends
