// The controller-side macro targets: `m80` and `fanuc` print the part as a
// macro program that evaluates the curve on the controller.
#pragma once

#include "targets.h"

namespace cncc::driver {

void m80Backend(const BackendRequest& request);
void fanucBackend(const BackendRequest& request);
// The controller runs the curve loops, within the budget the profile's
// increment leaves; method=nurbs as G06.2 blocks.
ir::LoweringOptions m80LoweringOptions(const frontend::PartItem& part,
                                       const DriverOptions& options);
ir::LoweringOptions fanucLoweringOptions(const frontend::PartItem& part,
                                         const DriverOptions& options);

} // namespace cncc::driver
