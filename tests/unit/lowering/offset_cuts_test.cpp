// Cuts beside the curve (side=left|right): the cut table holds the exact
// offset, the IR's tool path lies on it within the tolerance, lines and arcs
// stay native arcs, and what a target cannot offset is an error at the cut.
#include "cncc/lowering/lowering.h"

#include "cncc/frontend/sema.h"
#include "cncc/frontend/source_manager.h"
#include "cncc/geom/composite_curve.h"
#include "cncc/geom/deviation.h"
#include "cncc/geom/line_arc_curves.h"
#include "cncc/geom/offset_curve.h"
#include "cncc/ir/interpreter.h"
#include "cncc/ir/passes.h"
#include "cncc/ir/printer.h"
#include "cncc/ir/verifier.h"

#include "../ir/curve_lap_fixtures.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numbers>
#include <string>

namespace cncc::ir {
namespace {

// A part compiled with `options`: its lowering (nullopt after an error) and
// the diagnostics.
class Compiled {
public:
  Compiled(const std::string& text, const LoweringOptions& options) {
    frontend::CheckOptions checking;
    checking.requirePart = true;
    program_ = frontend::checkProgram(sources_, sources_.addFile("offsets.cdl", text), checking,
                                      diagnostics_);
    EXPECT_FALSE(diagnostics_.hasErrors());
    part = lowerPartWithCuts(*program_, *program_->selectedPart, diagnostics_, options);
  }

  bool reported(frontend::DiagnosticKind kind) const {
    for (const frontend::Diagnostic& diagnostic : diagnostics_.diagnostics()) {
      if (diagnostic.kind == kind) {
        return true;
      }
    }
    return false;
  }

  std::optional<LoweredPart> part;

private:
  frontend::SourceManager sources_;
  frontend::DiagnosticEngine diagnostics_;
  std::optional<frontend::CheckedProgram> program_;
};

std::string polarPart(const char* side) {
  return std::string("part p() {\n  tool 1 diameter=4 feed=300\n  safe z=5\n"
                     "  curve polar(r = 18 + 4*cos(2*t)*cos(6*t), t = 0 .. 2*pi) side=") +
         side + " tolerance=0.01\n}\n";
}

TEST(OffsetCuts, TheCutTableHoldsTheExactOffsetAndTheToolPathFollowsIt) {
  for (const char* side : {"left", "right"}) {
    Compiled compiled(polarPart(side), {});
    ASSERT_TRUE(compiled.part) << side;
    ASSERT_EQ(compiled.part->function.cuts.size(), 1u);
    const auto* offset =
        dynamic_cast<const geom::OffsetCurve*>(compiled.part->function.cuts.front().curve.get());
    ASSERT_NE(offset, nullptr) << side;
    EXPECT_EQ(offset->distance(), std::string(side) == "left" ? 2.0 : -2.0);
    for (double t = 0; t < 6.28; t += 0.1) {
      EXPECT_NEAR((offset->point(t) - offset->base().point(t)).norm(), 2.0, 1e-12);
    }
    // Every feed of the cut ends on the offset, and every chord keeps within
    // the tolerance of it.
    ToolPath path = interpret(compiled.part->function);
    std::vector<Eigen::Vector3d> points;
    for (const MachineEvent& event : path.events) {
      if (event.kind == MachineEvent::Kind::Feed && event.z == 0) {
        points.emplace_back(event.x, event.y, 0);
      }
    }
    ASSERT_GT(points.size(), 150u) << side;
    // The first feed is the plunge's end at the start; the lap closes there.
    points.push_back(points.front());
    geom::DeviationOptions coarse;
    coarse.accuracy = 1e-5;
    double deviation = geom::measureDeviation(points, *offset, coarse).maxDeviation();
    EXPECT_LE(deviation, 0.01 + coarse.accuracy) << side;
    EXPECT_GT(deviation, 0.005) << side; // the chords use the tolerance
  }
}

TEST(OffsetCuts, LinesAndArcsStayNativeArcs) {
  Compiled compiled("part p() {\n  tool 1 diameter=6 feed=300\n  safe z=5\n"
                    "  curve path(line((0, 0), (30, 0)), arc(center=(30, 10), radius=10, "
                    "from=-pi/2, to=pi/2), line((30, 20), (0, 20)), line((0, 20), (0, 0))) "
                    "side=right\n}\n",
                    {});
  ASSERT_TRUE(compiled.part);
  const CutGeometry& cut = compiled.part->function.cuts.front();
  EXPECT_EQ(cut.arcMoves, CutArcs::Native);
  const auto* offset = dynamic_cast<const geom::CompositeCurve*>(cut.curve.get());
  ASSERT_NE(offset, nullptr);
  ASSERT_EQ(offset->pieceCount(), 6u); // four pieces, arcs at two corners
  const auto* arc = dynamic_cast<const geom::ArcCurve*>(&offset->piece(1));
  ASSERT_NE(arc, nullptr);
  EXPECT_DOUBLE_EQ(arc->radius(), 13.0);
  int arcMoves = 0;
  for (const MachineEvent& event : interpret(compiled.part->function).events) {
    arcMoves += event.kind == MachineEvent::Kind::Arc ? 1 : 0;
  }
  EXPECT_EQ(arcMoves, 3); // the slot's end and the two corners
}

TEST(OffsetCuts, ControllerTargetsRefuseAnOffsetThatDependsOnAParameter) {
  LoweringOptions controller;
  controller.controllerLoops = true;
  Compiled compiled("part p(size = 20) {\n  tool 1 diameter=4 feed=300\n  safe z=5\n"
                    "  curve arc(center=(0, 0), radius=size, from=0, to=2*pi) side=left\n}\n",
                    controller);
  EXPECT_FALSE(compiled.part);
  EXPECT_TRUE(compiled.reported(frontend::DiagnosticKind::UnsupportedConstruct));
  // The host computes it at the default.
  Compiled host("part p(size = 20) {\n  tool 1 diameter=4 feed=300\n  safe z=5\n"
                "  curve arc(center=(0, 0), radius=size, from=0, to=2*pi) side=left\n}\n",
                {});
  ASSERT_TRUE(host.part);
  EXPECT_NEAR(host.part->function.cuts.front().curve->point(0).x(), 18.0, 1e-12);
}

// With the tool diameter a parameter the controller computes each tool
// centre from the point and the derivative of the same arithmetic: every
// feed of the loop is exactly C(t) + d N(t) at its step's t, through
// exp, sin, sqrt, atan, pow, division and products of t.
TEST(OffsetCuts, ControllerOffsetsFollowTheCurvesDerivative) {
  LoweringOptions controller;
  controller.controllerLoops = true;
  const char* curve = "param(x = 3*t + 0.2*cos(t), y = exp(t/3)*sin(2*t) + sqrt(1 + t*t) + "
                      "atan(t) + pow(t, 3)/9 - t/(2 + t), t = 0 .. 3)";
  for (const char* side : {"left", "right"}) {
    Compiled compiled(std::string("part p(dia = 1) {\n  tool 1 diameter=dia feed=300\n"
                                  "  safe z=5\n  curve ") +
                          curve + " side=" + side + " tolerance=0.01\n}\n",
                      controller);
    ASSERT_TRUE(compiled.part) << side;
    const auto* offset =
        dynamic_cast<const geom::OffsetCurve*>(compiled.part->function.cuts.front().curve.get());
    ASSERT_NE(offset, nullptr);
    std::vector<Eigen::Vector3d> feeds;
    for (const MachineEvent& event : interpret(compiled.part->function).events) {
      if (event.kind == MachineEvent::Kind::Feed && event.z == 0) {
        feeds.emplace_back(event.x, event.y, 0);
      }
    }
    // The plunge's end, then the loop's steps 1 .. N.
    ASSERT_GT(feeds.size(), 20u) << side;
    auto steps = static_cast<double>(feeds.size() - 1);
    for (std::size_t i = 0; i < feeds.size(); ++i) {
      Eigen::Vector3d exact = offset->point(3.0 * static_cast<double>(i) / steps);
      EXPECT_NEAR((feeds[i] - exact).norm(), 0.0, 1e-9) << side << " step " << i;
    }
  }
}

// The program keeps the tool's radius below the largest the curve takes,
// and grows its step count with the radius (the offset's curvature).
TEST(OffsetCuts, ControllerOffsetsCheckTheRadiusAndGrowTheirSteps) {
  LoweringOptions controller;
  controller.controllerLoops = true;
  std::string text = polarPart("right").replace(polarPart("right").find("p()"), 3, "p(dia = 4)");
  text.replace(text.find("diameter=4"), 10, "diameter=dia");
  Compiled compiled(text, controller);
  ASSERT_TRUE(compiled.part);
  std::string printed = printFunction(compiled.part->function);
  EXPECT_NE(printed.find("the tool radius must be below 2.3313 for this curve"), std::string::npos)
      << printed;
  EXPECT_NE(printed.find("the tool diameter is not positive"), std::string::npos);
  auto feeds = [&](const std::string& diameter) {
    std::string own = text;
    own.replace(own.find("dia = 4"), 7, "dia = " + diameter);
    Compiled at(own, controller);
    std::size_t count = 0;
    for (const MachineEvent& event : interpret(at.part->function).events) {
      count += event.kind == MachineEvent::Kind::Feed ? 1 : 0;
    }
    return count;
  };
  std::size_t thin = feeds("0.1");
  std::size_t wide = feeds("4.6");
  EXPECT_GT(static_cast<double>(wide), 1.2 * static_cast<double>(thin));
}

// A tool diameter that is a parameter on a host target: the lowering gives
// it the controller's laps (the regions read the parameter, the counts grow
// with it); the host's legalisations cut the circle's offset as arcs and
// the polar curve's as chords of the exact offset at the compiled radius,
// with the parameter fixed. Without them the host computed the offset
// itself (the circle in chords).
TEST(OffsetCuts, AParameterRadiusOnAHostIsTheControllersLapsCutAtTheCompiledRadius) {
  LoweringOptions host;
  host.expandCurveLaps = false;
  Compiled compiled("part p(dia = 4) {\n  tool 1 diameter=dia feed=300\n  safe z=5\n"
                    "  curve arc(center=(0, 0), radius=20, from=0, to=2*pi) side=right\n"
                    "  curve polar(r = 18 + 4*cos(2*t)*cos(6*t), t = 0 .. 2*pi) side=right "
                    "tolerance=0.01\n}\n",
                    host);
  ASSERT_TRUE(compiled.part);
  Function& function = compiled.part->function;
  ASSERT_EQ(function.parameters.size(), 1u);
  EXPECT_FALSE(function.parameters.front().fixed);
  bool grows = false;
  for (const CurveTableEntry& entry : function.curves) {
    grows = grows || entry.offsetGrowth.has_value();
  }
  EXPECT_TRUE(grows);
  ToolPath before = interpret(function);
  Function legalised = function;
  frontend::DiagnosticEngine diagnostics;
  ASSERT_TRUE(legaliseCurves(legalised, diagnostics));
  EXPECT_TRUE(verifyFunction(legalised).empty());
  EXPECT_TRUE(legalised.parameters.front().fixed);
  std::size_t arcs = 0;
  for (const Instruction& instruction : legalised.instructions) {
    arcs += instruction.opcode == Opcode::Arc ? 1 : 0;
    EXPECT_NE(instruction.opcode, Opcode::CurveLap);
  }
  EXPECT_GE(arcs, 1u);
  ToolPath after = interpret(legalised);
  curve_lap_test::expectSameMoves(before, after);
  const geom::Curve& offset = *function.cuts.back().curve;
  geom::CurveProximity near(offset, 1e-7);
  std::size_t checked = 0;
  for (const MachineEvent& event : after.events) {
    if (event.kind == MachineEvent::Kind::Feed && event.x < 25 && std::fabs(event.x) > 0.5) {
      checked += near.closestPoint({event.x, event.y, 0}).distance < 1e-6 ? 1 : 0;
    }
  }
  EXPECT_GT(checked, 50u); // the polar contour's chords end on its exact offset
}

// The cut's feeds at z = 0 (the plunge's end first).
std::vector<Eigen::Vector3d> levelFeeds(const ToolPath& path) {
  std::vector<Eigen::Vector3d> points;
  for (const MachineEvent& event : path.events) {
    if (event.kind == MachineEvent::Kind::Feed && event.z == 0) {
      points.emplace_back(event.x, event.y, 0);
    }
  }
  return points;
}

// A slot of lines and an arc, its convex corners rounded and its concave
// one (the notch) cut back: with the diameter a parameter, one curve.lap
// per pass whose regions are the pieces' offsets and an arc region per
// convex corner, written out as loops and blocks that run the same path for
// the values edited at the machine.
TEST(OffsetCuts, ControllerOffsetsAreLapsOfThePiecesAndTheCornerArcs) {
  LoweringOptions controller;
  controller.controllerLoops = true;
  controller.expandCurveLaps = false;
  controller.coordinateIncrement = 0.001;
  Compiled compiled("part p(dia = 4) {\n  tool 1 diameter=dia feed=300\n  safe z=5\n"
                    "  curve path(line((0, 0), (40, 0)), arc(center=(40, 8), radius=8, "
                    "from=-pi/2, to=pi/2), line((40, 16), (20, 16)), line((20, 16), (20, 30)), "
                    "line((20, 30), (0, 30)), line((0, 30), (0, 0))) side=right\n}\n",
                    controller);
  ASSERT_TRUE(compiled.part);
  Function& function = compiled.part->function;
  ASSERT_EQ(function.curves.size(), 1u);
  const CurveTableEntry& entry = function.curves.front();
  EXPECT_EQ(entry.sampling, CurveSampling::Steps);
  // Six pieces; convex corners after the fourth, fifth and sixth piece (the
  // last where the path closes); the notch's is concave.
  EXPECT_EQ(entry.regionCount(), 9u);
  ASSERT_EQ(entry.arcRegions.size(), 4u);
  EXPECT_EQ(entry.arcRegions[0].region, 1u); // the slot's end
  EXPECT_EQ(entry.arcRegions[1].region, 4u);
  EXPECT_EQ(entry.arcRegions[3].region, 8u);
  Function expanded = function;
  runCurveLegalisation(expanded);
  EXPECT_TRUE(verifyFunction(expanded).empty());
  for (const std::map<std::string, double>& edited :
       {std::map<std::string, double>{}, {{"dia", 2}}, {{"dia", 6.5}}}) {
    InterpreterOptions options;
    options.parameters = edited;
    ToolPath before = interpret(function, options);
    curve_lap_test::expectSameMoves(before, interpret(expanded, options));
    // The notch's crossing lies the radius from both lines it joins.
    double radius = (edited.empty() ? 4 : edited.begin()->second) / 2;
    bool crossing = false;
    for (const Eigen::Vector3d& point : levelFeeds(before)) {
      crossing = crossing || (point - Eigen::Vector3d(20 + radius, 16 + radius, 0)).norm() < 1e-9;
    }
    EXPECT_TRUE(crossing) << "dia " << 2 * radius;
  }
}

// A tool radius that is a number: on a target that runs loops a curve that
// is neither a line nor an arc is cut by the controller's loop over its
// offset, its count left to the legalisation, which measures it on the
// exact offset: within the tolerance, and using it.
TEST(OffsetCuts, AConstantRadiusBesideACurveIsALoopOnTheController) {
  LoweringOptions controller;
  controller.controllerLoops = true;
  controller.expandCurveLaps = false;
  Compiled compiled(polarPart("right"), controller);
  ASSERT_TRUE(compiled.part);
  Function& function = compiled.part->function;
  ASSERT_EQ(function.curves.size(), 1u);
  const CurveTableEntry& entry = function.curves.front();
  EXPECT_EQ(entry.sampling, CurveSampling::Steps);
  ASSERT_EQ(entry.regionSteps.size(), 1u);
  EXPECT_EQ(entry.regionSteps.front(), stepsChosenByLegalisation);
  EXPECT_EQ(printFunction(function).find("alarm"), std::string::npos);
  Function expanded = function;
  runCurveLegalisation(expanded);
  double count = 0; // the curve loop's, which the pass chose
  for (const Instruction& instruction : expanded.instructions) {
    if (instruction.opcode == Opcode::Loop) {
      count = std::max(count, expanded.definition(instruction.operands[1]).number);
    }
  }
  EXPECT_GT(count, 100);
  curve_lap_test::expectSameMoves(interpret(function), interpret(expanded));
  const auto* offset =
      dynamic_cast<const geom::OffsetCurve*>(compiled.part->function.cuts.front().curve.get());
  ASSERT_NE(offset, nullptr);
  std::vector<Eigen::Vector3d> points = levelFeeds(interpret(function));
  geom::DeviationOptions coarse;
  coarse.accuracy = 1e-5;
  double deviation = geom::measureDeviation(points, *offset, coarse).maxDeviation();
  EXPECT_LE(deviation, 0.01 + coarse.accuracy);
  EXPECT_GT(deviation, 0.005); // the steps use the tolerance
}

// What only the compiler's offset gives keeps the host's laps: points as
// numbers for lead arcs and samples=, and with fitted arcs too, asking
// fit-arcs for them; a path of lines and arcs is its arcs. A ramp is the
// controller's.
TEST(OffsetCuts, TheHostOffsetStaysWhereTheCutAsksForIt) {
  LoweringOptions controller;
  controller.controllerLoops = true;
  controller.expandCurveLaps = false;
  for (const char* modifier :
       {" lead=3", " samples=200", " arcs=true", " sweep depth=2 step=1 entry=ramp"}) {
    bool ramp = std::string(modifier).ends_with("ramp");
    bool arcs = std::string(modifier) == " arcs=true";
    std::string text = polarPart("right");
    text.insert(text.find("tolerance=0.01") + 14, modifier);
    LoweringOptions options = controller;
    options.fittedArcs = std::string(modifier) == " arcs=true";
    Compiled compiled(text, options);
    ASSERT_TRUE(compiled.part) << modifier;
    for (const CurveTableEntry& entry : compiled.part->function.curves) {
      EXPECT_EQ(entry.sampling == CurveSampling::Steps, ramp) << modifier;
      EXPECT_EQ(entry.arcsAsked.has_value(), arcs) << modifier;
      EXPECT_EQ(entry.pointsAsNumbers, !ramp) << modifier;
    }
  }
  Compiled slot("part p() {\n  tool 1 diameter=4 feed=300\n  safe z=5\n  curve path(line((0, "
                "0), (40, 0)), arc(center=(40, 8), radius=8, from=-pi/2, to=pi/2), line((40, 16), "
                "(0, 16)), line((0, 16), (0, 0))) side=right\n}\n",
                controller);
  ASSERT_TRUE(slot.part);
  EXPECT_TRUE(slot.part->function.curves.empty());
}

// On the host the offset is a curve.lap too: its pieces the offset's (a
// NURBS cut back at both ends, where it meets the lines at concave
// corners), its regions the drawn curve's arithmetic moved along the
// normal; the points the legalisation writes out are the ones the lap ran,
// and they lie on the exact offset.
TEST(OffsetCuts, HostOffsetsAreLapsOnTheExactOffset) {
  LoweringOptions host;
  host.expandCurveLaps = false;
  Compiled compiled("part p() {\n  tool 1 diameter=4 feed=300\n  safe z=5\n"
                    "  curve path(nurbs(degree=3, points=[(0, 0), (10, 20), (30, 25), (50, 0)]), "
                    "line((50, 0), (50, -20)), line((50, -20), (0, 0))) side=right "
                    "tolerance=0.01 sweep depth=2 step=1 entry=ramp\n}\n",
                    host);
  ASSERT_TRUE(compiled.part);
  Function& function = compiled.part->function;
  ASSERT_EQ(function.curves.size(), 1u);
  const CurveTableEntry& entry = function.curves.front();
  EXPECT_EQ(entry.sampling, CurveSampling::ChordTolerance);
  // Numbers where a controller computes the program (the lowering is the
  // same for every target); tables on this host's (below).
  EXPECT_TRUE(entry.pointsAsNumbers);
  const geom::Curve& offset = *compiled.part->function.cuts.front().curve;
  EXPECT_EQ(entry.geometry.get(), &offset);
  ASSERT_GE(entry.pieces.size(), 3u);
  const CurvePieceLayout& nurbs = entry.pieces.front();
  ASSERT_FALSE(nurbs.spans.empty());
  EXPECT_GT(nurbs.from, 0.0); // cut back at the concave corners
  EXPECT_LT(nurbs.to, 1.0);
  EXPECT_EQ(nurbs.spans.front().first, nurbs.from);
  EXPECT_EQ(nurbs.spans.back().second, nurbs.to);
  ToolPath before = interpret(function);
  Function expanded = function;
  ASSERT_TRUE(expandCurveLaps(expanded));
  EXPECT_TRUE(verifyFunction(expanded).empty());
  EXPECT_FALSE(expanded.tables.empty());
  curve_lap_test::expectSameMoves(before, interpret(expanded));
  std::vector<Eigen::Vector3d> points;
  for (const MachineEvent& event : before.events) {
    if (event.kind == MachineEvent::Kind::Feed && event.z == -2) {
      points.emplace_back(event.x, event.y, 0);
    }
  }
  ASSERT_GT(points.size(), 20u);
  geom::CurveProximity near(offset, 1e-7);
  for (const Eigen::Vector3d& point : points) {
    EXPECT_LT(near.closestPoint(point).distance, 1e-6) << point.transpose();
  }
}

// comp=controller runs the drawn curve: where no G39 goes between its
// chords, a curve.lap of the curve itself at the points chosen for the
// offsets' budget, the same moves after the legalisation.
TEST(OffsetCuts, CompensatedChordsAreALapOfTheDrawnCurve) {
  LoweringOptions host;
  host.expandCurveLaps = false;
  host.cutterCompensation = true;
  std::string text = polarPart("right");
  text.insert(text.find(" tolerance=0.01"), " comp=controller");
  Compiled compiled(text, host);
  ASSERT_TRUE(compiled.part);
  Function& function = compiled.part->function;
  EXPECT_TRUE(verifyFunction(function).empty());
  ASSERT_EQ(function.curves.size(), 1u);
  const CurveTableEntry& entry = function.curves.front();
  ASSERT_NE(entry.chosenParameters, nullptr);
  EXPECT_GT(entry.chosenParameters->size(), 150u);
  ToolPath before = interpret(function);
  Function expanded = function;
  ASSERT_TRUE(expandCurveLaps(expanded));
  EXPECT_TRUE(verifyFunction(expanded).empty());
  curve_lap_test::expectSameMoves(before, interpret(expanded));
  // The lap's points are the drawn curve's, r = 18 + 4 cos 2t cos 6t at t
  // (the other feeds are the start-up, lead and cancel moves).
  std::size_t onCurve = 0;
  for (const Eigen::Vector3d& point : levelFeeds(before)) {
    double t = std::atan2(point.y(), point.x());
    double r = 18 + 4 * std::cos(2 * t) * std::cos(6 * t);
    onCurve += std::abs(point.norm() - r) < 1e-9 ? 1 : 0;
  }
  EXPECT_GE(onCurve, entry.chosenParameters->size() - 1);
}

// With G39 at the corners (fanuc, m80), one lap per stretch between them,
// a corner.arc between the laps; the legalisation keeps the moves.
TEST(OffsetCuts, CompensatedChordsWithCornersAreALapPerStretch) {
  LoweringOptions controller;
  controller.expandCurveLaps = false;
  controller.cutterCompensation = true;
  controller.controllerLoops = true;
  controller.compensationCornerArcs = true;
  Compiled compiled("part p() {\n  tool 1 diameter=6 feed=400\n  safe z=5\n"
                    "  curve path(line((20, 0), (40, 0)), param(x = 20 + 20*cos(t), y = "
                    "15*sin(t), t = 0 .. pi), line((0, 0), (20, 0))) side=right comp=controller "
                    "tolerance=0.01\n}\n",
                    controller);
  ASSERT_TRUE(compiled.part);
  Function& function = compiled.part->function;
  EXPECT_TRUE(verifyFunction(function).empty());
  ASSERT_EQ(function.curves.size(), 3u); // two convex corners inside the path
  std::size_t corners = 0;
  for (const Instruction& instruction : function.instructions) {
    corners += instruction.opcode == Opcode::CornerArc ? 1 : 0;
  }
  EXPECT_EQ(corners, 2u);
  // Each stretch starts where the one before ends.
  EXPECT_EQ(function.curves[0].chosenParameters->back(),
            function.curves[1].chosenParameters->front());
  ToolPath before = interpret(function);
  Function expanded = function;
  ASSERT_TRUE(expandCurveLaps(expanded));
  EXPECT_TRUE(verifyFunction(expanded).empty());
  curve_lap_test::expectSameMoves(before, interpret(expanded));
}

// Heights at which compensation is switched on (the start-up line's).
std::vector<double> compensatedHeights(const ToolPath& path) {
  std::vector<double> heights;
  double z = 0;
  for (const MachineEvent& event : path.events) {
    if (event.kind == MachineEvent::Kind::Compensation && event.number != 0) {
      heights.push_back(z);
    }
    if (isMove(event)) {
      z = event.z;
    }
  }
  return heights;
}

// On a target that runs loops, a compensated cut's passes are one pass loop
// whose depth and step the program computes: edited, it cuts other heights.
TEST(OffsetCuts, CompensatedPassesAreTheControllersLoopOfEditableDepth) {
  LoweringOptions controller;
  controller.cutterCompensation = true;
  controller.controllerLoops = true;
  Compiled compiled("part p(depth = 5, stepdown = 2) {\n  tool 1 diameter=8 feed=300\n"
                    "  safe z=5\n  curve path(line((0, 0), (40, 0)), arc(center=(40, 10), "
                    "radius=10, from=-pi/2, to=pi/2), line((40, 20), (0, 20)), arc(center=(0, "
                    "10), radius=10, from=pi/2, to=3*pi/2)) side=right comp=controller lead=3 "
                    "sweep depth=depth step=stepdown\n}\n",
                    controller);
  ASSERT_TRUE(compiled.part);
  const Function& function = compiled.part->function;
  EXPECT_TRUE(verifyFunction(function).empty());
  std::vector<const Instruction*> passLoops;
  std::size_t compensations = 0;
  for (InstructionId id : function.body.instructions) { // the top level
    const Instruction& instruction = function.instructions[id];
    if (instruction.opcode == Opcode::Loop &&
        instruction.index == static_cast<std::uint32_t>(LoopRole::Passes)) {
      passLoops.push_back(&instruction);
    }
    compensations += instruction.opcode == Opcode::Compensation ? 1 : 0;
  }
  ASSERT_EQ(passLoops.size(), 1u);
  EXPECT_EQ(compensations, 0u); // on and off in the pass loop's body
  EXPECT_EQ(compensatedHeights(interpret(function)), (std::vector<double>{-2, -4, -5}));
  InterpreterOptions edited;
  edited.parameters = {{"depth", 7}, {"stepdown", 3}};
  EXPECT_EQ(compensatedHeights(interpret(function, edited)), (std::vector<double>{-3, -6, -7}));
}

TEST(OffsetCuts, ATooLargeToolIsRefusedAtTheCut) {
  Compiled compiled(
      polarPart("right").replace(polarPart("right").find("diameter=4"), 10, "diameter=5"), {});
  EXPECT_FALSE(compiled.part);
  EXPECT_TRUE(compiled.reported(frontend::DiagnosticKind::ToolTooLarge));
}

std::string circlePart(const char* side, const char* lead) {
  return std::string("part p() {\n  tool 1 diameter=6 feed=300\n  safe z=5\n"
                     "  curve arc(center=(0, 0), radius=20, from=0, to=2*pi) side=") +
         side + " lead=" + lead + "\n}\n";
}

TEST(OffsetCuts, LeadArcsJoinTheOffsetTangentiallyOnTheToolsSide) {
  // Outside the circle (side=right of a counter-clockwise circle): the
  // offset has radius 23 and starts at (23, 0) heading +y; the lead-in's
  // centre is 5 further out, at (28, 0).
  Compiled compiled(circlePart("right", "5"), {});
  ASSERT_TRUE(compiled.part);
  const auto* path =
      dynamic_cast<const geom::CompositeCurve*>(compiled.part->function.cuts.front().curve.get());
  ASSERT_NE(path, nullptr);
  ASSERT_EQ(path->pieceCount(), 3u); // lead-in, the offset, lead-out
  const auto* leadIn = dynamic_cast<const geom::ArcCurve*>(&path->piece(0));
  const auto* leadOut = dynamic_cast<const geom::ArcCurve*>(&path->piece(2));
  ASSERT_NE(leadIn, nullptr);
  ASSERT_NE(leadOut, nullptr);
  EXPECT_DOUBLE_EQ(leadIn->radius(), 5.0);
  EXPECT_NEAR((leadIn->centre() - Eigen::Vector2d(28, 0)).norm(), 0, 1e-12);
  EXPECT_NEAR(std::fabs(leadIn->sweep()), std::numbers::pi / 2, 1e-12);
  geom::ParameterRange in = leadIn->domain();
  EXPECT_NEAR((leadIn->point(in.t0) - Eigen::Vector3d(28, -5, 0)).norm(), 0, 1e-12);
  EXPECT_NEAR((leadIn->point(in.t1) - Eigen::Vector3d(23, 0, 0)).norm(), 0, 1e-12);
  geom::ParameterRange out = leadOut->domain();
  EXPECT_NEAR((leadOut->point(out.t1) - Eigen::Vector3d(28, 5, 0)).norm(), 0, 1e-12);
  // The program lowers the tool at the lead-in's start, and its arcs and
  // lap are the cut's: the first feed after the plunge is an arc.
  std::vector<MachineEvent> events = interpret(compiled.part->function).events;
  std::size_t plunge = 0;
  while (plunge < events.size() && events[plunge].kind != MachineEvent::Kind::Feed) {
    ++plunge;
  }
  ASSERT_LT(plunge + 1, events.size());
  EXPECT_NEAR(events[plunge].x, 28, 1e-9);
  EXPECT_NEAR(events[plunge].y, -5, 1e-9);
  EXPECT_EQ(events[plunge + 1].kind, MachineEvent::Kind::Arc);
}

TEST(OffsetCuts, ALeadArcThatCrossesThePartIsRefused) {
  // Inside the circle the offset has radius 17: an arc of radius 20 tangent
  // to it from inside runs outside it, into the part.
  Compiled wide(circlePart("left", "20"), {});
  EXPECT_FALSE(wide.part);
  EXPECT_TRUE(wide.reported(frontend::DiagnosticKind::ToolTooLarge));
  Compiled fits(circlePart("left", "16"), {});
  EXPECT_TRUE(fits.part);
}

} // namespace
} // namespace cncc::ir
