// Each registered target's description (registered_targets.def), defined in
// its backend folder.
#pragma once

#include "cncc/backends/target_info.h"

namespace cncc::backends {

#define CNCC_TARGET(name) extern const TargetInfo name;
#include "registered_targets.def"
#undef CNCC_TARGET

} // namespace cncc::backends
