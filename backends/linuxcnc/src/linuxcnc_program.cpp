#include "cncc/backends/linuxcnc_program.h"

#include "linuxcnc_dialect.h"
#include "macro_printer.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <set>

namespace cncc::backends {

namespace {

// LinuxCNC's read-only predefined named parameters (LinuxCNC 2.9): a part
// parameter of one of these names would be refused at run time.
constexpr std::array predefinedNames = {
    "_x",
    "_y",
    "_z",
    "_a",
    "_b",
    "_c",
    "_u",
    "_v",
    "_w",
    "_abs_x",
    "_abs_y",
    "_abs_z",
    "_abs_a",
    "_abs_b",
    "_abs_c",
    "_abs_u",
    "_abs_v",
    "_abs_w",
    "_line",
    "_motion_mode",
    "_plane",
    "_ccomp",
    "_metric",
    "_imperial",
    "_absolute",
    "_incremental",
    "_inverse_time",
    "_units_per_minute",
    "_units_per_rev",
    "_coord_system",
    "_tool_offset",
    "_retract_r_plane",
    "_retract_old_z",
    "_spindle_rpm_mode",
    "_spindle_css_mode",
    "_ijk_absolute_mode",
    "_lathe_diameter_mode",
    "_lathe_radius_mode",
    "_spindle_on",
    "_spindle_cw",
    "_mist",
    "_flood",
    "_speed_override",
    "_feed_override",
    "_adaptive_feed",
    "_feed_hold",
    "_feed",
    "_rpm",
    "_current_tool",
    "_current_pocket",
    "_selected_tool",
    "_selected_pocket",
    "_value",
    "_value_returned",
    "_task",
    "_call_level",
    "_remap_level",
};

bool isPredefined(const std::string& name) {
  return std::find(predefinedNames.begin(), predefinedNames.end(), name) != predefinedNames.end();
}

ir::AllocationOptions allocationOptions(std::size_t parameterCount) {
  ir::AllocationOptions options;
  options.variables.push_back({linuxcncFirstGlobal, linuxcncLastGlobal});
  // Part parameters are named, not numbered: the allocator is given numbers
  // beyond the globals for them, which the printer never writes.
  for (std::size_t i = 0; i < parameterCount; ++i) {
    options.parameterVariables.push_back(linuxcncLastGlobal + 1 + static_cast<int>(i));
  }
  options.maximumBracketDepth = 12;
  // About ten characters an operation, room for the address and `#n = `.
  options.maximumInlineOperations = (linuxcncMaximumLineLength - 24) / 12;
  options.shape = linuxcncInlineShape;
  options.statementOpcodes = linuxcncStatementOpcodes();
  return options;
}

// The o<name> of a callable program: the part's name in lower case.
std::string subroutineName(const std::string& partName) {
  std::string name;
  for (char c : partName) {
    name += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  return name;
}

} // namespace

std::vector<std::string> linuxcncParameterNames(const std::vector<ir::Parameter>& parameters) {
  std::vector<std::string> names;
  std::set<std::string> taken;
  for (const ir::Parameter& parameter : parameters) {
    std::string name = "_";
    for (char c : parameter.name) {
      name += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    }
    while (isPredefined(name) || taken.contains(name)) {
      name += '_';
    }
    taken.insert(name);
    names.push_back(name);
  }
  return names;
}

double linuxcncBlendTolerance(const std::vector<ir::CutGeometry>& cuts) {
  std::optional<double> smallest;
  for (const ir::CutGeometry& cut : cuts) {
    if (!std::isnan(cut.tolerance) && cut.tolerance > 0) {
      smallest = std::min(smallest.value_or(cut.tolerance), cut.tolerance);
    }
  }
  return smallest.value_or(ir::defaultTolerance);
}

LinuxcncProgram writeLinuxcncProgram(const ir::Function& function,
                                     const LinuxcncProgramOptions& options) {
  LinuxcncProgram program;
  ir::AllocationResult allocated =
      ir::allocateVariables(function, allocationOptions(function.parameters.size()));
  for (const ir::AllocationFailure& failure : allocated.failures) {
    program.errors.push_back(failure.message);
  }
  if (!program.errors.empty()) {
    return program;
  }
  MacroDialect dialect = linuxcncDialect(linuxcncCoordinateDecimals(options.inches));
  MacroPrintOptions printOptions;
  printOptions.sourceName = options.sourceName;
  printOptions.partName = options.partName;
  printOptions.subroutineName = subroutineName(options.partName);
  printOptions.inches = options.inches;
  printOptions.callable = options.callable;
  printOptions.setup = &options.setup;
  printOptions.parameterNames = linuxcncParameterNames(function.parameters);
  MacroExpressionWriter numbers(function, allocated.allocation, dialect, {}, program.errors);
  printOptions.blend = numbers.constant(options.blendTolerance);
  PrintedMacroProgram printed =
      MacroProgramPrinter(function, allocated.allocation, dialect, printOptions, program.errors)
          .print();
  if (program.errors.empty()) {
    program.text = std::move(printed.text);
    program.lineOrigins = std::move(printed.lineOrigins);
  }
  return program;
}

} // namespace cncc::backends
