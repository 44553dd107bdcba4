// #4001-#4120: the modal information a macro reads to save and restore the
// state it changes (`#10 = #4003 ... G#10`), as of the preceding block. Only
// what the virtual controller tracks is answered; the rest is refused.
#include "sim_machine.h"

#include <fmt/format.h>

namespace cncc::backends::sim {

namespace {

[[noreturn]] void notCommanded(const Block& block, int variable, std::string_view what) {
  failInBlock(block, fmt::format("#{}: {} has not been commanded, and its power-on state is a "
                                 "parameter",
                                 variable, what));
}

} // namespace

std::optional<Value> Machine::modalInformation(int variable, const Block& block) const {
  switch (variable) {
  case 4001: // group 01: G00-G03
    if (!modal_.motion) {
      notCommanded(block, variable, "G00, G01, G02 or G03");
    }
    return Value::of(*modal_.motion);
  case 4002:
    return Value::of(17); // only G17 is simulated
  case 4003:
    return Value::of(modal_.absolute ? 90 : 91);
  case 4006:
    return Value::of(modal_.inches ? 20 : 21);
  case 4007:
    return Value::of(compensation_.modalCode());
  case 4008:
    return Value::of(modal_.lengthOffset ? 43 : 49);
  case 4009:
    return Value::of(modal_.cycle.code ? *modal_.cycle.code : 80);
  case 4010:
    if (!modal_.cycle.returnToInitial) {
      notCommanded(block, variable, "G98 or G99");
    }
    return Value::of(*modal_.cycle.returnToInitial ? 98 : 99);
  case 4012:
    return Value::of(modal_.modalCall ? 66 : 67);
  case 4016:
    return Value::of(modal_.coordinates.rotated ? 68 : 69);
  case 4017:
    return Value::of(modal_.coordinates.polar ? 16 : 15);
  case 4107:
    if (!modal_.radiusRegister) {
      notCommanded(block, variable, "D");
    }
    return Value::of(*modal_.radiusRegister);
  case 4109:
    if (!modal_.feed) {
      notCommanded(block, variable, "F");
    }
    return Value::of(*modal_.feed);
  case 4111:
    if (!modal_.lengthOffset) {
      notCommanded(block, variable, "G43 H");
    }
    return Value::of(*modal_.lengthOffset);
  case 4119:
    return Value::of(modal_.spindleSpeed);
  case 4120:
    if (!modal_.selectedTool) {
      notCommanded(block, variable, "T");
    }
    return Value::of(*modal_.selectedTool);
  default:
    return std::nullopt;
  }
}

} // namespace cncc::backends::sim
