// The pass of a sweep that an instruction's events belong to in a pass
// loop, and the comment that starts a pass.
#include "cncc/ir/sweep_pass.h"

#include <gtest/gtest.h>

namespace cncc::ir {
namespace {

TEST(SweepPassTest, ATripOfAPassLoopIsThePassOfWhatHasNoneOfItsOwn) {
  EXPECT_EQ(passInLoop({}, 2, 3), (SweepPass{2, 3, false}));
  // A ramp lap in the loop (number 0, ramp) is the trip's ramp.
  EXPECT_EQ(passInLoop({0, 0, true}, 2, 3), (SweepPass{2, 3, true}));
  // A written-out pass keeps its own number.
  EXPECT_EQ(passInLoop({1, 4, false}, 2, 3), (SweepPass{1, 4, false}));
}

TEST(SweepPassTest, TripsPastTheCounterAreItsLargest) {
  EXPECT_EQ(passTrip(2, 5), (SweepPass{2, 5, false}));
  constexpr std::uint32_t largest = 4'294'967'295u;
  EXPECT_EQ(passTrip(1e12, 1e13), (SweepPass{largest, largest, false}));
}

TEST(SweepPassTest, ThePassCommentSaysTheDepthWithoutTheArithmeticsLastBits) {
  EXPECT_EQ(passDepthComment(-2), "pass at depth 2");
  EXPECT_EQ(passDepthComment(-2.5), "pass at depth 2.5");
  // 3 * 0.1, and -min(k step, depth) as the controller computes it.
  EXPECT_EQ(passDepthComment(-0.30000000000000004), "pass at depth 0.3");
  EXPECT_EQ(passDepthComment(0), "pass at depth 0");
}

} // namespace
} // namespace cncc::ir
