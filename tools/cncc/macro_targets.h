// The controller-side macro targets: `m80` and `fanuc` print the part as a
// macro program that evaluates the curve on the controller.
#pragma once

#include "targets.h"

namespace cncc::driver {

void m80Backend(const BackendRequest& request);
void fanucBackend(const BackendRequest& request);

} // namespace cncc::driver
