#include "heidenhain_target.h"

#include "commands.h"

#include "cncc/backends/heidenhain_program.h"
#include "cncc/ir/interpreter.h"
#include "cncc/ir/verifier.h"
#include "cncc/lowering/lowering.h"

#include <fmt/format.h>

#include <optional>

namespace cncc::driver {

namespace {

// The host run that finds the blank takes a second or so at most (its
// events are not kept): a part whose loops (over parameters, run by the TNC)
// take more steps at the values it is compiled with gets no BLK FORM rather
// than a compile of minutes.
constexpr std::size_t maximumBlankSteps = 20'000'000;

// The blank of BLK FORM: the part run on the host with its defaults; a part
// that cannot run there gets no BLK FORM (its compile reports why elsewhere).
std::optional<backends::HeidenhainBlank> blankOf(const ir::Function& function) {
  backends::HeidenhainBlankFinder finder;
  ir::InterpreterOptions options;
  options.maximumSteps = maximumBlankSteps;
  try {
    ir::interpret(function, finder, options);
  } catch (const ir::InterpreterError&) {
    return std::nullopt;
  }
  return finder.blank();
}

} // namespace

const backends::TncProfile& tncProfile(const DriverOptions& options) {
  std::string_view name = options.profile.empty() ? "tnc640" : std::string_view(options.profile);
  const backends::TncProfile* profile = backends::findTncProfile(name);
  if (profile == nullptr) {
    throw InternalError(fmt::format("unknown TNC profile '{}'", name));
  }
  return *profile;
}

std::vector<int> heidenhainParameterQ(std::size_t count, const DriverOptions& options) {
  std::vector<std::string> errors;
  return backends::heidenhainParameterVariables(count, tncProfile(options), errors);
}

ir::LoweringOptions heidenhainLoweringOptions(const frontend::PartItem& part,
                                              const DriverOptions& options) {
  ir::LoweringOptions lowering = backends::heidenhainLoweringOptions(
      tncProfile(options), ir::partUnits(part) == ir::PartUnits::Inches);
  lowering.arcsOnEveryCut = options.arcs;
  return lowering;
}

void heidenhainBackend(const BackendRequest& request) {
  std::optional<ir::LoweredPart> lowered = lowerForTarget(request);
  if (!lowered) {
    return;
  }
  backends::GcodeOptions names = gcodeOptionsFor(request);
  backends::HeidenhainProgramOptions options;
  options.sourceName = names.sourceName;
  options.partName = names.partName;
  options.inches = names.inches;
  options.profile = tncProfile(request.options);
  options.blank = blankOf(lowered->function);
  backends::HeidenhainProgram program =
      backends::writeHeidenhainProgram(lowered->function, options);
  writeProgramIfItFits(request, "the TNC", program.errors, program.text,
                       std::move(program.lineOrigins));
}

} // namespace cncc::driver
