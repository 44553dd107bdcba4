// The `heidenhain` target: the part as a Heidenhain TNC conversational
// program whose labels and FN jumps evaluate the curve on the control, its
// parameters Q1.. set at the top.
#pragma once

#include "targets.h"

#include "cncc/backends/tnc_profile.h"

#include <vector>

namespace cncc::driver {

void heidenhainBackend(const BackendRequest& request);
ir::LoweringOptions heidenhainLoweringOptions(const frontend::PartItem& part,
                                              const DriverOptions& options);
// The TNC profile --profile names (tnc640 without one).
const backends::TncProfile& tncProfile(const DriverOptions& options);
// The Q parameter each of `count` part parameters is set in (verify edits them).
std::vector<int> heidenhainParameterQ(std::size_t count, const DriverOptions& options);

} // namespace cncc::driver
