#include "cncc/ir/sweep_pass.h"

#include <fmt/format.h>

#include <algorithm>
#include <limits>

namespace cncc::ir {

SweepPass passInLoop(SweepPass own, std::uint32_t number, std::uint32_t count) {
  if (own.number != 0) {
    return own;
  }
  return {number, count, own.ramp};
}

SweepPass passTrip(double trip, double trips) {
  auto whole = [](double count) {
    constexpr double largest = std::numeric_limits<std::uint32_t>::max();
    return static_cast<std::uint32_t>(std::clamp(count, 0.0, largest));
  };
  return {whole(trip), whole(trips)};
}

std::string passDepthComment(double z) {
  // Ten digits: a height the program computes (-min(k step, depth)) reads
  // as the depth written, without the last bits of its arithmetic.
  return fmt::format("pass at depth {:.10g}", z == 0 ? 0.0 : -z);
}

} // namespace cncc::ir
