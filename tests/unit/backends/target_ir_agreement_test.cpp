// The IR a target prints is the program it prints: for every example and
// every target, the final IR run by the interpreter and the printed program
// run by the target's executor (the virtual controllers, LinuxCNC's own
// interpreter) make the same path within the printed rounding, not just
// within the part's tolerance.
#include "target_compile.h"

#include "cncc/backends/machine_setup.h"
#include "cncc/backends/verification.h"
#include "cncc/ir/tool_centre_path.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <set>

namespace cncc::backends {
namespace {

// How far apart the two runs' chords of one arc or spline block may be:
// each keeps within its sagitta of the curve (the interpreter's at
// executedArcSagitta, the controllers' at controllerArcSagitta or their
// sample tolerance), on top of the rounding the verification adds.
constexpr double chordAgreement = 1e-4;

struct AgreementCase {
  std::string example;
  std::string part; // empty: the example's only part
  std::string target;
};

void PrintTo(const AgreementCase& test, std::ostream* out) {
  *out << test.example << (test.part.empty() ? "" : " -p " + test.part) << " -t " << test.target;
}

std::string caseName(const ::testing::TestParamInfo<AgreementCase>& info) {
  const AgreementCase& test = info.param;
  std::string name = test.example.substr(0, test.example.find('.')) +
                     (test.part.empty() ? "" : "_" + test.part) + "_" + test.target;
  for (char& c : name) {
    c = std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  }
  return name;
}

std::vector<AgreementCase> agreementCases() {
  std::vector<AgreementCase> cases;
  const std::pair<const char*, const char*> examples[] = {
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
      {"compensation/compensated_contours.cdl", ""},
      {"family/flange.cdl", ""},
      {"family/plate.cdl", ""},
  };
  for (const auto& [example, part] : examples) {
    // comp=controller is for the targets with cutter compensation.
    bool compensated = std::string_view(example).starts_with("compensation/");
    for (const TargetInfo* target : allTargetInfos()) {
      if (target->execute != nullptr && (target->cutterCompensation || !compensated)) {
        cases.push_back({example, part, std::string(target->name)});
      }
    }
  }
  return cases;
}

double feedLength(const ExecutedPath& path) {
  double length = 0;
  Eigen::Vector3d at = path.start;
  for (const ExecutedMove& move : path.moves) {
    if (!move.rapid) {
      length += (move.end - at).norm();
    }
    at = move.end;
  }
  return length;
}

// The cuts the controller's cutter radius compensation offsets.
std::set<std::size_t> compensatedCuts(const ir::ToolPath& path) {
  std::set<std::size_t> cuts;
  std::optional<std::size_t> cut;
  for (const ir::MachineEvent& event : path.events) {
    if (event.kind == ir::MachineEvent::Kind::CutBegin) {
      cut = static_cast<std::size_t>(event.number);
    } else if (event.kind == ir::MachineEvent::Kind::Compensation && event.number != 0 && cut) {
      cuts.insert(*cut);
    }
  }
  return cuts;
}

class TargetIrAgreement : public ::testing::TestWithParam<AgreementCase> {};

TEST_P(TargetIrAgreement, TheFinalIrRunsAsThePrintedProgram) {
  const AgreementCase& test = GetParam();
  const TargetInfo& target = *findTargetInfo(test.target);
  std::unique_ptr<testing::CheckedExample> checked = testing::checkExample(test.example, test.part);
  ASSERT_NE(checked, nullptr);
  std::optional<testing::TargetCompilation> compiled =
      testing::compileThroughTarget(target, *checked);
  ASSERT_TRUE(compiled);
  ASSERT_TRUE(compiled->printed.problems.empty());

  // The interpreter's path of the final IR, where the tool's centre goes.
  ExecutedPath irPath = executedPathOfToolPath(ir::toolCentrePath(compiled->programmed));
  ExecutionRequest request;
  request.text = compiled->printed.text;
  request.toolRadii = compensationRadii(compiled->programmed, false);
  request.radiiOfTools = compensationRadii(compiled->programmed, true);
  request.lowerCaseComments =
      builtinMachineSetup(target.machineSetup).commentCase == CommentCase::AsWritten;
  ProgramExecution execution = target.execute(request);
  ASSERT_FALSE(execution.failure) << execution.failure->message;

  // Each feed move of the program lies on the IR's path...
  double allowance = chordAgreement + 2 * execution.increment;
  std::vector<double> allowances(compiled->lowered.function.cuts.size(), allowance);
  // ... but where the controller offsets it (comp=controller): its offset
  // of the printed points, whose rounding the offset turns with each chord,
  // keeps within the cut's tolerance of the IR's model of it.
  for (std::size_t cut : compensatedCuts(compiled->programmed)) {
    allowances[cut] += compiled->lowered.function.cuts[cut].tolerance;
  }
  StrayMoves stray = assignCuts(execution.path, irPath, allowances, allowance);
  EXPECT_EQ(stray.count, 0U) << stray.count << " moves off the IR's path, the farthest "
                             << stray.largestDistance << " at " << stray.where.transpose();
  // ... and none of the IR's path is missing from the program (a helix
  // started from a printed point a rounding off its radius is as much
  // longer or shorter in every turn: 5e-4 of its length in the inch bores).
  double irLength = feedLength(irPath);
  EXPECT_NEAR(feedLength(execution.path), irLength, 1e-3 * irLength);
}

INSTANTIATE_TEST_SUITE_P(Examples, TargetIrAgreement, ::testing::ValuesIn(agreementCases()),
                         caseName);

} // namespace
} // namespace cncc::backends
