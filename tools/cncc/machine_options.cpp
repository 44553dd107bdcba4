#include "machine_options.h"

#include "cncc/backends/target_info.h"

#include "commands.h"
#include "diagnostic_output.h"

#include <fmt/format.h>

#include <fstream>
#include <sstream>
#include <vector>

namespace cncc::driver {

namespace {

// Line `number` (1-based) of `text`, without its line break.
std::string_view lineOf(std::string_view text, int number) {
  for (int line = 1; line < number; ++line) {
    std::size_t end = text.find('\n');
    if (end == std::string_view::npos) {
      return "";
    }
    text.remove_prefix(end + 1);
  }
  std::string_view line = text.substr(0, text.find('\n'));
  return line.ends_with('\r') ? line.substr(0, line.size() - 1) : line;
}

void printText(const std::string& path, std::string_view text,
               const backends::MachineDiagnostic& diagnostic) {
  std::string message = fmt::format("{} [{}]", diagnostic.message, diagnostic.code);
  if (diagnostic.line == 0) {
    fmt::print(stderr, "cncc: error: {}\n", message);
    return;
  }
  fmt::print(stderr, "{}:{}:{}: error: {}\n", path, diagnostic.line, diagnostic.column, message);
  std::string_view line = lineOf(text, diagnostic.line);
  if (!line.empty()) {
    // Tabs stay tabs so that the caret lines up under the column.
    std::string indent;
    for (std::size_t i = 0; i + 1 < static_cast<std::size_t>(diagnostic.column) && i < line.size();
         ++i) {
      indent += line[i] == '\t' ? '\t' : ' ';
    }
    fmt::print(stderr, "  {}\n  {}^\n", line, indent);
  }
}

void printJson(const std::string& path, const backends::MachineDiagnostic& diagnostic) {
  std::string range = diagnostic.line == 0
                          ? "null"
                          : fmt::format("{{\"file\":{},\"line\":{},\"column\":{}}}",
                                        jsonString(path), diagnostic.line, diagnostic.column);
  fmt::print(stderr,
             "{{\"severity\":\"error\",\"name\":{},\"message\":{},\"range\":{},"
             "\"notes\":[]}}\n",
             jsonString(diagnostic.code), jsonString(diagnostic.message), range);
}

std::string fileText(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  std::ostringstream text;
  text << file.rdbuf();
  return text.str();
}

} // namespace

const backends::MachineSetup& machineSetup(const DriverOptions& options) {
  if (options.machine) {
    return options.machine->setup;
  }
  const backends::TargetInfo* target = backends::findTargetInfo(options.target);
  return backends::builtinMachineSetup(target != nullptr ? target->machineSetup : "");
}

const backends::ControllerProfile& controllerProfile(const DriverOptions& options,
                                                     std::string_view defaultProfile) {
  if (options.machine && options.machine->profile) {
    return *options.machine->profile;
  }
  std::string_view name =
      options.profile.empty() ? defaultProfile : std::string_view(options.profile);
  const backends::ControllerProfile* profile = backends::findControllerProfile(name);
  if (profile == nullptr) {
    throw InternalError(fmt::format("unknown controller profile '{}'", name));
  }
  return *profile;
}

const backends::TncProfile& tncProfile(const DriverOptions& options) {
  std::string_view name = options.profile.empty() ? "tnc640" : std::string_view(options.profile);
  const backends::TncProfile* profile = backends::findTncProfile(name);
  if (profile == nullptr) {
    throw InternalError(fmt::format("unknown TNC profile '{}'", name));
  }
  return *profile;
}

std::optional<backends::ControllerProfile> machineProfile(const DriverOptions& options) {
  if (options.machine) {
    return options.machine->profile;
  }
  return std::nullopt;
}

std::shared_ptr<const backends::MachineDescription>
loadMachineFile(const std::string& path, DiagnosticsFormat format, ColourMode) {
  std::vector<backends::MachineDiagnostic> diagnostics;
  std::optional<backends::MachineDescription> machine =
      backends::readMachineFile(path, diagnostics);
  if (machine) {
    return std::make_shared<const backends::MachineDescription>(std::move(*machine));
  }
  std::string text = fileText(path);
  for (const backends::MachineDiagnostic& diagnostic : diagnostics) {
    if (format == DiagnosticsFormat::Json) {
      printJson(path, diagnostic);
    } else {
      printText(path, text, diagnostic);
    }
  }
  return nullptr;
}

} // namespace cncc::driver
