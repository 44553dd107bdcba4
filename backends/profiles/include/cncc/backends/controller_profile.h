// What a controller accepts, as data: the register allocator, the program
// printers and the virtual controller all read the same profile, so a
// program that does not fit its controller is refused at compile time with
// the limit named, and the simulator enforces the same limits when it runs
// what was printed. Facts and their sources are in TARGETS.md; uncertain
// ones take the conservative value every variant of the controller accepts.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace cncc::backends {

// A contiguous range of numbered variables, `#first` to `#last` inclusive.
struct VariableRange {
  int first = 0;
  int last = -1;
  int count() const { return last >= first ? last - first + 1 : 0; }
  bool contains(int variable) const { return variable >= first && variable <= last; }
};

// Which G65 argument letter reaches which local variable (`A` -> #1).
struct ArgumentLetter {
  char letter = 'A';
  int variable = 1;
};

struct ControllerProfile {
  std::string name;        // "fanuc", "m80", ...
  std::string description; // one line for messages and --help

  // Variables a program may use for its own values, in the order the
  // register allocator prefers them: locals of a macro call, volatile
  // commons, retained commons.
  VariableRange locals;                      // #1-#33, local to a G65 call
  std::vector<VariableRange> volatileCommon; // #100-#199: cleared at power-off
  std::vector<VariableRange> retainedCommon; // #500-#999: kept at power-off
  std::vector<ArgumentLetter> argumentLetters;

  int maximumLoopNesting = 3;    // WHILE .. DOm nesting (m = 1..this)
  int maximumLoopIdentifier = 3; // the largest m in DOm / ENDm
  int maximumBracketNesting = 5; // [ ] levels, function brackets included
  int maximumCallNesting = 4;    // G65 macro call depth
  int maximumBlockLength = 128;  // characters in one block (line)
  int maximumProgramNumber = 9999;
  int maximumSequenceNumber = 99999;
  int significantDigits = 8;            // in a printed constant
  int coordinateDecimals = 3;           // digits after the point, millimetres
  double leastInputIncrement = 0.001;   // mm: every executed coordinate is rounded to it
  double maximumCoordinate = 99999.999; // mm
  // G02/G03: how far the end point may be from the circle through the start
  // around the centre (mm) before the controller alarms (Fanuc parameter
  // 3410; its setting varies (?), this is a common value).
  double arcRadiusTolerance = 0.005;
  bool hasIndirectVariables = true; // `#[expression]`
  bool hasThen = true;              // `IF [..] THEN statement`
  bool hasPowerFunction = false;    // `POW[a,b]` (30i)
  // After a tool change (M06) a Z move needs the tool's length offset
  // (G43 H..): without it the spindle gauge line, not the tool tip, goes to Z.
  bool requiresLengthOffset = true;
  // The machine's largest feed (mm/min) and spindle speed (rpm), from a
  // machine file's [limits]; 0: none. The virtual controller alarms past them.
  double maximumFeed = 0;
  double maximumSpindleSpeed = 0;
  // The extended work offsets G54.1 P1 .. P(this) the machine has (0:
  // none), from its machine file; the virtual controller alarms past them.
  int maximumExtendedWorkOffset = 48;
  // Where G39 (corner circular interpolation under G41/G42) is written:
  // Fanuc in a block of its own after the move that ends at the corner,
  // `G39 I.. J..` towards the next move's start (I J from the corner);
  // Mitsubishi on that move's block, `G39 G01 X.. Y..`, the arc at its end.
  bool cornerArcOnMoveBlock = false;
  // Whether the control reads two-letter abbreviations of macro words in a
  // shop's programs (WH for WHILE, SI for SIN; backends/sim/README.md has
  // the table). No manual statement of it was found for any built-in
  // profile (?), so none reads them: a machine file's [profile] sets
  // `macro_word_abbreviations = true` for a control known to. The compiler
  // never prints them, and strict reading never accepts them.
  bool macroWordAbbreviations = false;

  // The letter of the G65 argument that reaches local `variable`, if any.
  std::optional<char> letterForLocal(int variable) const;
  // The local variable that argument `letter` reaches, if any.
  std::optional<int> localForLetter(char letter) const;
  // How many variables of the allocatable ranges exist in all.
  int allocatableVariableCount() const;
};

// The built-in profiles: "fanuc" (conservative Fanuc 0i/16i/30i),
// "fanuc-0i-small" (only #100-#149 and #500-#531), "m80".
std::span<const ControllerProfile> builtinControllerProfiles();
const ControllerProfile* findControllerProfile(std::string_view name);

} // namespace cncc::backends
