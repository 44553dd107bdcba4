#include "cncc/backends/machine_file.h"
#include "cncc/backends/machine_setup.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace cncc::backends {
namespace {

struct Read {
  std::optional<MachineDescription> machine;
  std::vector<MachineDiagnostic> diagnostics;
};

Read readText(const std::string& text) {
  Read result;
  result.machine = readMachineText(text, "test.toml", result.diagnostics);
  return result;
}

// The one diagnostic of a bad file.
MachineDiagnostic onlyDiagnostic(const std::string& text) {
  Read result = readText(text);
  EXPECT_FALSE(result.machine);
  EXPECT_EQ(result.diagnostics.size(), 1u);
  return result.diagnostics.empty() ? MachineDiagnostic{} : result.diagnostics.front();
}

void expectDiagnostic(const std::string& text, int line, int column, const std::string& code) {
  MachineDiagnostic diagnostic = onlyDiagnostic(text);
  EXPECT_EQ(diagnostic.line, line) << diagnostic.message;
  EXPECT_EQ(diagnostic.column, column) << diagnostic.message;
  EXPECT_EQ(diagnostic.code, code) << diagnostic.message;
}

void expectEqualSetups(const MachineSetup& a, const MachineSetup& b) {
  EXPECT_EQ(a.dialect, b.dialect);
  EXPECT_EQ(a.lengthOffset, b.lengthOffset);
  EXPECT_EQ(a.toolEdge, b.toolEdge);
  EXPECT_EQ(a.workOffset, b.workOffset);
  EXPECT_EQ(a.extendedWorkOffset, b.extendedWorkOffset);
  EXPECT_EQ(a.maximumExtendedWorkOffset, b.maximumExtendedWorkOffset);
  EXPECT_EQ(a.coolantFlood, b.coolantFlood);
  EXPECT_EQ(a.coolantMist, b.coolantMist);
  EXPECT_EQ(a.coolantThrough, b.coolantThrough);
  EXPECT_EQ(a.coolantOff, b.coolantOff);
  EXPECT_EQ(a.contouringOn, b.contouringOn);
  EXPECT_EQ(a.contouringOff, b.contouringOff);
  EXPECT_EQ(a.endRetract, b.endRetract);
  EXPECT_EQ(a.start, b.start);
  EXPECT_EQ(a.toolChange, b.toolChange);
  EXPECT_EQ(a.end, b.end);
  EXPECT_EQ(a.lineNumbers.enabled, b.lineNumbers.enabled);
  EXPECT_EQ(a.lineNumbers.start, b.lineNumbers.start);
  EXPECT_EQ(a.lineNumbers.increment, b.lineNumbers.increment);
  EXPECT_EQ(a.lineNumbers.maximum, b.lineNumbers.maximum);
  EXPECT_EQ(a.comments, b.comments);
  EXPECT_EQ(a.commentCase, b.commentCase);
}

const char* const fullFanucFile = R"toml(name = "vmc 3"
description = "Fanuc 0i-MF"
target = "fanuc"
[profile]
extends = "fanuc"
maximum_block_length = 100
coordinate_decimals = 4
least_input_increment = 0.0001
maximum_program_number = 8999
maximum_sequence_number = 9999
maximum_loop_nesting = 2
macro_word_abbreviations = true
[setup]
length_offset = "G43 Z50. H{length}"
tool_edge = ""
work_offset = "G{code} (work)"
extended_work_offset = "G54.1 P{number}"
maximum_extended_work_offset = 300
coolant_flood = "M8"
coolant_mist = "M7"
coolant_through = "M88"
coolant_off = "M9 M89"
high_speed = true
contouring_on = "G08 P1"
contouring_off = "G08 P0"
end_retract = ["G91 G28 Z0.", "G90"]
[limits]
maximum_feed = 8000
maximum_spindle_speed = 12000.5
)toml";

TEST(MachineFileTest, ReadsEveryFieldOfAFullFile) {
  Read result = readText(fullFanucFile);
  ASSERT_TRUE(result.machine) << result.diagnostics.front().message;
  const MachineDescription& machine = *result.machine;
  EXPECT_EQ(machine.name, "vmc 3");
  EXPECT_EQ(machine.description, "Fanuc 0i-MF");
  EXPECT_EQ(machine.target, "fanuc");
  ASSERT_TRUE(machine.profile);
  EXPECT_EQ(machine.profile->name, "fanuc");
  EXPECT_EQ(machine.profile->maximumBlockLength, 100);
  EXPECT_EQ(machine.profile->coordinateDecimals, 4);
  EXPECT_DOUBLE_EQ(machine.profile->leastInputIncrement, 0.0001);
  EXPECT_EQ(machine.profile->maximumProgramNumber, 8999);
  EXPECT_EQ(machine.profile->maximumSequenceNumber, 9999);
  EXPECT_EQ(machine.profile->maximumLoopNesting, 2);
  EXPECT_TRUE(machine.profile->macroWordAbbreviations);
  EXPECT_EQ(machine.profile->locals.first, findControllerProfile("fanuc")->locals.first);
  const MachineSetup& setup = machine.setup;
  EXPECT_EQ(setup.dialect, "fanuc");
  EXPECT_EQ(setup.lengthOffset, "G43 Z50. H{length}");
  EXPECT_EQ(setup.toolEdge, "");
  EXPECT_EQ(setup.workOffset, "G{code} (work)");
  EXPECT_EQ(setup.extendedWorkOffset, "G54.1 P{number}");
  EXPECT_EQ(setup.maximumExtendedWorkOffset, 300);
  EXPECT_EQ(setup.coolantThrough, "M88");
  EXPECT_EQ(setup.coolantOff, "M9 M89");
  EXPECT_EQ(setup.contouringOn, "G08 P1");
  EXPECT_EQ(setup.contouringOff, "G08 P0");
  EXPECT_EQ(setup.endRetract, (std::vector<std::string>{"G91 G28 Z0.", "G90"}));
  EXPECT_DOUBLE_EQ(machine.maximumFeed, 8000);
  EXPECT_DOUBLE_EQ(machine.maximumSpindleSpeed, 12000.5);
}

TEST(MachineFileTest, LeavesTheBuiltinValuesOfWhatTheFileDoesNotSet) {
  Read result = readText("target = \"m80\"\n[profile]\nextends = \"m80\"\n");
  ASSERT_TRUE(result.machine);
  expectEqualSetups(result.machine->setup, builtinMachineSetup("m80"));
  EXPECT_EQ(result.machine->profile->maximumBlockLength,
            findControllerProfile("m80")->maximumBlockLength);
  EXPECT_EQ(result.machine->maximumFeed, 0);
}

// The built-in setups, shipped as machine files (stdlib/machines) for shops
// to copy: each file reads to exactly what the target prints without one.
TEST(MachineFileTest, TheShippedDefaultsAreTheBuiltinSetups) {
  std::filesystem::path folder = std::filesystem::path(CNCC_STDLIB_DIR) / "machines";
  for (std::string target : {"fanuc", "m80", "linuxcnc", "sinumerik", "gcode"}) {
    SCOPED_TRACE(target);
    std::vector<MachineDiagnostic> diagnostics;
    std::optional<MachineDescription> machine =
        readMachineFile((folder / (target + ".toml")).string(), diagnostics);
    ASSERT_TRUE(machine) << diagnostics.front().message;
    EXPECT_EQ(machine->target, target);
    expectEqualSetups(machine->setup, builtinMachineSetup(target));
    if (machine->profile) {
      const ControllerProfile* builtin = findControllerProfile(target);
      ASSERT_NE(builtin, nullptr);
      EXPECT_EQ(machine->profile->name, builtin->name);
      EXPECT_EQ(machine->profile->maximumSequenceNumber, builtin->maximumSequenceNumber);
      EXPECT_EQ(machine->profile->maximumBlockLength, builtin->maximumBlockLength);
    }
  }
}

TEST(MachineFileTest, HighSpeedFalseEmptiesTheContouringBlocks) {
  Read result = readText("target = \"linuxcnc\"\n[setup]\nhigh_speed = false\n");
  ASSERT_TRUE(result.machine);
  EXPECT_EQ(result.machine->setup.contouringOn, "");
  EXPECT_EQ(result.machine->setup.contouringOff, "");
  expectDiagnostic("target = \"linuxcnc\"\n[setup]\nhigh_speed = false\ncontouring_on = \"G64\"\n",
                   4, 17, "machine-conflict");
}

TEST(MachineFileTest, ReportsASyntaxErrorAtItsPosition) {
  MachineDiagnostic diagnostic = onlyDiagnostic("target = \"fanuc\"\n[setup\n");
  EXPECT_EQ(diagnostic.code, "machine-syntax");
  EXPECT_EQ(diagnostic.line, 2);
  EXPECT_GT(diagnostic.column, 1);
}

TEST(MachineFileTest, ReportsUnknownKeysAndTables) {
  expectDiagnostic("target = \"gcode\"\nspeed = 3\n", 2, 1, "machine-unknown-key");
  expectDiagnostic("target = \"gcode\"\n[setup]\n  coolant = \"M8\"\n", 3, 3,
                   "machine-unknown-key");
  expectDiagnostic("target = \"gcode\"\n[spindle]\nmaximum = 3\n", 2, 2, "machine-unknown-table");
  expectDiagnostic("target = \"fanuc\"\n[profile]\nextends = \"fanuc\"\nblock_length = 9\n", 4, 1,
                   "machine-unknown-key");
}

TEST(MachineFileTest, ReportsWrongTypesAtTheValue) {
  expectDiagnostic("target = 3\n", 1, 10, "machine-wrong-type");
  expectDiagnostic("target = \"gcode\"\n[setup]\nwork_offset = 54\n", 3, 15, "machine-wrong-type");
  expectDiagnostic("target = \"gcode\"\n[setup]\nhigh_speed = \"yes\"\n", 3, 14,
                   "machine-wrong-type");
  expectDiagnostic("target = \"gcode\"\n[setup]\nend_retract = [\"G90\", 28]\n", 3, 23,
                   "machine-wrong-type");
  expectDiagnostic("target = \"gcode\"\n[limits]\nmaximum_feed = \"fast\"\n", 3, 16,
                   "machine-wrong-type");
  expectDiagnostic(
      "target = \"fanuc\"\n[profile]\nextends = \"fanuc\"\ncoordinate_decimals = 3.5\n", 4, 23,
      "machine-wrong-type");
  expectDiagnostic("target = \"gcode\"\nsetup = 1\n", 2, 9, "machine-wrong-type");
  expectDiagnostic(
      "target = \"fanuc\"\n[profile]\nextends = \"fanuc\"\nmacro_word_abbreviations = 1\n", 4, 28,
      "machine-wrong-type");
}

TEST(MachineFileTest, ReportsNumbersOutOfRange) {
  std::string fanuc = "target = \"fanuc\"\n[profile]\nextends = \"fanuc\"\n";
  expectDiagnostic(fanuc + "maximum_block_length = 8\n", 4, 24, "machine-out-of-range");
  expectDiagnostic(fanuc + "coordinate_decimals = 7\n", 4, 23, "machine-out-of-range");
  expectDiagnostic(fanuc + "least_input_increment = 0\n", 4, 25, "machine-out-of-range");
  expectDiagnostic(fanuc + "maximum_loop_nesting = 4\n", 4, 24, "machine-out-of-range");
  expectDiagnostic(fanuc + "maximum_program_number = -1\n", 4, 26, "machine-out-of-range");
  expectDiagnostic("target = \"gcode\"\n[limits]\nmaximum_feed = 0\n", 3, 16,
                   "machine-out-of-range");
  expectDiagnostic("target = \"gcode\"\n[limits]\nmaximum_spindle_speed = -100.0\n", 3, 25,
                   "machine-out-of-range");
  expectDiagnostic("target = \"gcode\"\n[setup]\nmaximum_extended_work_offset = 0\n", 3, 32,
                   "machine-out-of-range");
  expectDiagnostic("target = \"gcode\"\n[setup]\nwork_offset = \"\"\n", 3, 15,
                   "machine-out-of-range");
}

TEST(MachineFileTest, ReportsTargetAndProfileProblems) {
  expectDiagnostic("name = \"x\"\n", 1, 1, "machine-missing-key");
  expectDiagnostic("target = \"haas\"\n", 1, 10, "machine-unknown-target");
  expectDiagnostic("target = \"fanuc\"\n", 1, 10, "machine-missing-key");
  expectDiagnostic("target = \"fanuc\"\n[profile]\nextends = \"okuma\"\n", 3, 11,
                   "machine-unknown-profile");
  expectDiagnostic("target = \"linuxcnc\"\n[profile]\nextends = \"fanuc\"\n", 2, 1,
                   "machine-profile-not-applicable");
}

TEST(MachineFileTest, ReportsPlaceholdersAFieldDoesNotHave) {
  expectDiagnostic("target = \"gcode\"\n[setup]\nlength_offset = \"G43 H{code}\"\n", 3, 17,
                   "machine-placeholder");
  expectDiagnostic("target = \"gcode\"\n[setup]\ncoolant_flood = \"M{length}\"\n", 3, 17,
                   "machine-placeholder");
  expectDiagnostic("target = \"gcode\"\n[setup]\nwork_offset = \"G{code\"\n", 3, 15,
                   "machine-placeholder");
  expectDiagnostic("target = \"gcode\"\n[setup]\nend_retract = [\"G53 Z{number}\"]\n", 3, 16,
                   "machine-placeholder");
}

TEST(MachineFileTest, ReportsBlocksThatAreNotBlocksOfTheDialect) {
  expectDiagnostic("target = \"gcode\"\n[setup]\ncoolant_flood = \"M#1\"\n", 3, 17,
                   "machine-invalid-block");
  expectDiagnostic("target = \"linuxcnc\"\n[setup]\ncoolant_off = \"M9 ; off\"\n", 3, 15,
                   "machine-invalid-block");
  expectDiagnostic("target = \"fanuc\"\n[profile]\nextends = \"fanuc\"\n[setup]\n"
                   "contouring_on = \"CYCLE832({tolerance})\"\n",
                   5, 17, "machine-invalid-block");
  expectDiagnostic("target = \"gcode\"\n[setup]\nend_retract = [\"G91 G28 Z\"]\n", 3, 16,
                   "machine-invalid-block");
  expectDiagnostic("target = \"sinumerik\"\n[setup]\nend_retract = [\"SUPA G0 (up)\"]\n", 3, 16,
                   "machine-invalid-block");
  expectDiagnostic("target = \"fanuc\"\n[profile]\nextends = \"fanuc\"\nmaximum_block_length = "
                   "16\n[setup]\ncoolant_flood = \"M8 (COOLANT FLOOD ON)\"\n",
                   6, 17, "machine-block-too-long");
}

TEST(MachineFileTest, AcceptsSinumerikCallsKeywordsAndAssignments) {
  Read result = readText(R"toml(target = "sinumerik"
[setup]
contouring_on = "CYCLE832({tolerance}, _SEMIFIN, 1) ; high speed"
end_retract = ["SUPA G0 Z0 D0", "G0 X=AC(0) Y=0", "G64 SOFT COMPCAD"]
)toml");
  EXPECT_TRUE(result.machine) << result.diagnostics.front().message;
}

TEST(MachineFileTest, ReadsSequencesLineNumbersAndComments) {
  Read result = readText(R"toml(target = "fanuc"
[profile]
extends = "fanuc"
maximum_sequence_number = 9999
[setup]
start = ["{units} G17 G90 G40 G49 G80 G94", "G91 G28 Z0.", "G90"]
tool_change = ["G91 G28 Z0.", "G90", "M6 T{tool}"]
end = ["M1"]
[program]
line_numbers = true
line_number_start = 100
line_number_increment = 5
comments = false
comment_case = "as-written"
)toml");
  ASSERT_TRUE(result.machine) << result.diagnostics.front().message;
  const MachineSetup& setup = result.machine->setup;
  EXPECT_EQ(startBlocks(setup, true).front(), "G20 G17 G90 G40 G49 G80 G94");
  EXPECT_EQ(toolChangeBlocks(setup, 12, "(DIAMETER 6.)"),
            (std::vector<std::string>{"G91 G28 Z0.", "G90", "M6 T12 (DIAMETER 6.)"}));
  EXPECT_EQ(setup.end, std::vector<std::string>{"M1"});
  EXPECT_TRUE(setup.lineNumbers.enabled);
  EXPECT_EQ(setup.lineNumbers.start, 100);
  EXPECT_EQ(setup.lineNumbers.increment, 5);
  // The profile's largest sequence number is the numbering's maximum.
  EXPECT_EQ(setup.lineNumbers.maximum, 9999);
  EXPECT_FALSE(setup.comments);
  EXPECT_EQ(setup.commentCase, CommentCase::AsWritten);
}

TEST(MachineFileTest, RefusesSequencesWithoutTheirPlaceholders) {
  // No {units}: the program's units would be the machine's last ones.
  expectDiagnostic("target = \"gcode\"\n[setup]\nstart = [\"G17 G90\"]\n", 3, 9,
                   "machine-missing-placeholder");
  expectDiagnostic("target = \"gcode\"\n[setup]\ntool_change = [\"M6\"]\n", 3, 15,
                   "machine-missing-placeholder");
  // {blend} is LinuxCNC's blending tolerance only.
  expectDiagnostic("target = \"gcode\"\n[setup]\nstart = [\"{units} G64 P{blend}\"]\n", 3, 10,
                   "machine-placeholder");
  EXPECT_TRUE(
      readText("target = \"linuxcnc\"\n[setup]\nstart = [\"{units} G64 P{blend}\"]\n").machine);
  expectDiagnostic("target = \"gcode\"\n[setup]\nend = [\"M30 #1\"]\n", 3, 8,
                   "machine-invalid-block");
}

TEST(MachineFileTest, RefusesLineNumbersBeyondTheController) {
  // Past the profile's largest sequence number.
  expectDiagnostic("target = \"fanuc\"\n[profile]\nextends = \"fanuc\"\n"
                   "maximum_sequence_number = 9999\n[program]\nline_number_maximum = 10000\n",
                   6, 23, "machine-out-of-range");
  // rs274 stops at N99999.
  expectDiagnostic("target = \"linuxcnc\"\n[program]\nline_number_start = 100000\n", 3, 21,
                   "machine-out-of-range");
  expectDiagnostic("target = \"gcode\"\n[program]\nline_number_increment = 0\n", 3, 25,
                   "machine-out-of-range");
  expectDiagnostic("target = \"gcode\"\n[program]\ncomment_case = \"lower\"\n", 3, 16,
                   "machine-out-of-range");
  expectDiagnostic("target = \"gcode\"\n[program]\nline_numbers = 1\n", 3, 16,
                   "machine-wrong-type");
}

TEST(MachineFileTest, ReportsEveryProblemOfAFile) {
  Read result = readText("target = \"gcode\"\nspeed = 1\n[setup]\nwork_offset = 1\n[limits]\n"
                         "maximum_feed = -1\n");
  EXPECT_FALSE(result.machine);
  ASSERT_EQ(result.diagnostics.size(), 3u);
  EXPECT_EQ(result.diagnostics[0].line, 2);
  EXPECT_EQ(result.diagnostics[1].line, 4);
  EXPECT_EQ(result.diagnostics[2].line, 6);
}

TEST(MachineFileTest, ReportsAFileThatCannotBeRead) {
  std::vector<MachineDiagnostic> diagnostics;
  EXPECT_FALSE(readMachineFile("/nonexistent/machine.toml", diagnostics));
  ASSERT_EQ(diagnostics.size(), 1u);
  EXPECT_EQ(diagnostics.front().code, "machine-file-not-readable");
  EXPECT_EQ(diagnostics.front().line, 0);
}

TEST(MachineFileTest, EveryExampleMachineReadsWithoutDiagnostics) {
  std::filesystem::path folder = std::filesystem::path(CNCC_SOURCE_DIR) / "examples" / "machines";
  int files = 0;
  for (const std::filesystem::directory_entry& entry :
       std::filesystem::directory_iterator(folder)) {
    if (entry.path().extension() != ".toml") {
      continue;
    }
    ++files;
    std::vector<MachineDiagnostic> diagnostics;
    std::optional<MachineDescription> machine = readMachineFile(entry.path().string(), diagnostics);
    EXPECT_TRUE(machine) << entry.path() << ":" << diagnostics.front().line << ": "
                         << diagnostics.front().message;
    EXPECT_TRUE(diagnostics.empty()) << entry.path();
  }
  EXPECT_EQ(files, 4);
}

} // namespace
} // namespace cncc::backends
