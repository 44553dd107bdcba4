// The machine a command is for: the machine file of --machine when one is
// given, else the target's built-in set-up and controller profile. Every
// printer and lowering asks these functions, never the built-in tables.
#pragma once

#include "driver_options.h"

#include "cncc/backends/controller_profile.h"
#include "cncc/backends/machine_file.h"
#include "cncc/backends/machine_setup.h"
#include "cncc/backends/tnc_profile.h"

#include <memory>
#include <optional>
#include <string>
#include <string_view>

namespace cncc::driver {

// The set-up blocks of the machine.
const backends::MachineSetup& machineSetup(const DriverOptions& options);

// The controller profile of a macro target: the machine file's, --profile's
// or `defaultProfile`.
const backends::ControllerProfile& controllerProfile(const DriverOptions& options,
                                                     std::string_view defaultProfile);

// The TNC profile --profile names (tnc640 without one).
const backends::TncProfile& tncProfile(const DriverOptions& options);

// The machine file's controller profile, if it has one (for the executors).
std::optional<backends::ControllerProfile> machineProfile(const DriverOptions& options);

// The machine file at `path`, or null after printing its diagnostics
// (`FILE:LINE:COL: error: message [code]` and the line quoted).
std::shared_ptr<const backends::MachineDescription>
loadMachineFile(const std::string& path, DiagnosticsFormat format, ColourMode colour);

} // namespace cncc::driver
