// A consumer of a run's machine events, handed them one at a time instead of
// a ToolPath that stores them all: for a run whose events are used once (a
// length, a bounding box, a printer) and need not be kept.
#pragma once

#include "cncc/ir/tool_path.h"

namespace cncc::ir {

class MachineEventSink {
public:
  virtual ~MachineEventSink() = default;

  // The next event, in the order a ToolPath of the same run would hold it;
  // `event` lives only during the call. An exception thrown here stops the
  // run and reaches the run's caller.
  virtual void event(const MachineEvent& event) = 0;

protected:
  MachineEventSink() = default;
  MachineEventSink(const MachineEventSink&) = default;
  MachineEventSink& operator=(const MachineEventSink&) = default;
};

} // namespace cncc::ir
