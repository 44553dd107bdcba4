#include "linuxcnc_rs274.h"

#include <cmath>
#include <string>

namespace cncc::testing {

std::string toolTableOf(const ir::ToolPath& path) {
  std::string table;
  for (const ir::MachineEvent& event : path.events) {
    if (event.kind == ir::MachineEvent::Kind::Tool) {
      long number = std::lround(event.number);
      table += "T" + std::to_string(number) + " P" + std::to_string(number) + " D" +
               std::to_string(event.diameter) + " ;\n";
    }
  }
  return table;
}

} // namespace cncc::testing
