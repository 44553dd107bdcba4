// Prints diagnostics to standard error in the format the user chose: text
// (`file:line:col: error: message [name]` with the quoted line), optionally
// coloured, or JSON with one object per line.
#pragma once

#include "driver_options.h"

#include "cncc/frontend/diagnostics.h"
#include "cncc/frontend/source_manager.h"

#include <string>
#include <string_view>

namespace cncc::driver {

// `text` as a JSON string literal, quotes included.
std::string jsonString(std::string_view text);

class DiagnosticOutput {
public:
  DiagnosticOutput(DiagnosticsFormat format, ColourMode colour);

  // Prints every diagnostic the engine holds, in its order.
  void print(const frontend::DiagnosticEngine& diagnostics,
             const frontend::SourceManager& sources) const;
  // A problem of the driver itself, with no diagnostic kind ("target 'm80'
  // has no backend in this version"): `cncc: error: message`.
  void driverError(std::string_view message) const;
  // The same for a warning (`cncc: warning: message`).
  void driverWarning(std::string_view message) const;

  // The same output printing errors only: for a second run of a phase whose
  // warnings were printed already (--stats compiles the part again).
  DiagnosticOutput errorsOnly() const;

private:
  void driverMessage(std::string_view severity, std::string_view colour,
                     std::string_view message) const;

  DiagnosticsFormat format_;
  bool colour_;
  bool errorsOnly_ = false;
};

} // namespace cncc::driver
