// The `sinumerik` target: the part run on the host, its cuts as Sinumerik
// spline blocks (or G1 chords), as one .MPF program.
#pragma once

#include "targets.h"

#include "cncc/backends/executed_path.h"
#include "cncc/backends/sinumerik_writer.h"
#include "cncc/lowering/lowering.h"

#include <optional>
#include <vector>

namespace cncc::driver {

struct SinumerikCompilation {
  backends::SinumerikProgram program;
  std::vector<ir::CutGeometry> cuts;
};

// The request's part compiled for Sinumerik; nullopt after a diagnostic.
std::optional<SinumerikCompilation> compileForSinumerik(const BackendRequest& request);

// The program as the virtual Sinumerik executes it. A program it cannot run
// is an InternalError (a bug in the writer, not in the input).
backends::ExecutedProgram executeSinumerik(const backends::SinumerikProgram& program);

void sinumerikBackend(const BackendRequest& request);
// The host computes the tool path; method=aspline/bspline/cspline are the
// controller's splines, so no spline-as-chords warning.
ir::LoweringOptions sinumerikLoweringOptions(const frontend::PartItem& part,
                                             const DriverOptions& options);

} // namespace cncc::driver
