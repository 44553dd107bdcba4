// Each target's description, defined in its backend folder; the registry
// (target_registry.cpp) lists them in the order --help shows.
#pragma once

#include "cncc/backends/target_info.h"

namespace cncc::backends {

extern const TargetInfo m80Target;        // macro/src/macro_targets.cpp
extern const TargetInfo fanucTarget;      // macro/src/macro_targets.cpp
extern const TargetInfo sinumerikTarget;  // sinumerik/src/sinumerik_target.cpp
extern const TargetInfo gcodeTarget;      // gcode/src/gcode_target.cpp
extern const TargetInfo linuxcncTarget;   // linuxcnc/src/linuxcnc_target.cpp
extern const TargetInfo heidenhainTarget; // heidenhain/src/heidenhain_target.cpp
extern const TargetInfo jitTarget;        // jit/src/jit_target.cpp

} // namespace cncc::backends
