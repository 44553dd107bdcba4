#include "cncc/backends/rs274.h"

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
std::filesystem::path uniqueDirectory() {
  std::string pattern = (std::filesystem::temp_directory_path() / "cncc-rs274-XXXXXX").string();
  if (mkdtemp(pattern.data()) == nullptr) {
    throw std::runtime_error("cannot create a directory for rs274 in " + pattern);
  }
  return pattern;
}

std::string shellQuoted(const std::string& text) {
  return "'" + text + "'";
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
  std::filesystem::path directory = uniqueDirectory();
  std::filesystem::path input = directory / "program.ngc";
  std::ofstream(input) << program;
  std::filesystem::path tools = directory / "tools.tbl";
  std::ofstream(tools) << toolTable;
  std::filesystem::path variables = directory / "offsets.var";
  std::ofstream(variables) << rs274WorkOffsets();
  std::filesystem::path output = directory / "canon.txt";
  std::filesystem::path errors = directory / "errors.txt";
  std::string lock = (std::filesystem::temp_directory_path() / "cncc-rs274.lock").string();
  std::string command =
      "flock " + shellQuoted(lock) + " timeout -s KILL " + std::to_string(seconds) + " " +
      shellQuoted(rs274) + " -t " + shellQuoted(tools.string()) + " -v " +
      shellQuoted(variables.string()) + " -g " + shellQuoted(input.string()) + " > " +
      shellQuoted(output.string()) + " 2> " + shellQuoted(errors.string()) + " < /dev/null";
  int status = std::system(command.c_str());
  Rs274Run run;
  // timeout's status for a killed program is 128 + 9.
  int code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  run.exitCode = code == 137 ? -1 : code;
  run.canon = readWhole(output);
  run.errors = readWhole(errors);
  std::filesystem::remove_all(directory);
  return run;
}

} // namespace cncc::backends
