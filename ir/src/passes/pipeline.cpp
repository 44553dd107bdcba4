// The pass registry and the default pipeline.
#include "cncc/ir/passes.h"

#include "cncc/ir/curve_lap.h"

#include "rewriter.h"

namespace cncc::ir {

namespace {

bool unrollWithDefaults(Function& function) {
  return unrollLoops(function);
}

bool unrollWhenNoLarger(Function& function) {
  UnrollOptions options;
  options.onlyWhenNoLarger = true;
  return unrollLoops(function, options);
}

constexpr Pass passTable[] = {
    {"unroll-host-control",
     "legalisation: on a target that computes on the host, each for loop written out trip by "
     "trip at its bounds' compiled values, each trip's cut its own, and each if that cuts as its "
     "branch taken there",
     unrollHostControl},
    {"choose-curve-blocks",
     "legalisation: each curve.lap of constants whose cut's method= asks for curve blocks cut as "
     "the NURBS, SPL or spline blocks its target prints, where they can follow it",
     chooseCurveBlocks},
    {"choose-controller-steps",
     "legalisation: on a target whose controller computes, each curve.lap within a chord "
     "tolerance along a curve of constants cut in uniform steps the controller counts",
     chooseControllerSteps},
    {"split-arc-laps",
     "legalisation: on a target that computes on the host, each curve.lap cut in steps with arcs "
     "as a lap per piece: the arcs' blocks at the compiled values, chords for the other pieces",
     splitArcLaps},
    {"bound-controller-steps",
     "legalisation: each curve.lap cut in steps whose counts at the compiled values are past a "
     "region's limit cut at points chosen on the host, what its regions read fixed",
     boundControllerSteps},
    {"write-curve-blocks",
     "legalisation: each curve.lap cut as NURBS or spline blocks as the move.nurbs or move.spline "
     "of its table",
     writeCurveBlocks},
    {"fit-arcs", "legalisation: each curve.lap cut as arcs as the fit's move.arc and move.feed ops",
     fitLapArcs},
    {"expand-controller-loops",
     "legalisation: each curve.lap cut in steps as a loop per region the controller runs",
     expandControllerLoops},
    {"expand-curve-laps",
     "legalisation: each curve.lap as loops over tables of the points chosen on the host",
     expandCurveLaps},
    {"fold", "constant folding and algebraic simplification", foldConstants},
    {"cse", "common subexpression elimination", eliminateCommonSubexpressions},
    {"licm", "loop-invariant code motion", hoistLoopInvariants},
    {"unroll",
     "full unrolling of loops of at most 8 trips and 64 body instructions (any body run at most "
     "once)",
     unrollWithDefaults},
    {"unroll-no-larger", "unroll, keeping only unrollings that leave the function no larger",
     unrollWhenNoLarger},
    {"dce", "dead code elimination", eliminateDeadCode},
    {"drop-pass-depths",
     "for the targets that print the IR as it stands: each pass.begin removed (a controller's "
     "pass loop says no depth)",
     dropPassDepths, false},
    {"expand-whole-powers",
     "for the macro programs: a ^ n with a whole constant n (|n| <= 64) as multiplications, "
     "defined for a negative a where EXP[LN[a]*n] is not, and a ^ (n + 1/2) times sqrt(a), "
     "defined at a = 0",
     expandWholePowers, false},
    {"fold-finite",
     "for a controller that alarms on a non-finite value: constant folding and x+0, x-0, x*1, "
     "x/1, x*0 as on finite numbers",
     foldAssumingFinite, false},
};

constexpr std::string_view defaultPassNames[] = {
    "fold", "cse", "licm", "unroll-no-larger", "fold", "cse", "dce",
};

} // namespace

std::span<const Pass> allPasses() {
  return passTable;
}

const Pass* findPass(std::string_view name) {
  for (const Pass& pass : passTable) {
    if (pass.name == name) {
      return &pass;
    }
  }
  return nullptr;
}

std::span<const std::string_view> defaultPipeline() {
  return defaultPassNames;
}

bool runPasses(Function& function, std::span<const std::string> names,
               const AfterPassCallback& afterPass, std::string* unknown) {
  std::vector<const Pass*> passes;
  for (const std::string& name : names) {
    const Pass* pass = findPass(name);
    if (pass == nullptr) {
      if (unknown != nullptr) {
        *unknown = name;
      }
      return false;
    }
    passes.push_back(pass);
  }
  for (const Pass* pass : passes) {
    pass->run(function);
    if (afterPass) {
      afterPass(pass->name, function);
    }
  }
  return true;
}

void runDefaultPipeline(Function& function, const AfterPassCallback& afterPass, int maximumRounds) {
  for (int round = 0; round < maximumRounds; ++round) {
    bool changed = false;
    for (std::string_view name : defaultPassNames) {
      const Pass* pass = findPass(name);
      changed |= pass->run(function);
      if (afterPass) {
        afterPass(pass->name, function);
      }
    }
    if (!changed) {
      break;
    }
  }
}

void runCurveLegalisation(Function& function, const AfterPassCallback& afterPass) {
  for (std::string_view name :
       {"unroll-host-control", "choose-curve-blocks", "choose-controller-steps", "split-arc-laps",
        "bound-controller-steps", "write-curve-blocks", "fit-arcs", "expand-controller-loops",
        "expand-curve-laps"}) {
    const Pass* pass = findPass(name);
    pass->run(function);
    if (afterPass) {
      afterPass(pass->name, function);
    }
  }
}

std::size_t instructionCount(const Function& function) {
  return passes::regionSize(function, function.body);
}

} // namespace cncc::ir
