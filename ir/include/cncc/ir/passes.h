// The IR optimiser: passes that rewrite a Function into an equivalent,
// usually smaller one. Every pass keeps the tool path the interpreter
// computes bit for bit: folding uses the interpreter's arithmetic, an
// algebraic identity is used only when it holds for every input (NaN, the
// infinities and signed zeros included), and effect operations (moves,
// spindle, tool, comment, cut.begin) are never removed, duplicated out of
// their loop or reordered. Parameters stay parameters: nothing is folded
// through `param`, so a controller program keeps them editable.
//
// The exceptions are `fold-finite`, a target's pass rather than the
// optimiser's: it takes every value to be finite, as a controller that
// alarms on a non-finite value has them, `expand-whole-powers`, whose
// products round otherwise than pow, and `drop-pass-depths`, which drops
// the comments a controller's pass loop cannot print (Pass::exact is false
// for them).
//
// Each pass returns whether it changed the function; its output verifies.
#pragma once

#include "cncc/ir/ir.h"

#include <cstddef>
#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace cncc::ir {

// `fold`: constant folding and algebraic simplification; an `if` on a
// constant becomes its taken region, a loop that runs zero times goes.
bool foldConstants(Function& function);
// `cse`: a pure operation equal to one that is visible at its place (same
// region or an enclosing one) is replaced by it.
bool eliminateCommonSubexpressions(Function& function);
// `licm`: pure operations in a loop's body whose operands come from outside
// the loop move before the loop. table.load (it can fail) and operations in
// an `if` inside the loop stay where they are.
bool hoistLoopInvariants(Function& function);

struct UnrollOptions {
  std::size_t maximumTripCount = 8;
  // Instructions in the body, nested regions included.
  std::size_t maximumBodySize = 64;
  // Keep an unrolled loop only when fold, cse and dce then leave the
  // function no larger than they leave it with the loop.
  bool onlyWhenNoLarger = false;
  // A trial costs a cleaned-up copy of the whole function: the instructions
  // the trials of one run may copy in all (a part of thousands of cuts has
  // thousands of pass loops). Past it the loops are tried in groups.
  std::size_t maximumTrialInstructions = 1'000'000;
};
// `unroll` (options as given) and `unroll-no-larger` (onlyWhenNoLarger):
// a loop with constant bounds that runs at most maximumTripCount times is
// replaced by copies of its body, the induction variable a constant in each.
bool unrollLoops(Function& function, const UnrollOptions& options = {});
// `dce`: pure operations whose results are unused go; so do ifs and loops
// without effects (a loop only when its bounds are known finite, since the
// interpreter rejects others).
bool eliminateDeadCode(Function& function);
// `fold-finite`: constant folding and x + 0, x - 0, x * 1, x / 1 -> x,
// x * 0 -> 0, as they are on finite numbers (numbers within 1e-12 of 0 or
// 1 taken as them). Only for the targets whose controller alarms where a
// value is not finite, so has no NaN, infinity or -0 for these to change:
// the macro programs (fold_finite.cpp). A non-finite result stays an
// operation, for the controller to alarm on.
bool foldAssumingFinite(Function& function);

// `expand-whole-powers`: a ^ n with a whole constant n, |n| <= 64, as
// multiplications (1 / the product for n < 0, 1 for n = 0): defined for
// every a, where a controller's EXP[LN[a]*n] alarms for a <= 0; and
// a ^ (n + 1/2) as the product times sqrt(a), defined from a = 0 on. For
// the macro programs, before fold-finite (whole_powers.cpp); not exact (the
// product rounds otherwise than pow).
bool expandWholePowers(Function& function);
// The largest |n| expand-whole-powers writes out (a ^ 64 takes six
// multiplications); a larger power keeps the controller's own.
constexpr double largestExpandedExponent = 64;

// `drop-pass-depths`: each pass.begin removed, for the targets that print
// the IR as it stands (a controller's pass loop says no depth).
bool dropPassDepths(Function& function);

struct Pass {
  std::string_view name;
  std::string_view description;
  bool (*run)(Function& function);
  // Keeps the interpreter's tool path bit for bit for every input (above);
  // false for fold-finite and expand-whole-powers, and for drop-pass-depths
  // (a pass loop's comments go).
  bool exact = true;
};

// Every pass by its stable name: the legalisations (curve_lap.h), the
// optimiser's passes in the order above, then fold-finite.
std::span<const Pass> allPasses();
const Pass* findPass(std::string_view name);

// fold, cse, licm, unroll-no-larger, fold, cse, dce.
std::span<const std::string_view> defaultPipeline();

// Called after each pass with its name and the function it left.
using AfterPassCallback = std::function<void(std::string_view name, const Function& function)>;

// Runs the named passes once, in order; false (and nothing run) when a
// name is unknown, with `unknown` set to it.
bool runPasses(Function& function, std::span<const std::string> names,
               const AfterPassCallback& afterPass, std::string* unknown = nullptr);

// Runs the default pipeline until a round changes nothing (at most
// `maximumRounds` rounds).
void runDefaultPipeline(Function& function, const AfterPassCallback& afterPass = {},
                        int maximumRounds = 4);

// The legalisation of curve.laps for a target: choose-controller-steps,
// split-arc-laps, bound-controller-steps, write-curve-blocks, fit-arcs,
// expand-controller-loops, then expand-curve-laps (curve_lap.h). Throws
// CurveLapError.
void runCurveLegalisation(Function& function, const AfterPassCallback& afterPass = {});

// The number of instructions placed in the function's regions.
std::size_t instructionCount(const Function& function);

} // namespace cncc::ir
