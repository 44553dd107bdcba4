// The machine side of the LinuxCNC dialect: the modal state and the words
// of a block (G, M, axes, F, S, T, ...), their values already evaluated,
// run in LinuxCNC's order of execution (linuxcnc_motion.cpp).
#pragma once

#include "linuxcnc_blocks.h"
#include "sim_compensation.h"

#include "cncc/backends/linuxcnc_controller.h"

#include <map>
#include <optional>
#include <set>

namespace cncc::backends::sim::linuxcnc {

// A block's words: G and M codes (G as ten times the code, G64 is 640 and
// G90.1 is 901), the other letters by value.
struct BlockWords {
  std::set<int> gCodes;
  std::set<int> mCodes;
  std::map<char, double> values;

  bool has(char letter) const { return values.count(letter) > 0; }
  bool hasG(int code) const { return gCodes.count(code) > 0; }
  bool hasM(int code) const { return mCodes.count(code) > 0; }
};

BlockWords collectWords(const std::vector<std::pair<char, double>>& words,
                        const LineContext& context);

class Machine {
public:
  Machine(LinuxcncRun& run, const LinuxcncRunOptions& options)
      : run_(run), options_(options),
        compensation_(
            compensated_,
            {.on = "G41/G42", .off = "G40", .transitionArcs = true, .offsetEntry = true}) {}

  // Runs a block's words; true when M2 or M30 ends the program.
  bool execute(const BlockWords& words, const LineContext& context);
  // The current point in work coordinates (#5420-#5422); nullopt for Z
  // after a G53 move in machine coordinates.
  std::optional<double> position(char axis) const;

private:
  bool executeWords(const BlockWords& words, const LineContext& context);
  void setUnits(bool inches, const LineContext& context);
  void spindle(const BlockWords& words, const LineContext& context);
  void motion(const BlockWords& words, const LineContext& context);
  Point3 target(const BlockWords& words) const;
  void arc(const BlockWords& words, Point3 end, const LineContext& context);
  void emit(LinuxcncMove move);
  // G40, G41/G42 D<tool>, G41.1/G42.1 D<diameter>.
  void setCompensation(const BlockWords& words, const LineContext& context);
  // The moves the compensation has let go of, to the run.
  void drainCompensated();

  LinuxcncRun& run_;
  const LinuxcncRunOptions& options_;
  // Cutter radius compensation (sim_compensation.h) with LinuxCNC's arc
  // about every outside corner and its tangent entry move; while it is on,
  // every move passes through it into `compensated_`.
  ExecutedPath compensated_;
  RadiusCompensation compensation_;
  sim::Block block_; // the block being executed, for compensation's messages
  Point3 position_;
  bool zInMachineCoordinates_ = false; // after G53 Z: unknown in work coordinates
  int motionMode_ = 800;               // G80: no motion mode
  bool absolute_ = true;
  bool absoluteArcCentres_ = false; // G90.1; G91.1 (the default) is incremental
  bool inches_ = false;
  bool moved_ = false;
  double feed_ = 0;
  double speed_ = 0;
  int spindleDirection_ = 0; // 3 or 4 while running
  std::optional<int> selectedTool_;
};

} // namespace cncc::backends::sim::linuxcnc
