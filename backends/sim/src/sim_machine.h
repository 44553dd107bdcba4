// The state of the virtual controller while it runs a program: the call
// stack with each level's locals, the common variables, the modal state and
// the path recorded so far. virtual_controller.cpp runs blocks and macro
// statements; sim_motion.cpp runs address words (modal codes, motion, calls).
#pragma once

#include "cncc/backends/virtual_controller.h"

#include "sim_compensation.h"
#include "sim_evaluator.h"
#include "sim_nurbs.h"

#include <array>
#include <map>
#include <optional>

namespace cncc::backends::sim {

// The words of a block after evaluation; vacant ones are dropped, as the
// controller drops an address whose variable is vacant.
struct BlockWords {
  std::vector<int> gCodes; // tenths
  std::vector<int> mCodes;
  std::map<char, double> values; // every other letter

  bool hasG(int tenths) const;
};

class Machine : public VariableReader {
public:
  Machine(const ProgramText& program, const ControllerProfile& profile,
          const SimulationOptions& options, ExecutedPath& path);

  // Runs to M30/M02 (or the final M99 of a macro call); throws
  // SimulationError.
  void run();
  std::size_t blocksExecuted() const { return blocksExecuted_; }
  const std::vector<std::size_t>& blockExecutions() const { return blockExecutions_; }
  std::map<int, std::optional<double>> commonVariables() const;

  Value read(int variable, const Block& block) const override;

private:
  static constexpr int localCount = 34; // #0 unused, #1-#33

  struct Frame {
    std::size_t program = 0;     // index in ProgramText::programs
    std::size_t returnBlock = 0; // where the caller goes on after M99
    int repeatsLeft = 0;         // L: further runs of the macro after this one
    bool subprogram = false;     // M98: runs with its caller's locals
    std::array<Value, localCount> arguments{};
    std::array<Value, localCount> locals{};
  };

  // A drilling cycle's modal data (sim_cycles.cpp).
  struct CannedCycle {
    std::optional<int> code;             // 73, 74, 81..86, 89 while a cycle is modal
    std::optional<bool> returnToInitial; // G98 (true) or G99
    double initialZ = 0;                 // Z when the cycle mode began
    std::optional<double> rPoint;        // R as written (G91: from the initial level)
    std::optional<double> bottom;        // Z as written (G91: from the R point)
    std::optional<double> peck;          // Q
  };

  // G52, G68 and G16 over the work coordinates (sim_coordinates.cpp).
  struct CoordinateSystem {
    Point3 shift; // G52
    bool rotated = false;
    double centreX = 0, centreY = 0; // G68's centre, in the local system
    double angle = 0;                // degrees, counterclockwise
    bool polar = false;              // G16
    bool isPlain() const;
  };

  // G66: the macro a block with a move calls, from the call level of G66.
  struct ModalCall {
    Frame frame;
    std::size_t level = 0; // frames_.size() when G66 ran
  };

  struct ModalState {
    std::optional<int> motion; // 0..3 once commanded
    bool absolute = true;
    bool inches = false;
    std::optional<double> feed;
    Point3 position;
    std::optional<int> selectedTool;
    bool toolChanged = false;          // an M06 has run
    std::optional<int> lengthOffset;   // G43 H.., cleared by G49 and M06
    std::optional<int> radiusRegister; // the last D
    bool atReference = false;          // after G28: off the work coordinates
    double spindleSpeed = 0;
    bool spindleRunning = false;
    CannedCycle cycle;
    CoordinateSystem coordinates;
    std::optional<ModalCall> modalCall;
  };

  // What running one block decided.
  enum class Next { Continue, Jump, Stop };

  Next executeBlock(const Block& block, std::size_t& next);
  void write(int variable, Value value, const Block& block);
  std::size_t findSequenceNumber(int number, const Block& from, std::size_t fromIndex) const;
  void runOutOfProgram(std::size_t index) const;

  // sim_motion.cpp
  Next executeWords(const Block& block, std::size_t& next);
  Next executeAddressWords(const Block& block, std::size_t& next);
  void executeAxisWords(const Block& block, const BlockWords& words);
  void cornerArc(const Block& block, const std::map<char, double>& axes);
  // sim_modal_codes.cpp
  void checkExtendedWorkOffset(const Block& block, const BlockWords& words) const;
  void applyModalCodes(const Block& block, const BlockWords& words);
  void applyFeedSpindleTool(const Block& block, const BlockWords& words);
  Next executeMCode(const Block& block, const BlockWords& words, std::size_t& next);
  void setCompensation(const Block& block, int tenths);
  // Every executed event goes to the path through the radius compensation.
  void output(const ExecutedEvent& event, const Block& block) { compensation_.add(event, block); }
  // sim_system_variables.cpp: #4001-#4120, nullopt for other variables.
  std::optional<Value> modalInformation(int variable, const Block& block) const;

  // sim_coordinates.cpp
  Point3 toWork(Point3 program) const;
  Point3 toProgram(Point3 work) const;
  void rotateVector(double& x, double& y) const;
  // Where the block's X Y Z go, in work coordinates.
  Point3 programmedTarget(const Block& block, const std::map<char, double>& axes) const;
  void setLocalShift(const Block& block, const std::map<char, double>& axes);
  void setRotation(const Block& block, const std::map<char, double>& axes);

  // sim_cycles.cpp
  static bool isCycleCode(int tenths);
  void setCycleMode(const Block& block, int tenths);
  void runCycleBlock(const Block& block, const std::map<char, double>& values);
  void drillHole(const Block& block, const std::map<char, double>& values);
  void drillDown(const Block& block, double rLevel, double bottom);
  void cycleMove(const Block& block, bool feed, Point3 target);
  std::string peckParameterName(int code) const;

  // sim_calls.cpp
  void callMacro(const Block& block, std::size_t& next);
  Frame macroCallFrame(const Block& block, std::string_view call);
  void enterMacro(const Block& block, Frame callee, std::size_t& next);
  void setModalCall(const Block& block);
  // After a block with a move: the G66 call, if one is modal; true if made.
  bool callAfterMove(const Block& block, std::size_t& next);
  void callSubprogram(const Block& block, const std::map<char, double>& values, std::size_t& next);
  std::size_t programIndex(int number, const Block& block, std::string_view call) const;
  void checkCallNesting(const Block& block, bool macroCall) const;
  // The frame whose locals #1-#33 are in use: M98 subprograms share their caller's.
  Frame& localFrame();
  const Frame& localFrame() const;
  Next returnFromMacro(const Block& block, const std::map<char, double>& values, std::size_t& next);

  // sim_motion.cpp, sim_arc.cpp
  void move(const Block& block, int motion, const std::map<char, double>& axes);
  void returnToReference(const Block& block, const std::map<char, double>& axes);
  void moveArc(const Block& block, int motion, Point3 target, const std::map<char, double>& axes);
  double increment() const;
  double roundToIncrement(double value) const;

  // sim_nurbs.cpp: G05 P10000 and G06.2 blocks; true when the block was one.
  bool executeNurbsWords(const Block& block, const std::vector<int>& gCodes,
                         const std::vector<int>& mCodes, const std::map<char, double>& values);
  void finishNurbs(const Block& block);

  const ProgramText& program_;
  const ControllerProfile& profile_;
  const SimulationOptions& options_;
  ExecutedPath& path_;
  std::vector<Frame> frames_;
  std::map<int, Value> commons_;
  std::map<int, Value> systemVariables_;
  ModalState modal_;
  NurbsInProgress nurbs_; // sim_nurbs.h
  RadiusCompensation compensation_{path_};
  bool moveCommanded_ = false; // the current block moved (for G66)
  std::size_t blocksExecuted_ = 0;
  std::vector<std::size_t> blockExecutions_; // by block index
};

} // namespace cncc::backends::sim
