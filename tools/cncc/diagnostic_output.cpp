#include "diagnostic_output.h"

#include <cstdio>
#include <fmt/format.h>
#include <string>
#include <unistd.h>

namespace cncc::driver {

namespace {

bool useColour(ColourMode mode) {
  switch (mode) {
  case ColourMode::Always:
    return true;
  case ColourMode::Never:
    return false;
  case ColourMode::Auto:
    return ::isatty(STDERR_FILENO) != 0;
  }
  return false;
}

} // namespace

std::string jsonString(std::string_view text) {
  std::string out = "\"";
  for (unsigned char c : text) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += static_cast<char>(c);
    } else if (c < 0x20) {
      out += fmt::format("\\u{:04x}", c);
    } else {
      out += static_cast<char>(c);
    }
  }
  return out + "\"";
}

DiagnosticOutput::DiagnosticOutput(DiagnosticsFormat format, ColourMode colour)
    : format_(format), colour_(useColour(colour)) {}

void DiagnosticOutput::print(const frontend::DiagnosticEngine& diagnostics,
                             const frontend::SourceManager& sources) const {
  for (const frontend::Diagnostic& diagnostic : diagnostics.diagnostics()) {
    if (errorsOnly_ && diagnostic.severity != frontend::Severity::Error) {
      continue;
    }
    if (format_ == DiagnosticsFormat::Json) {
      fmt::print(stderr, "{}\n", frontend::renderJson(diagnostic, sources));
    } else {
      fmt::print(stderr, "{}", frontend::renderText(diagnostic, sources, {.colour = colour_}));
    }
  }
  std::fflush(stderr);
}

DiagnosticOutput DiagnosticOutput::errorsOnly() const {
  DiagnosticOutput output = *this;
  output.errorsOnly_ = true;
  return output;
}

void DiagnosticOutput::driverError(std::string_view message) const {
  driverMessage("error", "1;31", message);
}

void DiagnosticOutput::driverWarning(std::string_view message) const {
  if (!errorsOnly_) {
    driverMessage("warning", "1;35", message);
  }
}

void DiagnosticOutput::driverMessage(std::string_view severity, std::string_view colour,
                                     std::string_view message) const {
  if (format_ == DiagnosticsFormat::Json) {
    fmt::print(stderr,
               "{{\"severity\":\"{}\",\"name\":null,\"message\":{},\"range\":null,"
               "\"notes\":[]}}\n",
               severity, jsonString(message));
  } else if (colour_) {
    fmt::print(stderr, "\033[1mcncc:\033[0m \033[{}m{}:\033[0m \033[1m{}\033[0m\n", colour,
               severity, message);
  } else {
    fmt::print(stderr, "cncc: {}: {}\n", severity, message);
  }
}

} // namespace cncc::driver
