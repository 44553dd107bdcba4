#include "registered_targets.h"

#include "cncc/backends/gcode_writer.h"

#include <fmt/format.h>

namespace cncc::backends {

namespace {

constexpr const TargetInfo* registeredTargets[] = {
#define CNCC_TARGET(name) &name,
#include "registered_targets.def"
#undef CNCC_TARGET
};

} // namespace

std::span<const TargetInfo* const> allTargetInfos() {
  return registeredTargets;
}

const TargetInfo* findTargetInfo(std::string_view name) {
  for (const TargetInfo* target : registeredTargets) {
    if (target->name == name) {
      return target;
    }
  }
  return nullptr;
}

std::string targetNameList(bool (*which)(const TargetInfo& target)) {
  std::string names;
  for (const TargetInfo* target : registeredTargets) {
    if (which != nullptr && !which(*target)) {
      continue;
    }
    names += names.empty() ? "" : ", ";
    names += target->name;
  }
  return names;
}

int programNumberOf(const TargetSettings& settings, int otherwise) {
  return programNumberFromFileName(settings.outputPath).value_or(otherwise);
}

std::vector<std::string> doesNotFit(std::string_view limit,
                                    const std::vector<std::string>& errors) {
  std::vector<std::string> problems;
  for (const std::string& error : errors) {
    problems.push_back(fmt::format("the part does not fit {}: {}", limit, error));
  }
  return problems;
}

} // namespace cncc::backends
