#include "cncc/backends/rs274.h"

#include "linuxcnc_canon_moves_script.h"

#include <fmt/format.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>

namespace cncc::backends {

namespace {

std::string readWhole(const std::filesystem::path& path) {
  std::ifstream stream(path);
  std::ostringstream text;
  text << stream.rdbuf();
  return text.str();
}

// A fresh directory of its own for one run (mkdtemp: never shared with
// another process, nor with what an earlier run left behind).
std::filesystem::path uniqueDirectory(const std::string& prefix) {
  std::string pattern = (std::filesystem::temp_directory_path() / (prefix + "-XXXXXX")).string();
  if (mkdtemp(pattern.data()) == nullptr) {
    throw std::runtime_error("cannot create a directory in " + pattern);
  }
  return pattern;
}

// The program, the tool table and the work offsets in `directory`, where
// the interpreter reads them.
struct InterpreterInput {
  std::filesystem::path program, toolTable, parameters;
};
InterpreterInput writeInput(const std::filesystem::path& directory, const std::string& program,
                            const std::string& toolTable) {
  InterpreterInput input{directory / "program.ngc", directory / "tools.tbl",
                         directory / "offsets.var"};
  std::ofstream(input.program) << program;
  std::ofstream(input.toolTable) << toolTable;
  std::ofstream(input.parameters) << rs274WorkOffsets();
  return input;
}

std::string shellQuoted(const std::string& text) {
  return "'" + text + "'";
}

// The status of `timeout -s KILL` for a program it killed: 128 + 9.
constexpr int kKilled = 137;

// `timeout -s KILL`, stopping what follows after `seconds`.
std::string timeLimit(int seconds) {
  return "timeout -s KILL " + std::to_string(seconds) + " ";
}

// `command` run by the shell, its standard output and error in files; the
// exit status, -1 when timeLimit killed it.
int runCommand(const std::string& command, const std::filesystem::path& output,
               const std::filesystem::path& errors) {
  std::string line = command + " > " + shellQuoted(output.string()) + " 2> " +
                     shellQuoted(errors.string()) + " < /dev/null";
  int status = std::system(line.c_str());
  int code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return code == kKilled ? -1 : code;
}

} // namespace

std::optional<std::string> findRs274() {
  const char* path = std::getenv("PATH");
  std::istringstream directories(path == nullptr ? "" : path);
  for (std::string directory; std::getline(directories, directory, ':');) {
    std::filesystem::path candidate = std::filesystem::path(directory) / "rs274";
    if (!directory.empty() && access(candidate.c_str(), X_OK) == 0) {
      return candidate.string();
    }
  }
  return std::nullopt;
}

std::string rs274ToolTable(std::string_view program, const std::map<int, double>& radii,
                           bool inches) {
  std::set<long> tools;
  bool comment = false;
  for (std::size_t i = 0; i < program.size(); ++i) {
    char c = program[i];
    comment = c == '(' ? true : c == ')' ? false : comment;
    // T selects a tool; H reads a tool's length from the table too.
    bool letter = c == 'T' || c == 't' || c == 'H' || c == 'h';
    bool word =
        !comment && letter && (i == 0 || !std::isalpha(static_cast<unsigned char>(program[i - 1])));
    if (word && i + 1 < program.size() &&
        std::isdigit(static_cast<unsigned char>(program[i + 1]))) {
      tools.insert(std::strtol(program.data() + i + 1, nullptr, 10));
    }
  }
  for (const auto& [tool, radius] : radii) {
    tools.insert(tool);
  }
  std::string table;
  for (long tool : tools) {
    auto radius = radii.find(static_cast<int>(tool));
    double diameter = radius == radii.end() ? 0 : 2 * radius->second / (inches ? 1 : 25.4);
    table += fmt::format("T{} P{} D{:.10g} ;\n", tool, tool, diameter);
  }
  return table;
}

std::string rs274WorkOffsets() {
  // #5220 selects G54; #5221 + 20 k .. are the X Y Z of G54 .. G59.3, in
  // the inches rs274 keeps them in.
  std::string text = "5220\t1\n";
  for (int system = 0; system < 9; ++system) {
    text += fmt::format("{}\t{}\n", 5223 + 20 * system, -rs274ReferenceHeight / 25.4);
  }
  return text;
}

Rs274Run runRs274(const std::string& rs274, const std::string& program,
                  const std::string& toolTable, int seconds) {
  std::filesystem::path directory = uniqueDirectory("cncc-rs274");
  InterpreterInput input = writeInput(directory, program, toolTable);
  std::filesystem::path output = directory / "canon.txt";
  std::filesystem::path errors = directory / "errors.txt";
  std::string lock = (std::filesystem::temp_directory_path() / "cncc-rs274.lock").string();
  std::string command = shellQuoted(rs274) + " -t " + shellQuoted(input.toolTable.string()) +
                        " -v " + shellQuoted(input.parameters.string()) + " -g " +
                        shellQuoted(input.program.string());
  Rs274Run run;
  run.exitCode =
      runCommand("flock " + shellQuoted(lock) + " " + timeLimit(seconds) + command, output, errors);
  run.canon = readWhole(output);
  run.errors = readWhole(errors);
  std::filesystem::remove_all(directory);
  return run;
}

std::string gcodeModulePython() {
  const char* chosen = std::getenv("CNCC_LINUXCNC_PYTHON");
  return chosen != nullptr && *chosen != '\0' ? chosen : "/usr/bin/python3";
}

GcodeModuleRun runGcodeModule(const std::string& program, const std::string& toolTable, bool inches,
                              int seconds, std::size_t maximumCalls) {
  GcodeModuleRun run;
  std::string python = gcodeModulePython();
  if (access(python.c_str(), X_OK) != 0) {
    run.missing = true;
    run.errors = python + " is not there";
    return run;
  }
  std::filesystem::path directory = uniqueDirectory("cncc-gcode");
  InterpreterInput input = writeInput(directory, program, toolTable);
  std::filesystem::path script = directory / "linuxcnc_canon_moves.py";
  std::ofstream(script) << linuxcncCanonMovesScript;
  std::filesystem::path output = directory / "canon.txt";
  std::filesystem::path errors = directory / "errors.txt";
  std::string command =
      shellQuoted(python) + " " + shellQuoted(script.string()) + (inches ? " --inches" : "") +
      (maximumCalls > 0 ? " --maximum-calls " + std::to_string(maximumCalls) : "") + " " +
      shellQuoted(input.program.string()) + " " + shellQuoted(input.toolTable.string()) + " " +
      shellQuoted(input.parameters.string());
  int code = runCommand(timeLimit(seconds) + command, output, errors);
  // The script's status 3: the module cannot be imported; 4: too many calls.
  run.missing = code == 3;
  run.tooManyCalls = code == 4;
  run.exitCode = code;
  run.canon = readWhole(output);
  run.errors = readWhole(errors);
  std::filesystem::remove_all(directory);
  return run;
}

} // namespace cncc::backends
