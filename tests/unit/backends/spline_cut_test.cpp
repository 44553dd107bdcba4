// Spline cuts on the sinumerik target are move.spline ops: interpreting the
// IR after the lowering gives the path the printed program executes in the
// virtual Sinumerik, spline by spline.
#include "sinumerik_test_parts.h"

#include "cncc/geom/deviation.h"
#include "cncc/ir/interpreter.h"
#include "cncc/ir/spline_move.h"

#include <gtest/gtest.h>

#include <sstream>

namespace cncc::backends {
namespace {

using testing::compileForSinumerik;
using testing::exampleText;
using testing::replaced;

// The points of each move.spline of the interpreted IR, from where it starts.
std::vector<std::vector<Eigen::Vector3d>> irSplines(const ir::ToolPath& path) {
  std::vector<std::vector<Eigen::Vector3d>> splines;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  for (const ir::MachineEvent& event : path.events) {
    bool motion = event.kind == ir::MachineEvent::Kind::Rapid ||
                  event.kind == ir::MachineEvent::Kind::Feed ||
                  event.kind == ir::MachineEvent::Kind::Arc;
    if (!motion) {
      continue;
    }
    if (event.splineStart) {
      splines.push_back({position});
    }
    position = {event.x, event.y, event.z};
    if (event.splineTable != 0) {
      splines.back().push_back(position);
    }
  }
  return splines;
}

void expectTheIrCutsWhatTheControllerCuts(const std::string& source,
                                          SinumerikOptions options = {}) {
  auto part = compileForSinumerik(source, options);
  ASSERT_TRUE(part);
  sinumerik::SinumerikRun run = sinumerik::runSinumerikProgram(part->output.text);
  ASSERT_FALSE(run.error) << run.error->what();
  std::vector<std::vector<Eigen::Vector3d>> splines = irSplines(part->path);
  ASSERT_EQ(splines.size(), run.splines.size());
  ASSERT_FALSE(splines.empty());
  for (std::size_t k = 0; k < splines.size(); ++k) {
    ASSERT_GT(splines[k].size(), 10u);
    // The IR's chords within 1e-5 of its spline, its start within the
    // printed rounding of the controller's (after a ramp, whose chords are
    // not on the printed grid).
    double deviation =
        geom::measureDeviation(splines[k], *run.splines[k].curve, {1e-7}).maxDeviation();
    EXPECT_LT(deviation, 2e-5) << "spline " << k;
  }
}

TEST(SplineCut, TheIrHoldsTheSplinesTheControllerCuts) {
  std::string sProfile = exampleText("s_profile.cdl");
  expectTheIrCutsWhatTheControllerCuts(
      replaced(sProfile, "tolerance=0.01", "tolerance=0.01 method=bspline"));
  expectTheIrCutsWhatTheControllerCuts(replaced(
      replaced(sProfile, "tolerance=0.01", "tolerance=0.01 method=bspline"), "w6 = 3", "w6 = 5"));
  for (const char* method : {"cspline", "aspline", "bspline"}) {
    SCOPED_TRACE(method);
    expectTheIrCutsWhatTheControllerCuts(replaced(exampleText("polar_contour.cdl"),
                                                  "tolerance=0.01",
                                                  std::string("tolerance=0.01 method=") + method));
  }
  SinumerikOptions options;
  options.transitions = SinumerikTransitions::Auto;
  options.subprograms = true;
  expectTheIrCutsWhatTheControllerCuts(
      replaced(sProfile, "tolerance=0.01", "tolerance=0.01 method=aspline"), options);
}

// The lowering puts the spline blocks in a table; its comment says how.
TEST(SplineCut, IrHasTheBlocksAndTheirComment) {
  auto part = compileForSinumerik(
      replaced(exampleText("s_profile.cdl"), "tolerance=0.01", "tolerance=0.01 method=bspline"));
  ASSERT_TRUE(part);
  std::size_t moves = 0;
  for (const ir::Instruction& instruction : part->function.instructions) {
    if (instruction.opcode == ir::Opcode::Spline) {
      ++moves;
      std::optional<ir::SplineBlockData> blocks =
          ir::readSplineMoveTable(part->function.tables[instruction.index]);
      ASSERT_TRUE(blocks);
      EXPECT_EQ(blocks->points.size(), 6u);
      EXPECT_EQ(blocks->weights[4], 3); // w6
    }
  }
  EXPECT_EQ(moves, 1u); // in the sweep's pass loop, which runs it once a pass
  std::size_t passes = 0;
  for (const ir::MachineEvent& event : ir::interpret(part->function).events) {
    passes +=
        event.kind == ir::MachineEvent::Kind::Comment && event.text.starts_with("pass at depth");
  }
  EXPECT_EQ(passes, 3u);
}

} // namespace
} // namespace cncc::backends
