#include "cncc/backends/tool_path_csv.h"

#include <fmt/format.h>

#include <array>
#include <optional>

namespace cncc::backends {

std::string formatCsvNumber(double value) {
  std::string text = fmt::format("{:.{}f}", value, toolPathCsvDecimals);
  std::size_t point = text.find('.');
  if (point != std::string::npos) {
    std::size_t last = text.find_last_not_of('0');
    text.erase(last == point ? point : last + 1);
  }
  // Assigning "0" here trips GCC 12's false -Wrestrict under the sanitizers.
  return text == "-0" ? std::string("0") : text;
}

std::string writeToolPathCsv(const ir::ToolPath& path, double arcSagitta) {
  if (!(ir::flattenedEventCount(path, arcSagitta) <= maximumToolPathCsvRows)) {
    throw ToolPathTooLarge(fmt::format("the tool path has more than {:.0f} moves (arcs as chords "
                                       "within {:g} mm)",
                                       maximumToolPathCsvRows, arcSagitta));
  }
  std::string out = "x,y,z,feed,rapid\n";
  std::optional<std::array<double, 3>> at; // where the last move ended
  for (const ir::MachineEvent& event : ir::flattenArcs(path, arcSagitta).events) {
    bool rapid = event.kind == ir::MachineEvent::Kind::Rapid;
    if (!rapid && event.kind != ir::MachineEvent::Kind::Feed) {
      continue;
    }
    std::array<double, 3> target{event.x, event.y, event.z};
    if (rapid && at == target) {
      continue; // a rapid to where the tool is (as the G-code printer leaves it out)
    }
    at = target;
    out += fmt::format("{},{},{},{},{}\n", formatCsvNumber(event.x), formatCsvNumber(event.y),
                       formatCsvNumber(event.z), formatCsvNumber(rapid ? 0.0 : event.feed),
                       rapid ? 1 : 0);
  }
  return out;
}

} // namespace cncc::backends
