// What --stats and `cncc plot` measure: a target's program, the path the
// controller executes when it runs it, and the true curve of every cut.
// A target that can be measured has a hostProgram in its TargetInfo.
#pragma once

#include "targets.h"

#include "cncc/backends/executed_path.h"
#include "cncc/lowering/lowering.h"

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace cncc::driver {

struct MeasuredPart {
  backends::ExecutedProgram program;
  std::vector<ir::CutGeometry> cuts;
  // "cut 2 (s_profile.cdl:8)" for cut index 1.
  std::vector<std::string> cutNames;
  bool inches = false;
};

// Whether measurePart knows how target `name`'s programs execute.
bool canMeasure(std::string_view name);

// Compiles the request's part for its target as the backend does and runs
// the program; nullopt after a diagnostic in `request.diagnostics`. A
// program that does not execute as its tool path says is an InternalError.
std::optional<MeasuredPart> measurePart(const BackendRequest& request);

// "mm" or "in".
inline std::string unitName(bool inches) {
  return inches ? "in" : "mm";
}

} // namespace cncc::driver
