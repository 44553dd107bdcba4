// The virtual controller's LinuxCNC dialect against LinuxCNC's own
// interpreter, on every LinuxCNC program the tests have: each example part
// compiled as `-t linuxcnc` compiles it, the programs of the LinuxCNC
// goldens (their expected output), and the shop-style programs of
// tests/golden/sim (linuxcnc_*.ngc). Both run the same text; their moves
// must be the same one by one: each traverse, feed and arc (its end, centre
// and turns), and each feed rate. Twice:
// - against the interpreter as a library (the `gcode` Python module,
//   backends/linuxcnc/src/linuxcnc_canon_moves.py), which hands every value over as a double: a
//   coordinate agrees within 1e-6 mm;
// - against the `rs274` program, which `cncc verify -t linuxcnc` runs: it
//   prints four decimals, so a coordinate agrees within half a unit of the
//   fourth decimal of what it printed.
#include "linuxcnc_rs274.h"

#include "cncc/backends/linuxcnc_controller.h"
#include "cncc/backends/linuxcnc_program.h"
#include "cncc/backends/macro_program.h"
#include "cncc/frontend/sema.h"
#include "cncc/frontend/source_manager.h"
#include "cncc/ir/passes.h"
#include "cncc/ir/verifier.h"
#include "cncc/lowering/lowering.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <string>
#include <vector>

namespace cncc::backends::sim {
namespace {

// Half a unit of rs274's fourth decimal, and the double rounding of both
// (in the program's units).
constexpr double printPrecision = 0.5e-4 + 1e-9;
// The agreement with the interpreter's own doubles, in millimetres.
constexpr double moduleAgreementMm = 1e-6;

struct ProgramCase {
  std::string name;
  std::string file; // relative to the source tree
  std::string part; // examples: the part to compile
};

void PrintTo(const ProgramCase& test, std::ostream* out) {
  *out << test.file << (test.part.empty() ? "" : " -p " + test.part);
}

std::string readFile(const std::filesystem::path& path) {
  std::ifstream file(path, std::ios::binary);
  std::ostringstream text;
  text << file.rdbuf();
  return text.str();
}

std::optional<std::string> compileExample(const ProgramCase& test) {
  frontend::SourceManager sources;
  frontend::DiagnosticEngine diagnostics;
  std::optional<frontend::FileId> id =
      sources.loadFile(std::string(CNCC_SOURCE_DIR) + "/" + test.file);
  if (!id) {
    ADD_FAILURE() << "cannot read " << test.file;
    return std::nullopt;
  }
  frontend::CheckOptions checking;
  checking.importPaths = {CNCC_STDLIB_DIR};
  checking.requirePart = true;
  checking.partName = test.part;
  std::optional<frontend::CheckedProgram> program =
      frontend::checkProgram(sources, *id, checking, diagnostics);
  if (diagnostics.hasErrors() || !program || program->selectedPart == nullptr) {
    ADD_FAILURE() << test.file << " does not check";
    return std::nullopt;
  }
  const frontend::PartItem& part = *program->selectedPart;
  bool inches = ir::partUnits(part) == ir::PartUnits::Inches;
  ir::LoweringOptions lowering; // as the linuxcnc target lowers
  lowering.controllerLoops = true;
  lowering.coordinateIncrement = inches ? 1e-6 : 1e-5;
  lowering.fittedArcs = true;
  lowering.passesBeforePrinting = macroPassesBeforePrinting();
  std::optional<ir::LoweredPart> lowered =
      ir::lowerPartWithCuts(*program, part, diagnostics, lowering);
  if (!lowered) {
    ADD_FAILURE() << test.file << " does not lower";
    return std::nullopt;
  }
  ir::runDefaultPipeline(lowered->function);
  EXPECT_TRUE(ir::runPasses(lowered->function, lowering.passesBeforePrinting, {}));
  EXPECT_TRUE(ir::verifyFunction(lowered->function).empty());
  LinuxcncProgramOptions printing;
  printing.sourceName = std::filesystem::path(test.file).filename().string();
  printing.partName = test.part;
  printing.inches = inches;
  printing.blendTolerance = linuxcncBlendTolerance(lowered->function.cuts);
  LinuxcncProgram printed = writeLinuxcncProgram(lowered->function, printing);
  if (!printed.errors.empty()) {
    ADD_FAILURE() << printed.errors.front();
    return std::nullopt;
  }
  return printed.text;
}

// A golden's program: its expected standard output. A callable one (a sub
// and M2) runs with the call its header gives (`; call: o<part> call [..]`)
// before the M2, so that both interpreters run the sub.
std::string goldenProgram(const std::string& expected) {
  std::string begin = "--- stdout ---\n";
  std::size_t from = expected.find(begin) + begin.size();
  std::string program = expected.substr(from, expected.find("--- stderr ---") - from);
  std::string header = "; call: ";
  std::size_t call = program.find(header);
  std::size_t end = program.rfind("\nM2\n");
  if (call != std::string::npos && end != std::string::npos) {
    std::size_t callEnd = program.find('\n', call);
    std::string text = program.substr(call + header.size(), callEnd - call - header.size());
    program.insert(end + 1, text + "\n");
  }
  return program;
}

std::optional<std::string> programOf(const ProgramCase& test) {
  std::filesystem::path path = std::filesystem::path(CNCC_SOURCE_DIR) / test.file;
  if (path.extension() == ".cdl") {
    return compileExample(test);
  }
  std::string text = readFile(path);
  return path.extension() == ".expected" ? goldenProgram(text) : text;
}

// One canonical call: `   12 N..... STRAIGHT_FEED(1.0000, 2.0000, ...)`.
struct CanonCall {
  std::string name;
  std::vector<double> numbers;
};

std::vector<CanonCall> canonCalls(const std::string& canon) {
  std::vector<CanonCall> calls;
  std::istringstream lines(canon);
  std::string line;
  while (std::getline(lines, line)) {
    std::size_t open = line.find('(');
    std::size_t name = line.rfind(' ', open);
    if (open == std::string::npos || name == std::string::npos) {
      continue;
    }
    CanonCall call{line.substr(name + 1, open - name - 1), {}};
    std::string list = line.substr(open + 1, line.rfind(')') - open - 1);
    std::replace(list.begin(), list.end(), ',', ' ');
    std::istringstream numbers(list);
    double number = 0;
    while (numbers >> number) {
      call.numbers.push_back(number);
    }
    calls.push_back(std::move(call));
  }
  return calls;
}

struct Comparison {
  std::size_t moves = 0;
  double largestDifference = 0; // program units
};

// Compares the moves one by one, each coordinate and feed within
// `tolerance` (in the program's units); the interpreter's traverse to the machine's Z0
// (G53 G0 Z0, rs274ReferenceHeight above the work) is not in the virtual
// controller's path, which stays in work coordinates.
Comparison compareMoves(const LinuxcncRun& run, const std::string& canon, double tolerance,
                        const char* reference) {
  std::vector<LinuxcncMove> moves;
  std::copy_if(
      run.moves.begin(), run.moves.end(), std::back_inserter(moves), [](const LinuxcncMove& move) {
        return move.kind == LinuxcncMove::Kind::Traverse || move.kind == LinuxcncMove::Kind::Feed ||
               move.kind == LinuxcncMove::Kind::Arc;
      });
  double machineZero = rs274ReferenceHeight / (run.inches ? 25.4 : 1.0);
  Comparison comparison;
  double feed = 0;
  std::size_t next = 0;
  auto agree = [&](double ours, double theirs, const char* what) {
    double difference = std::abs(ours - theirs);
    comparison.largestDifference = std::max(comparison.largestDifference, difference);
    EXPECT_LE(difference, tolerance)
        << what << " of move " << next << " (line " << moves[next].line
        << "): " << std::setprecision(17) << ours << " here, " << theirs << " by " << reference;
  };
  for (const CanonCall& call : canonCalls(canon)) {
    if (call.name == "SET_FEED_RATE" && !call.numbers.empty()) {
      feed = call.numbers[0];
    }
    bool straight = call.name == "STRAIGHT_TRAVERSE" || call.name == "STRAIGHT_FEED";
    if (!straight && call.name != "ARC_FEED") {
      continue;
    }
    if (call.name == "STRAIGHT_TRAVERSE" && std::abs(call.numbers.at(2) - machineZero) < 1e-3) {
      continue;
    }
    if (next >= moves.size()) {
      ADD_FAILURE() << reference
                    << " moves on after the virtual controller's last move: " << call.name;
      return comparison;
    }
    const LinuxcncMove& move = moves[next];
    LinuxcncMove::Kind kind = call.name == "STRAIGHT_TRAVERSE" ? LinuxcncMove::Kind::Traverse
                              : call.name == "STRAIGHT_FEED"   ? LinuxcncMove::Kind::Feed
                                                               : LinuxcncMove::Kind::Arc;
    EXPECT_EQ(move.kind, kind) << "move " << next << " (line " << move.line << ")";
    if (kind == LinuxcncMove::Kind::Arc) {
      agree(move.end.x, call.numbers.at(0), "the end X");
      agree(move.end.y, call.numbers.at(1), "the end Y");
      agree(move.centre.x, call.numbers.at(2), "the centre X");
      agree(move.centre.y, call.numbers.at(3), "the centre Y");
      EXPECT_EQ(move.turns, static_cast<int>(call.numbers.at(4))) << "line " << move.line;
      agree(move.end.z, call.numbers.at(5), "the end Z");
    } else {
      agree(move.end.x, call.numbers.at(0), "X");
      agree(move.end.y, call.numbers.at(1), "Y");
      agree(move.end.z, call.numbers.at(2), "Z");
    }
    if (kind != LinuxcncMove::Kind::Traverse) {
      agree(move.feed, feed, "the feed");
    }
    ++next;
  }
  EXPECT_EQ(next, moves.size()) << "the virtual controller moves on after the last move by "
                                << reference;
  comparison.moves = next;
  return comparison;
}

class LinuxcncAgainstRs274 : public ::testing::TestWithParam<ProgramCase> {};

TEST_P(LinuxcncAgainstRs274, SameMovesToRs274sPrecision) {
  CNCC_FIND_RS274(rs274);
  std::optional<std::string> program = programOf(GetParam());
  ASSERT_TRUE(program);
  LinuxcncRun run = runLinuxcncProgram(*program);
  ASSERT_FALSE(run.error) << run.error->line() << ": " << run.error->what() << "\n" << *program;
  testing::Rs274Run reference = testing::runRs274(*rs274, *program, rs274ToolTable(*program));
  ASSERT_EQ(reference.exitCode, 0) << reference.errors;
  Comparison comparison = compareMoves(run, reference.canon, printPrecision, "rs274");
  EXPECT_GT(comparison.moves, 0u);
  std::cout << "[ moves    ] " << comparison.moves << " moves, largest difference "
            << comparison.largestDifference * (run.inches ? 25.4 : 1.0) << " mm\n";
}

class LinuxcncAgainstGcodeModule : public ::testing::TestWithParam<ProgramCase> {};

TEST_P(LinuxcncAgainstGcodeModule, SameMovesWithin1e6Millimetre) {
  std::optional<std::string> program = programOf(GetParam());
  ASSERT_TRUE(program);
  LinuxcncRun run = runLinuxcncProgram(*program);
  ASSERT_FALSE(run.error) << run.error->line() << ": " << run.error->what() << "\n" << *program;
  testing::GcodeModuleRun reference =
      testing::runGcodeModule(*program, rs274ToolTable(*program), run.inches);
  // The README's set-up installs linuxcnc-uspace, which has the module.
  ASSERT_FALSE(reference.missing)
      << "LinuxCNC's gcode Python module (Debian package linuxcnc-uspace) is not installed: "
      << reference.errors;
  ASSERT_EQ(reference.exitCode, 0) << reference.errors;
  double millimetre = run.inches ? 1 / 25.4 : 1.0;
  Comparison comparison =
      compareMoves(run, reference.canon, moduleAgreementMm * millimetre, "LinuxCNC's interpreter");
  EXPECT_GT(comparison.moves, 0u);
  std::cout << "[ moves    ] " << comparison.moves << " moves, largest difference "
            << comparison.largestDifference / millimetre << " mm\n";
}

// The comparison above is only as fine as what the script prints: a value
// with more digits than rs274's four decimals comes back whole, in either
// unit, and a G20 program's lengths in inches.
TEST(LinuxcncGcodeModule, PrintsTheInterpretersDoublesWhole) {
  for (bool inches : {false, true}) {
    std::string program = std::string(inches ? "G20" : "G21") +
                          " G90\nG0 X1.2345678901234 Y-0.000123456789 Z5\nG1 X2 F123.456789\nM2\n";
    testing::GcodeModuleRun run = testing::runGcodeModule(program, "", inches);
    ASSERT_FALSE(run.missing) << "LinuxCNC's gcode Python module is not installed: " << run.errors;
    ASSERT_EQ(run.exitCode, 0) << run.errors;
    std::vector<CanonCall> calls = canonCalls(run.canon);
    auto traverse = std::find_if(calls.begin(), calls.end(), [](const CanonCall& call) {
      return call.name == "STRAIGHT_TRAVERSE";
    });
    ASSERT_NE(traverse, calls.end()) << run.canon;
    EXPECT_NEAR(traverse->numbers.at(0), 1.2345678901234, 1e-13) << run.canon;
    EXPECT_NEAR(traverse->numbers.at(1), -0.000123456789, 1e-13) << run.canon;
    EXPECT_NEAR(traverse->numbers.at(2), 5, 1e-13) << run.canon;
    auto feed = std::find_if(calls.begin(), calls.end(), [](const CanonCall& call) {
      return call.name == "SET_FEED_RATE" && call.numbers.at(0) > 0;
    });
    ASSERT_NE(feed, calls.end()) << run.canon;
    EXPECT_NEAR(feed->numbers.at(0), 123.456789, 1e-10) << run.canon;
  }
}

// An error of the interpreter's is a failed run with its line, not a short
// list of moves.
TEST(LinuxcncGcodeModule, ReportsTheInterpretersError) {
  testing::GcodeModuleRun run =
      testing::runGcodeModule("G21 G90\nG0 X0 Y0\nG2 X10 Y0 I3 J0 F100\nM2\n", "", false);
  ASSERT_FALSE(run.missing) << "LinuxCNC's gcode Python module is not installed: " << run.errors;
  EXPECT_EQ(run.exitCode, 1);
  EXPECT_NE(run.errors.find("line 3"), std::string::npos) << run.errors;
  EXPECT_NE(run.errors.find("radius"), std::string::npos) << run.errors;
}

std::vector<ProgramCase> programCases() {
  std::vector<ProgramCase> cases;
  const std::pair<const char*, const char*> examples[] = {
      {"archimedean_spiral.cdl", "archimedean_spiral"},
      {"bolt_circle.cdl", "bolt_circle"},
      {"cam_profile.cdl", "cam_profile"},
      {"helix_bore.cdl", "bore_plate_mm"},
      {"helix_bore.cdl", "bore_plate_inch"},
      {"offset_contours.cdl", "offset_contours"},
      {"polar_contour.cdl", "polar_contour"},
      {"rosette_plate.cdl", "rosette_plate"},
      {"s_profile.cdl", "s_profile"},
      {"worn_cutter.cdl", "worn_cutter"}};
  for (const auto& [file, part] : examples) {
    cases.push_back({std::string("example_") + part, std::string("examples/") + file, part});
  }
  std::filesystem::path root(CNCC_SOURCE_DIR);
  std::vector<std::filesystem::path> files;
  for (const char* folder : {"tests/golden/linuxcnc", "tests/golden/sim"}) {
    for (const auto& entry : std::filesystem::directory_iterator(root / folder)) {
      std::string name = entry.path().filename().string();
      bool golden = entry.path().extension() == ".expected" &&
                    std::string_view(folder).ends_with("linuxcnc") &&
                    readFile(entry.path()).starts_with("exit code: 0");
      bool shop = name.starts_with("linuxcnc_") && entry.path().extension() == ".ngc" &&
                  name.find("alarm") == std::string::npos;
      if (golden || shop) {
        files.push_back(entry.path());
      }
    }
  }
  std::sort(files.begin(), files.end());
  for (const std::filesystem::path& file : files) {
    std::string name = (file.extension() == ".ngc" ? "shop_" : "golden_") + file.stem().string();
    cases.push_back({name, std::filesystem::relative(file, root).string(), ""});
  }
  return cases;
}

std::string caseName(const ::testing::TestParamInfo<ProgramCase>& info) {
  return info.param.name;
}

INSTANTIATE_TEST_SUITE_P(Programs, LinuxcncAgainstRs274, ::testing::ValuesIn(programCases()),
                         caseName);
INSTANTIATE_TEST_SUITE_P(Programs, LinuxcncAgainstGcodeModule, ::testing::ValuesIn(programCases()),
                         caseName);

// The list above is every example part: a new part in examples/ must join it.
TEST(LinuxcncAgainstRs274Cases, CoverEveryExamplePart) {
  std::size_t parts = 0;
  for (const auto& entry :
       std::filesystem::directory_iterator(std::filesystem::path(CNCC_SOURCE_DIR) / "examples")) {
    if (entry.path().extension() != ".cdl") {
      continue;
    }
    std::istringstream lines(readFile(entry.path()));
    std::string line;
    while (std::getline(lines, line)) {
      parts += line.starts_with("part ") ? 1 : 0;
    }
  }
  std::size_t examples = 0;
  for (const ProgramCase& test : programCases()) {
    examples += test.file.starts_with("examples/") ? 1 : 0;
  }
  EXPECT_EQ(examples, parts);
}

} // namespace
} // namespace cncc::backends::sim
