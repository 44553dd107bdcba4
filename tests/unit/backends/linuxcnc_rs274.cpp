#include "linuxcnc_rs274.h"

#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace cncc::testing {

namespace {

std::string readWhole(const std::filesystem::path& path) {
  std::ifstream stream(path);
  std::ostringstream text;
  text << stream.rdbuf();
  return text.str();
}

// A fresh directory of its own for one rs274 run (mkdtemp: never shared with
// another test process, nor with what an earlier run left behind).
std::filesystem::path uniqueDirectory() {
  std::string pattern = (std::filesystem::temp_directory_path() / "cncc-rs274-XXXXXX").string();
  if (mkdtemp(pattern.data()) == nullptr) {
    throw std::runtime_error("cannot create a directory for rs274 in " + pattern);
  }
  return pattern;
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

Rs274Run runRs274(const std::string& rs274, const std::string& program,
                  const std::string& toolTable) {
  std::filesystem::path directory = uniqueDirectory();
  std::filesystem::path input = directory / "program.ngc";
  std::ofstream(input) << program;
  std::filesystem::path tools = directory / "tools.tbl";
  std::ofstream(tools) << toolTable;
  std::filesystem::path output = directory / "canon.txt";
  std::filesystem::path errors = directory / "errors.txt";
  // One rs274 at a time across the test processes: concurrent runs were seen
  // to read each other's tool table ("tool not found").
  std::string lock = (std::filesystem::temp_directory_path() / "cncc-rs274.lock").string();
  std::string command = "flock '" + lock + "' '" + rs274 + "' -t '" + tools.string() + "' -g '" +
                        input.string() + "' > '" + output.string() + "' 2> '" + errors.string() +
                        "' < /dev/null";
  int status = std::system(command.c_str());
  Rs274Run run;
  run.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  run.canon = readWhole(output);
  run.errors = readWhole(errors);
  std::filesystem::remove_all(directory);
  return run;
}

} // namespace cncc::testing
