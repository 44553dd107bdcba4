#include "linuxcnc_rs274.h"

#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

namespace cncc::testing {

namespace {

std::string readWhole(const std::filesystem::path& path) {
  std::ifstream stream(path);
  std::ostringstream text;
  text << stream.rdbuf();
  return text.str();
}

std::string shellQuoted(const std::string& text) {
  return "'" + text + "'";
}

// Debian's Python, which the module is built for; another python3 on PATH
// (a version manager's) finds it through the script's fallback, if at all.
std::string pythonForTheModule() {
  return access("/usr/bin/python3", X_OK) == 0 ? "/usr/bin/python3" : "python3";
}

} // namespace

GcodeModuleRun runGcodeModule(const std::string& program, const std::string& toolTable, bool inches,
                              int seconds) {
  std::string pattern = (std::filesystem::temp_directory_path() / "cncc-gcode-XXXXXX").string();
  if (mkdtemp(pattern.data()) == nullptr) {
    throw std::runtime_error("cannot create a directory in " + pattern);
  }
  std::filesystem::path directory(pattern);
  std::filesystem::path input = directory / "program.ngc";
  std::ofstream(input) << program;
  std::filesystem::path tools = directory / "tools.tbl";
  std::ofstream(tools) << toolTable;
  std::filesystem::path variables = directory / "offsets.var";
  std::ofstream(variables) << backends::rs274WorkOffsets();
  std::filesystem::path output = directory / "canon.txt";
  std::filesystem::path errors = directory / "errors.txt";
  std::string script =
      std::string(CNCC_SOURCE_DIR) + "/tests/unit/backends/linuxcnc_canon_moves.py";
  std::string command = "timeout -s KILL " + std::to_string(seconds) + " " + pythonForTheModule() +
                        " " + shellQuoted(script) + (inches ? " --inches " : " ") +
                        shellQuoted(input.string()) + " " + shellQuoted(tools.string()) + " " +
                        shellQuoted(variables.string()) + " > " + shellQuoted(output.string()) +
                        " 2> " + shellQuoted(errors.string()) + " < /dev/null";
  int status = std::system(command.c_str());
  GcodeModuleRun run;
  int code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  // The script's status 3: no module; timeout's for a killed run: 128 + 9.
  run.missing = code == 3;
  run.exitCode = code == 137 ? -1 : code;
  run.canon = readWhole(output);
  run.errors = readWhole(errors);
  std::filesystem::remove_all(directory);
  return run;
}

std::string toolTableOf(const ir::ToolPath& path) {
  std::string table;
  for (const ir::MachineEvent& event : path.events) {
    if (event.kind == ir::MachineEvent::Kind::Tool) {
      long number = std::lround(event.number);
      table += "T" + std::to_string(number) + " P" + std::to_string(number) + " D" +
               std::to_string(event.diameter) + " ;\n";
    }
  }
  return table;
}

} // namespace cncc::testing
