// The default pipeline on every example that lowers: the interpreter's tool
// path is the same before and after, and the function does not grow.
#include "cncc/frontend/sema.h"
#include "cncc/frontend/source_manager.h"
#include "cncc/ir/curve_lap.h"
#include "cncc/ir/curve_lap_steps.h"
#include "cncc/ir/interpreter.h"
#include "cncc/ir/passes.h"
#include "cncc/ir/printer.h"
#include "cncc/ir/verifier.h"
#include "cncc/lowering/lowering.h"
#include "lowered_text.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <string>

namespace cncc::ir {
namespace {

// An example checked and lowered; the checked program is kept, since the
// curve table's geometry of target-neutral IR evaluates its expressions.
struct LoweredExample {
  frontend::SourceManager sources;
  frontend::DiagnosticEngine diagnostics;
  frontend::CheckedProgram program;
  std::optional<Function> function;
};

std::unique_ptr<LoweredExample> lowerExampleKept(const std::string& name, const std::string& part,
                                                 const LoweringOptions& lowering) {
  auto lowered = std::make_unique<LoweredExample>();
  std::optional<frontend::FileId> file =
      lowered->sources.loadFile(std::string(CNCC_SOURCE_DIR) + "/examples/" + name);
  if (!file) {
    ADD_FAILURE() << "cannot read " << name;
    return lowered;
  }
  frontend::CheckOptions options;
  options.importPaths = {CNCC_STDLIB_DIR};
  options.requirePart = true;
  options.partName = part;
  lowered->program = frontend::checkProgram(lowered->sources, *file, options, lowered->diagnostics);
  if (!lowered->diagnostics.hasErrors() && lowered->program.selectedPart != nullptr) {
    lowered->function =
        lowerPart(lowered->program, *lowered->program.selectedPart, lowered->diagnostics, lowering);
  }
  return lowered;
}

std::optional<Function> lowerExample(const std::string& name, const std::string& part) {
  return lowerExampleKept(name, part, {})->function;
}

// The same path to the last bit; where `cutsRenumbered`, a cut.begin's
// number after is its place in the program (unroll-host-control gives each
// trip of a loop its own cut).
void expectSamePath(const ToolPath& before, const ToolPath& after, const std::string& name,
                    bool cutsRenumbered = false) {
  ASSERT_EQ(before.events.size(), after.events.size()) << name;
  std::size_t inexact = 0;
  double cuts = 0;
  for (std::size_t i = 0; i < before.events.size(); ++i) {
    const MachineEvent& a = before.events[i];
    const MachineEvent& b = after.events[i];
    ASSERT_EQ(a.kind, b.kind) << name << " event " << i;
    EXPECT_EQ(a.text, b.text) << name << " event " << i;
    EXPECT_EQ(a.alongZ, b.alongZ) << name << " event " << i;
    double number = a.number;
    if (cutsRenumbered && a.kind == MachineEvent::Kind::CutBegin) {
      number = cuts++;
    }
    for (auto [x, y] :
         {std::pair{a.x, b.x}, std::pair{a.y, b.y}, std::pair{a.z, b.z}, std::pair{a.feed, b.feed},
          std::pair{number, b.number}, std::pair{a.diameter, b.diameter}}) {
      EXPECT_NEAR(x, y, 1e-9) << name << " event " << i;
      inexact += x == y ? 0 : 1;
    }
  }
  // Folding uses the interpreter's arithmetic: not even the last bit moves.
  EXPECT_EQ(inexact, 0u) << name;
}

struct Example {
  const char* file;
  const char* part; // empty: the file's only part
};

constexpr Example examples[] = {
    {"archimedean_spiral.cdl", ""},
    {"bolt_circle.cdl", ""},
    {"cam_profile.cdl", ""},
    {"helix_bore.cdl", "bore_plate_mm"},
    {"helix_bore.cdl", "bore_plate_inch"},
    {"offset_contours.cdl", ""},
    {"polar_contour.cdl", ""},
    {"rosette_plate.cdl", ""},
    {"s_profile.cdl", ""},
    {"worn_cutter.cdl", ""},
};

TEST(PassesExamplesTest, DefaultPipelineKeepsToolPathAndDoesNotGrow) {
  int lowered = 0;
  for (const Example& example : examples) {
    std::string name = std::string(example.file) + (*example.part ? ":" : "") + example.part;
    std::optional<Function> function = lowerExample(example.file, example.part);
    if (!function) {
      std::cout << name << ": does not lower in this version, skipped\n";
      continue;
    }
    ++lowered;
    ToolPath before = interpret(*function);
    std::size_t countBefore = instructionCount(*function);
    runDefaultPipeline(*function, [&](std::string_view pass, const Function& after) {
      EXPECT_TRUE(verifyFunction(after).empty()) << name << " after " << pass;
    });
    std::size_t countAfter = instructionCount(*function);
    expectSamePath(before, interpret(*function), name);
    EXPECT_LE(countAfter, countBefore) << name;
    std::cout << name << ": " << countBefore << " -> " << countAfter << " instructions, "
              << before.events.size() << " events\n";
  }
  // archimedean_spiral, polar_contour and s_profile lower today.
  EXPECT_GE(lowered, 3);
}

// The function's curve.laps cut as `sampling` says (all: nullopt).
using EntryTest = std::function<bool(const CurveTableEntry&)>;

std::size_t curveLapCount(const Function& function, const EntryTest& counted = nullptr) {
  std::size_t laps = 0;
  for (const Instruction& instruction : function.instructions) {
    laps += instruction.opcode == Opcode::CurveLap &&
                    (!counted || counted(function.curves[instruction.index]))
                ? 1
                : 0;
  }
  return laps;
}

EntryTest cutBy(CurveSampling sampling) {
  return [sampling](const CurveTableEntry& entry) { return entry.sampling == sampling; };
}

// Cut as arcs, or asking for them in place of chords or steps.
bool arcsWanted(const CurveTableEntry& entry) {
  return entry.sampling == CurveSampling::Arcs || entry.arcsAsked;
}

// Calls `check` with each example lowered with `lowering` (its source kept
// alive meanwhile); an example that does not lower is a failure.
void forEveryLoweredExample(const LoweringOptions& lowering,
                            const std::function<void(const std::string&, Function&)>& check) {
  for (const Example& example : examples) {
    std::string name = std::string(example.file) + (*example.part ? ":" : "") + example.part;
    std::unique_ptr<LoweredExample> lowered =
        lowerExampleKept(example.file, example.part, lowering);
    if (!lowered->function) {
      ADD_FAILURE() << name << " does not lower";
      continue;
    }
    check(name, *lowered->function);
  }
}

// Every example lowered with `lowering`, its laps left (expandCurveLaps
// off): interpreting the IR after choose-curve-blocks (where the target's
// blocks take the place of the chords the lowering gives every target; on
// a host after unroll-host-control, which gives each trip its curve) and
// after the legalisations gives the same path to the last bit. The laps
// cut as `sampling` says (all: nullopt) there.
std::size_t legaliseEveryExample(LoweringOptions lowering, const EntryTest& counted = nullptr) {
  lowering.expandCurveLaps = false;
  std::size_t laps = 0;
  forEveryLoweredExample(lowering, [&](const std::string& name, Function& function) {
    unrollHostControl(function);
    chooseCurveBlocks(function);
    laps += curveLapCount(function, counted);
    ToolPath before = interpret(function);
    runCurveLegalisation(function);
    EXPECT_EQ(curveLapCount(function), 0u) << name;
    EXPECT_TRUE(verifyFunction(function).empty()) << name;
    expectSamePath(before, interpret(function), name, lowering.keepLoops);
  });
  return laps;
}

// The target-neutral IR, its laps run by the interpreter, gives the path
// of the IR after expand-curve-laps to the last bit: every stage runs.
TEST(PassesExamplesTest, ExpandingCurveLapsKeepsToolPath) {
  // Every example but the ones cut on arcs alone has laps along its curves.
  EXPECT_GE(legaliseEveryExample({}), 10u);
}

// The same with --arcs on a target that prints G02/G03 (as gcode's grid):
// the level laps of every cut ask for arcs, which fit-arcs writes out as
// the interpreter ran them (or, where no fit keeps them, leaves to the
// expansion the interpreter ran instead).
TEST(PassesExamplesTest, FittingArcsKeepsToolPath) {
  LoweringOptions arcs;
  arcs.fittedArcs = true;
  arcs.arcsOnEveryCut = true;
  arcs.coordinateIncrement = 0.0001;
  EXPECT_GE(legaliseEveryExample(arcs, arcsWanted), 10u);
}

// A target whose host computes the program, given a `for` or `if` on
// parameters as a controller is (the target-neutral IR): its loops and
// branches run as unroll-host-control writes them out, each trip's laps
// cut at the chords the host chooses for that trip.
TEST(PassesExamplesTest, HostLegalisationOfLoopsKeepsEveryExamplesToolPath) {
  LoweringOptions host;
  host.keepLoops = true;
  host.coordinateIncrement = 0.0001;
  EXPECT_GE(legaliseEveryExample(host), 10u);
  host.splineInterpolation = true; // sinumerik: its spline blocks in each trip
  host.splineBlocks = true;
  host.coordinateIncrement = 0.001;
  EXPECT_GE(legaliseEveryExample(host, cutBy(CurveSampling::SplineBlocks)), 7u);
}

// And on a target that runs loops: the laps of a cut whose curve is
// numbers (chords choose-controller-steps cuts in steps) ask for arcs
// inside the pass loop (its height the loop's); the examples' other curves
// read parameters (arcs-as-chords).
TEST(PassesExamplesTest, FittingArcsInControllerLoopsKeepsToolPath) {
  LoweringOptions arcs;
  arcs.controllerLoops = true;
  arcs.fittedArcs = true;
  arcs.arcsOnEveryCut = true;
  arcs.coordinateIncrement = 0.0001; // fine enough for the parts in inches
  EXPECT_GE(legaliseEveryExample(arcs, arcsWanted), 1u);
}

// Read back from its text, a lap asking for arcs has not the source's
// curve: the interpreter fits the curve its regions compute (which may
// differ from the source's in the last bits), and the arcs, on a grid of
// 0.001, are the same.
TEST(PassesExamplesTest, ArcsFittedAgainFromTheTextAreTheSame) {
  LoweringOptions arcs;
  arcs.expandCurveLaps = false;
  arcs.fittedArcs = true;
  arcs.arcsOnEveryCut = true;
  arcs.coordinateIncrement = 0.001;
  std::unique_ptr<LoweredExample> lowered = lowerExampleKept("polar_contour.cdl", "", arcs);
  ASSERT_TRUE(lowered->function);
  ASSERT_GE(curveLapCount(*lowered->function, arcsWanted), 1u);
  ParseError error;
  std::optional<Function> parsed = parseFunction(printFunction(*lowered->function), error);
  ASSERT_TRUE(parsed) << error.line << ": " << error.message;
  ToolPath before = interpret(*lowered->function);
  ToolPath after = interpret(*parsed);
  ASSERT_EQ(before.events.size(), after.events.size());
  std::size_t arcMoves = 0;
  for (std::size_t i = 0; i < before.events.size(); ++i) {
    const MachineEvent& a = before.events[i];
    const MachineEvent& b = after.events[i];
    ASSERT_EQ(a.kind, b.kind) << i;
    arcMoves += a.kind == MachineEvent::Kind::Arc ? 1 : 0;
    for (auto [x, y] : {std::pair{a.x, b.x}, std::pair{a.y, b.y}, std::pair{a.z, b.z},
                        std::pair{a.centreX, b.centreX}, std::pair{a.centreY, b.centreY}}) {
      EXPECT_NEAR(x, y, 1e-9) << i;
    }
  }
  EXPECT_GE(arcMoves, 10u);
}

// On a target that runs loops: its laps left (expandCurveLaps off), at
// the printed grid of a millimetre part.
LoweringOptions controllerLoopOptions() {
  LoweringOptions controller;
  controller.expandCurveLaps = false;
  controller.controllerLoops = true;
  controller.coordinateIncrement = 0.001;
  return controller;
}

// The legalisations write the laps out as loops over no tables, and the
// path is the one the laps ran, to the last bit.
void expectLoopsKeepPath(Function& function, const std::string& name) {
  ToolPath before = interpret(function);
  runCurveLegalisation(function);
  EXPECT_EQ(curveLapCount(function), 0u) << name;
  EXPECT_TRUE(function.tables.empty()) << name;
  EXPECT_TRUE(verifyFunction(function).empty()) << name;
  expectSamePath(before, interpret(function), name);
}

// On a target that runs loops, a cut of constant pieces is the chords every
// target's lowering gives it, which choose-controller-steps cuts in steps,
// their counts left to expand-controller-loops; its loops run the points
// the interpreter ran the lap with, before either pass.
TEST(PassesExamplesTest, ControllerLoopsKeepToolPath) {
  LoweringOptions controller = controllerLoopOptions();
  std::unique_ptr<test_support::LoweredText> lowered = test_support::lowerText(R"(
part ring(depth = 4) {
  tool 1 diameter=4 feed=200
  safe z=3
  curve path(line(from = (22, 0), to = (30, 0)), line(from = (30, 0), to = (22, 0)),
             polar(r = 18 + 4*cos(2*t)*cos(6*t), t = 0 .. 2*pi)) sweep depth=depth step=2
             entry=ramp
})",
                                                                               controller);
  ASSERT_TRUE(lowered->part);
  Function& function = lowered->part->function;
  ASSERT_EQ(function.curves.size(), 1u);
  EXPECT_EQ(function.curves.front().sampling, CurveSampling::ChordTolerance);
  ASSERT_TRUE(function.cuts.front().controllerDigits);
  ToolPath beforeThePass = interpret(function);
  ASSERT_TRUE(chooseControllerSteps(function));
  const CurveTableEntry& entry = function.curves.front();
  EXPECT_EQ(entry.sampling, CurveSampling::Steps);
  // Within 0.01 less the rounding of two axes (a plane) and the literals'.
  EXPECT_NEAR(entry.amount, 0.01 - std::sqrt(2.0) * 0.0005 - 0.02 * 0.001, 1e-15);
  EXPECT_EQ(entry.regionSteps, std::vector<int>(3, stepsChosenByLegalisation));
  // A step for each line, many for the polar curve.
  std::vector<int> chosen = withChosenSteps(entry, *entry.geometry).regionSteps;
  EXPECT_EQ(chosen[0], 1);
  EXPECT_EQ(chosen[1], 1);
  EXPECT_GT(chosen[2], 50);
  expectSamePath(beforeThePass, interpret(function), "ring, stepped");
  expectLoopsKeepPath(function, "ring");
}

// A span one chord cuts is one step (no loop for the nesting of the
// program's loops to count), as the legalisation measures it.
TEST(PassesExamplesTest, ASpanOneChordCutsIsOneStep) {
  LoweringOptions controller = controllerLoopOptions();
  std::unique_ptr<test_support::LoweredText> lowered = test_support::lowerText(R"(
part square() {
  tool 1 diameter=4 feed=200
  safe z=3
  curve bspline(degree=1, points=[(0,0), (10,0), (10,10), (0,10)]) sweep depth=2 step=1
})",
                                                                               controller);
  ASSERT_TRUE(lowered->part);
  Function& function = lowered->part->function;
  ASSERT_TRUE(chooseControllerSteps(function));
  const CurveTableEntry& entry = function.curves.front();
  EXPECT_EQ(withChosenSteps(entry, *entry.geometry).regionSteps, (std::vector<int>{1, 1, 1}));
  expectLoopsKeepPath(function, "square");
  auto loops = std::count_if(function.instructions.begin(), function.instructions.end(),
                             [](const Instruction& op) { return op.opcode == Opcode::Loop; });
  EXPECT_EQ(loops, 1); // the passes'
}

// A B-spline's knot spans are regions of u in 0 .. 1, each in its own
// count of steps (the chords' regions, cut in steps by
// choose-controller-steps), the program computing each point from the
// span's polynomial: the loops run the points the lap ran, on the ramp too.
TEST(PassesExamplesTest, KnotSpansAreRegionsOfTheirOwnSteps) {
  LoweringOptions controller = controllerLoopOptions();
  std::unique_ptr<test_support::LoweredText> lowered = test_support::lowerText(R"(
part hook() {
  tool 1 diameter=4 feed=200
  safe z=3
  curve bspline(degree=2, points=[(0,0), (10,10), (20,0), (30,10), (15,-10), (0,0)])
        tolerance=0.01 entry=ramp sweep depth=2 step=1
})",
                                                                               controller);
  ASSERT_TRUE(lowered->part);
  Function& function = lowered->part->function;
  ASSERT_EQ(function.curves.size(), 1u);
  ASSERT_TRUE(chooseControllerSteps(function));
  const CurveTableEntry& entry = function.curves.front();
  EXPECT_EQ(entry.sampling, CurveSampling::Steps);
  ASSERT_EQ(entry.pieces.size(), 1u);
  EXPECT_EQ(entry.pieces.front().spans.size(), 4u);
  ASSERT_EQ(entry.regionSteps.size(), 4u);
  // Each span's count is the legalisation's, measured on the curve.
  std::vector<int> counts = withChosenSteps(entry, *entry.geometry).regionSteps;
  for (std::size_t region = 0; region < 4; ++region) {
    EXPECT_EQ(entry.regionRange(region), (std::pair<double, double>{0.0, 1.0}));
    EXPECT_EQ(entry.regionSteps[region], stepsChosenByLegalisation);
    EXPECT_GT(counts[region], 1);
  }
  expectLoopsKeepPath(function, "hook");
}

// A piece that depends on parameters is a region whose range and count the
// program computes: the lap and its loops take the same points for values
// edited at the machine too.
TEST(PassesExamplesTest, ComputedStepsFollowEditedParameters) {
  LoweringOptions controller = controllerLoopOptions();
  std::unique_ptr<test_support::LoweredText> lowered = test_support::lowerText(R"(
part rosette(a = 10, b = 2, turns = 2) {
  tool 1 diameter=1 feed=100
  safe z=2
  curve polar(r = a + b*cos(3*t), t = 0 .. turns*2*pi) tolerance=0.01 entry=ramp sweep depth=2
        step=1
})",
                                                                               controller);
  ASSERT_TRUE(lowered->part);
  Function& function = lowered->part->function;
  ASSERT_EQ(function.curves.size(), 1u);
  EXPECT_EQ(function.curves.front().regionSteps, std::vector<int>{0});
  Function expanded = function;
  runCurveLegalisation(expanded);
  EXPECT_EQ(curveLapCount(expanded), 0u);
  EXPECT_TRUE(verifyFunction(expanded).empty());
  std::size_t moves = 0;
  for (const std::map<std::string, double>& edited : {std::map<std::string, double>{},
                                                      {{"a", 3}, {"b", 0.5}, {"turns", 3}},
                                                      {{"b", 5}, {"turns", 1.25}}}) {
    InterpreterOptions options;
    options.parameters = edited;
    ToolPath before = interpret(function, options);
    expectSamePath(before, interpret(expanded, options), "rosette");
    EXPECT_NE(before.events.size(), moves); // the count follows the values
    moves = before.events.size();
  }
}

// Every example lowered for a target that runs loops: the IR before the
// legalisations and after them gives the same path to the last bit.
TEST(PassesExamplesTest, ControllerLegalisationKeepsEveryExamplesToolPath) {
  LoweringOptions controller;
  controller.controllerLoops = true;
  controller.coordinateIncrement = 0.0001; // fine enough for the parts in inches
  // polar_contour's ramp and level laps.
  EXPECT_GE(legaliseEveryExample(controller, cutBy(CurveSampling::Steps)), 1u);
}

// Every example lowered for a target that prints NURBS blocks (Fanuc, M80),
// for one that prints spline blocks (Sinumerik) and for one that prints
// cubic spans (Heidenhain SPL): a lap cut as the blocks runs as their
// moves, before write-curve-blocks and after it.
TEST(PassesExamplesTest, CurveBlocksKeepEveryExamplesToolPath) {
  LoweringOptions nurbs;
  nurbs.controllerLoops = true;
  nurbs.nurbsBlocks = true;
  nurbs.coordinateIncrement = 0.0001;
  // cam_profile's engraved mark, method=nurbs.
  EXPECT_GE(legaliseEveryExample(nurbs, cutBy(CurveSampling::NurbsBlocks)), 1u);
  LoweringOptions splines;
  splines.splineInterpolation = true;
  splines.splineBlocks = true;
  splines.coordinateIncrement = 0.001;
  // rosette_plate's petals (method=cspline) and the other spline cuts: 7
  // laps, each in its sweep's pass loop.
  EXPECT_GE(legaliseEveryExample(splines, cutBy(CurveSampling::SplineBlocks)), 7u);
  LoweringOptions spans;
  spans.controllerLoops = true;
  spans.fittedArcs = true;
  spans.polynomialBlocks = true;
  spans.coordinateIncrement = 0.0001;
  // cam_profile's mark as SPL spans; rosette_plate's petals read the
  // variable of the loop the controller runs: chords.
  EXPECT_GE(legaliseEveryExample(spans, cutBy(CurveSampling::PolynomialBlocks)), 1u);
}

// Every example as the macro targets give it to their printer (controller
// loops, the default pipeline, then fold-finite): fold-finite moves no
// number by more than what it takes as 0 or 1, and finds something to fold.
TEST(PassesExamplesTest, FoldFiniteKeepsEveryExamplesPathToRounding) {
  LoweringOptions controller;
  controller.controllerLoops = true;
  controller.coordinateIncrement = 0.0001;
  std::size_t changed = 0;
  forEveryLoweredExample(controller, [&](const std::string& name, Function& function) {
    runDefaultPipeline(function);
    ToolPath before = interpret(function);
    changed += foldAssumingFinite(function) ? 1 : 0;
    EXPECT_TRUE(verifyFunction(function).empty()) << name;
    ToolPath after = interpret(function);
    ASSERT_EQ(before.events.size(), after.events.size()) << name;
    for (std::size_t i = 0; i < before.events.size(); ++i) {
      const MachineEvent& a = before.events[i];
      const MachineEvent& b = after.events[i];
      ASSERT_EQ(a.kind, b.kind) << name << " event " << i;
      for (auto [x, y] : {std::pair{a.x, b.x}, std::pair{a.y, b.y}, std::pair{a.z, b.z},
                          std::pair{a.feed, b.feed}, std::pair{a.number, b.number}}) {
        ASSERT_NEAR(x, y, 1e-9) << name << " event " << i;
      }
    }
  });
  EXPECT_GE(changed, 1u);
}

TEST(PassesExamplesTest, EveryPassAloneKeepsToolPath) {
  std::optional<Function> lowered = lowerExample("s_profile.cdl", "");
  ASSERT_TRUE(lowered);
  ToolPath before = interpret(*lowered);
  for (const Pass& pass : allPasses()) {
    if (!pass.exact) {
      continue; // fold-finite: FoldFiniteKeepsEveryExamplesPathToRounding
    }
    Function function = *lowered;
    pass.run(function);
    EXPECT_TRUE(verifyFunction(function).empty()) << pass.name;
    expectSamePath(before, interpret(function), std::string(pass.name));
  }
}

} // namespace
} // namespace cncc::ir
