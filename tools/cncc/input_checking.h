// Loading an input file and running the front end on it: shared by every
// command that reads a .cdl file.
#pragma once

#include "driver_options.h"

#include "cncc/frontend/diagnostics.h"
#include "cncc/frontend/sema.h"
#include "cncc/frontend/source_manager.h"

#include <optional>
#include <string>

namespace cncc::driver {

// Loads `path`; when it cannot be read, reports file-not-readable (with no
// location: `cncc: error: cannot read 'x.cdl': No such file or directory`).
std::optional<frontend::FileId> loadInput(const std::string& path, frontend::SourceManager& sources,
                                          frontend::DiagnosticEngine& diagnostics);

// Loads and checks `path` with the imports, -D values and -p part of
// `options`. `requirePart`: compiling needs one part; checking takes all.
std::optional<frontend::CheckedProgram> checkInput(const std::string& path,
                                                   const DriverOptions& options, bool requirePart,
                                                   frontend::SourceManager& sources,
                                                   frontend::DiagnosticEngine& diagnostics);

} // namespace cncc::driver
