// Arc output of the gcode target (arcs=true, --arcs): every example compiled
// with arcs on every cut, the printed program run by a G-code reader written
// here (G00/G01 lines, G02/G03 arcs sampled from their I J centres, the
// radius going linearly from the start's to the end's as a controller
// interpolates it), and each pass measured against its cut's true curve in
// both directions. The reference figure: the Archimedean spiral at 5 um in at
// most a third of its 90 minimal chords.
#include "cncc/backends/gcode_writer.h"
#include "cncc/frontend/sema.h"
#include "cncc/frontend/source_manager.h"
#include "cncc/geom/deviation.h"
#include "cncc/ir/interpreter.h"
#include "cncc/lowering/lowering.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <memory>
#include <numbers>
#include <sstream>
#include <string>

namespace cncc {
namespace {

struct CompiledPart {
  frontend::SourceManager sources;
  frontend::DiagnosticEngine diagnostics;
  std::optional<frontend::CheckedProgram> program;
  std::optional<ir::LoweredPart> lowered;
  ir::ToolPath path;
  std::string text;
};

// The example's part compiled for gcode with --arcs.
std::unique_ptr<CompiledPart> compileWithArcs(const std::string& name, const std::string& part) {
  auto result = std::make_unique<CompiledPart>();
  std::optional<frontend::FileId> file =
      result->sources.loadFile(std::string(CNCC_SOURCE_DIR) + "/examples/" + name);
  if (!file) {
    ADD_FAILURE() << "cannot read " << name;
    return nullptr;
  }
  frontend::CheckOptions options;
  options.importPaths = {CNCC_STDLIB_DIR};
  options.requirePart = true;
  options.partName = part;
  result->program = frontend::checkProgram(result->sources, *file, options, result->diagnostics);
  if (result->diagnostics.hasErrors() || result->program->selectedPart == nullptr) {
    ADD_FAILURE() << name << " does not check";
    return nullptr;
  }
  // As the gcode target lowers: the chords leave room for the printed rounding.
  backends::GcodeOptions gcode;
  ir::LoweringOptions lowering;
  lowering.coordinateIncrement = std::pow(10.0, -gcode.decimals);
  lowering.fittedArcs = true;
  lowering.arcsOnEveryCut = true;
  result->lowered = ir::lowerPartWithCuts(*result->program, *result->program->selectedPart,
                                          result->diagnostics, lowering);
  if (!result->lowered) {
    ADD_FAILURE() << name << " does not lower";
    return nullptr;
  }
  result->path = ir::interpret(result->lowered->function);
  result->text = backends::writeGcode(result->path, gcode);
  return result;
}

// One pass as the reader executed it: the XY points of its lap (arcs
// sampled densely), from the end of the plunge or ramp to the retract.
struct ExecutedPass {
  std::size_t cut = 0;
  std::vector<Eigen::Vector3d> points;
  std::size_t arcs = 0;
  std::size_t lines = 0; // G01 moves in the plane of the pass
  double largestSweep = 0;
};

std::map<char, double> wordsOf(const std::string& line) {
  std::map<char, double> words;
  std::istringstream stream(line.substr(0, line.find('(')));
  char letter = 0;
  while (stream >> letter) {
    double value = 0;
    stream >> value;
    words[letter] = value;
  }
  return words;
}

// Points along G02/G03 from `from` to `to` around `centre`, close enough
// (sagitta 1e-6 mm) that the polyline is the arc for the measurement.
void sampleArc(const Eigen::Vector2d& from, const Eigen::Vector2d& to,
               const Eigen::Vector2d& centre, bool clockwise, ExecutedPass& pass) {
  Eigen::Vector2d a = from - centre;
  Eigen::Vector2d b = to - centre;
  double startAngle = std::atan2(a.y(), a.x());
  double endAngle = std::atan2(b.y(), b.x());
  double sweep = endAngle - startAngle;
  while (clockwise ? sweep >= 0 : sweep <= 0) {
    sweep += clockwise ? -2 * std::numbers::pi : 2 * std::numbers::pi;
  }
  double radius = std::max(a.norm(), b.norm());
  double step = 2 * std::acos(1 - std::min(1.0, 1e-6 / radius));
  int count = std::max(2, static_cast<int>(std::ceil(std::fabs(sweep) / step)));
  for (int k = 1; k <= count; ++k) {
    double share = static_cast<double>(k) / count;
    double r = a.norm() + (b.norm() - a.norm()) * share;
    double angle = startAngle + sweep * share;
    pass.points.emplace_back(centre.x() + r * std::cos(angle), centre.y() + r * std::sin(angle), 0);
  }
  pass.largestSweep = std::max(pass.largestSweep, std::fabs(sweep));
  ++pass.arcs;
}

// Runs the program. A full-line comment of the program is one of the tool
// path's Comment events, in order: the cut of the latest CutBegin before it
// says which cut the following moves belong to.
std::vector<ExecutedPass> executePasses(const CompiledPart& part);

// The deviation of a pass from its cut's curve, the pass put in the curve's
// plane (the reader reads the pass depth, the curve lies at its own z).
double passDeviation(const ExecutedPass& pass, const ir::CutGeometry& cut) {
  double z = cut.curve->point(cut.curve->domain().t0).z();
  std::vector<Eigen::Vector3d> points = pass.points;
  for (Eigen::Vector3d& point : points) {
    point.z() = z;
  }
  return geom::measureDeviation(points, *cut.curve, {cut.tolerance * 1e-3}).maxDeviation();
}

std::vector<ExecutedPass> executePasses(const CompiledPart& part) {
  std::vector<std::optional<std::size_t>> commentCuts;
  std::optional<std::size_t> cut;
  for (const ir::MachineEvent& event : part.path.events) {
    if (event.kind == ir::MachineEvent::Kind::CutBegin) {
      cut = static_cast<std::size_t>(event.number);
    } else if (event.kind == ir::MachineEvent::Kind::Comment) {
      commentCuts.push_back(cut);
    }
  }
  std::vector<ExecutedPass> passes;
  std::istringstream lines(part.text);
  std::string line;
  int lineNumber = 0;
  std::size_t comments = 0;
  std::optional<std::size_t> current;
  Eigen::Vector3d position(0, 0, 0);
  bool inPass = false;
  while (std::getline(lines, line)) {
    if (++lineNumber <= 3) {
      continue; // %, O1 and the header comment
    }
    if (line.rfind("(", 0) == 0) {
      current = comments < commentCuts.size() ? commentCuts[comments] : std::nullopt;
      ++comments;
      continue;
    }
    std::map<char, double> words = wordsOf(line);
    if (!words.count('G')) {
      continue;
    }
    int motion = static_cast<int>(words['G']);
    Eigen::Vector3d target = position;
    for (int axis = 0; axis < 3; ++axis) {
      if (auto found = words.find(static_cast<char>('X' + axis)); found != words.end()) {
        target[axis] = found->second;
      }
    }
    if (motion == 0) {
      inPass = false;
    } else if (motion >= 1 && motion <= 3 && current) {
      if (!inPass) {
        passes.push_back({*current, {Eigen::Vector3d(position.x(), position.y(), 0)}});
        inPass = true;
      }
      ExecutedPass& pass = passes.back();
      if (motion == 1 && target.z() != position.z()) {
        // The plunge or a ramp chord: the lap starts after the last of them.
        pass.points = {Eigen::Vector3d(target.x(), target.y(), 0)};
      } else if (motion == 1) {
        pass.points.emplace_back(target.x(), target.y(), 0);
        ++pass.lines;
      } else {
        Eigen::Vector2d centre = position.head<2>() + Eigen::Vector2d(words['I'], words['J']);
        sampleArc(position.head<2>(), target.head<2>(), centre, motion == 2, pass);
      }
    }
    position = target;
  }
  return passes;
}

// What every example promises with arcs: each pass of each fitted cut
// within the cut's tolerance of its true curve, arcs of at most 180 degrees.
void expectArcsWithinTolerance(const std::string& example, const std::string& partName = {}) {
  SCOPED_TRACE(example + " " + partName);
  std::unique_ptr<CompiledPart> part = compileWithArcs(example, partName);
  ASSERT_TRUE(part);
  std::vector<ExecutedPass> passes = executePasses(*part);
  std::size_t measured = 0;
  std::vector<const ExecutedPass*> firstPass(part->lowered->function.cuts.size(), nullptr);
  for (const ExecutedPass& pass : passes) {
    const ir::CutGeometry& cut = part->lowered->function.cuts.at(pass.cut);
    bool fitted = cut.arcMoves == ir::CutArcs::Fitted;
    if (cut.arcMoves == ir::CutArcs::None) {
      EXPECT_EQ(pass.arcs, 0u) << "cut " << pass.cut << " has no fit but arcs";
      continue;
    }
    // Every pass repeats the first one's moves at its own depth: measured once.
    if (firstPass[pass.cut] != nullptr) {
      EXPECT_EQ(pass.points, firstPass[pass.cut]->points) << "cut " << pass.cut;
      continue;
    }
    firstPass[pass.cut] = &pass;
    EXPECT_LE(passDeviation(pass, cut), cut.tolerance) << "cut " << pass.cut;
    // Fitted arcs turn at most half a turn; an arc of the part, a full one.
    EXPECT_LE(pass.largestSweep, (fitted ? 1 : 2) * std::numbers::pi + 1e-9);
    EXPECT_GT(pass.arcs, 0u);
    ++measured;
  }
  EXPECT_GT(measured, 0u) << "no pass was printed with arcs";
}

TEST(ArcsOutput, SProfileWithinTolerance) {
  expectArcsWithinTolerance("s_profile.cdl");
}

TEST(ArcsOutput, ArchimedeanSpiralWithinTolerance) {
  expectArcsWithinTolerance("archimedean_spiral.cdl");
}

TEST(ArcsOutput, PolarContourWithinTolerance) {
  expectArcsWithinTolerance("polar_contour.cdl");
}

TEST(ArcsOutput, RosettePlateWithinTolerance) {
  expectArcsWithinTolerance("rosette_plate.cdl");
}

TEST(ArcsOutput, CamProfileWithinTolerance) {
  expectArcsWithinTolerance("cam_profile.cdl");
}

// The bores are arcs with z and the floors arcs: printed as they are, one
// helical G03 per turn (6 turns of 1.5 mm down to 9 mm) and one G03 per
// floor circle, with nothing fitted and no chords.
TEST(ArcsOutput, HelixBoreCutsItsArcsNatively) {
  for (const char* partName : {"bore_plate_mm", "bore_plate_inch"}) {
    std::unique_ptr<CompiledPart> part = compileWithArcs("helix_bore.cdl", partName);
    ASSERT_TRUE(part);
    EXPECT_TRUE(part->diagnostics.diagnostics().empty()); // no arcs-as-chords
    std::vector<ExecutedPass> passes = executePasses(*part);
    ASSERT_EQ(passes.size(), 6u) << partName; // a bore and a floor per hole
    for (const ExecutedPass& pass : passes) {
      EXPECT_EQ(part->lowered->function.cuts.at(pass.cut).arcMoves, ir::CutArcs::Native);
      EXPECT_EQ(pass.lines, 0u) << partName << " cut " << pass.cut;
      EXPECT_EQ(pass.arcs, pass.cut % 2 == 0 ? 6u : 1u) << partName << " cut " << pass.cut;
    }
  }
}

// REFERENCE-CASES.md, case 2: 90 chords at 5 um; the arcs must take at most 30
// blocks (arcs and the lines between them) for the same tolerance.
TEST(ArcsOutput, SpiralInAThirdOfTheMinimalChords) {
  std::unique_ptr<CompiledPart> part = compileWithArcs("archimedean_spiral.cdl", "");
  ASSERT_TRUE(part);
  std::vector<ExecutedPass> passes = executePasses(*part);
  ASSERT_EQ(passes.size(), 1u);
  std::size_t blocks = passes[0].arcs + passes[0].lines;
  RecordProperty("blocks", static_cast<int>(blocks));
  EXPECT_LE(blocks, 30u);
  EXPECT_GE(passes[0].arcs, 2u);
  EXPECT_LE(passDeviation(passes[0], part->lowered->function.cuts[0]), 0.005);
}

// The fitted arcs are IR ops: every pass of the S profile (depth 3, step 1)
// has the same move.arc ops at its own depth, and the printed program has one
// G02/G03 per arc the IR runs.
TEST(ArcsOutput, FittedArcsAreMovesOfTheIr) {
  std::unique_ptr<CompiledPart> part = compileWithArcs("s_profile.cdl", "");
  ASSERT_TRUE(part);
  ASSERT_EQ(part->lowered->function.cuts.at(0).arcMoves, ir::CutArcs::Fitted);
  std::map<double, std::size_t> arcsAtDepth;
  for (const ir::MachineEvent& event : part->path.events) {
    if (event.kind == ir::MachineEvent::Kind::Arc) {
      ++arcsAtDepth[event.z];
    }
  }
  ASSERT_EQ(arcsAtDepth.size(), 3u);
  EXPECT_EQ(arcsAtDepth.begin()->first, -3);
  EXPECT_EQ(arcsAtDepth.begin()->second, arcsAtDepth.rbegin()->second);
  std::size_t printed = 0;
  std::istringstream lines(part->text);
  for (std::string line; std::getline(lines, line);) {
    printed += line.starts_with("G02") || line.starts_with("G03");
  }
  EXPECT_EQ(printed, 3 * arcsAtDepth.begin()->second);
}

// Every number of a fitted arc is on the printed grid (4 decimals) already,
// the centre offset from the start as printed: the IR is the program.
TEST(ArcsOutput, FittedArcsAreOnThePrintedGrid) {
  std::unique_ptr<CompiledPart> part = compileWithArcs("archimedean_spiral.cdl", "");
  ASSERT_TRUE(part);
  auto onGrid = [](double value) {
    return std::fabs(value * 1e4 - std::round(value * 1e4)) < 1e-6;
  };
  Eigen::Vector2d at(0, 0);
  std::size_t arcs = 0;
  for (const ir::MachineEvent& event : part->path.events) {
    if (event.kind == ir::MachineEvent::Kind::Arc) {
      EXPECT_TRUE(onGrid(event.x) && onGrid(event.y)) << event.x << " " << event.y;
      EXPECT_TRUE(onGrid(event.centreX - at.x()) && onGrid(event.centreY - at.y()));
      ++arcs;
    }
    if (event.kind == ir::MachineEvent::Kind::Feed || event.kind == ir::MachineEvent::Kind::Rapid ||
        event.kind == ir::MachineEvent::Kind::Arc) {
      at = {event.x, event.y};
    }
  }
  EXPECT_GT(arcs, 2u);
}

} // namespace
} // namespace cncc
