#include "jit_runtime.h"

#include "cncc/ir/interpreter.h"
#include "cncc/ir/nurbs_move.h"
#include "cncc/ir/polynomial_move.h"
#include "cncc/ir/spline_move.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace cncc::backends::jit {

namespace {

void notePosition(RunContext& context, const ir::MachineEvent& event) {
  if (ir::isMove(event)) {
    context.previousPosition = context.position;
    context.position = {event.x, event.y, event.z};
    context.positionKind = event.kind;
    context.motions = std::min(context.motions + 1, 2);
  }
}

// The last two moves as a stored run's events end with them: what the
// interpreter's splineMove reads of the events before it.
void seedLastMotions(const RunContext& context, std::vector<ir::MachineEvent>& events) {
  if (context.motions == 2) {
    ir::MachineEvent before;
    before.kind = ir::MachineEvent::Kind::Rapid;
    before.x = context.previousPosition[0];
    before.y = context.previousPosition[1];
    before.z = context.previousPosition[2];
    events.push_back(std::move(before));
  }
  if (context.motions >= 1) {
    ir::MachineEvent last;
    last.kind = context.positionKind;
    last.x = context.position[0];
    last.y = context.position[1];
    last.z = context.position[2];
    events.push_back(std::move(last));
  }
}

// Appends one event to the run's events, or hands it to the sink.
void deliver(RunContext& context, ir::MachineEvent&& event) {
  notePosition(context, event);
  if (context.events != nullptr) {
    context.events->push_back(std::move(event));
  } else {
    context.sink->event(event);
  }
}

// Records an event; an exception (out of memory, or the sink's) must not
// unwind through the native code, so it is kept for the caller and reported
// as a failure.
template <typename MakeEvent> std::int32_t record(RunContext* context, MakeEvent makeEvent) {
  try {
    deliver(*context, makeEvent());
    return 0;
  } catch (...) {
    context->exception = std::current_exception();
    return 1;
  }
}

// A move of several events, made by one of the interpreter's functions that
// append to a vector: appended to the run's events, or made in pendingMoves
// (after the last two moves when `readsLastMotions`: what the function
// reads of the events before it) and handed to the sink. The events made
// before an error are kept (or handed on) as the run's events before it.
template <typename Append>
std::int32_t recordMoves(RunContext* context, Append append, bool readsLastMotions = false) {
  if (context->exception) {
    return 1;
  }
  bool streaming = context->events == nullptr;
  std::vector<ir::MachineEvent>& target = streaming ? context->pendingMoves : *context->events;
  // A streaming run's pendingMoves is empty here: the events it hands on
  // follow the seeded ones.
  std::size_t first =
      streaming && readsLastMotions ? static_cast<std::size_t>(context->motions) : target.size();
  try {
    if (streaming && readsLastMotions) {
      seedLastMotions(*context, target);
    }
    append(target);
  } catch (...) {
    context->exception = std::current_exception();
  }
  try {
    for (std::size_t i = first; i < target.size(); ++i) {
      notePosition(*context, target[i]);
      if (streaming) {
        context->sink->event(target[i]);
      }
    }
  } catch (...) {
    if (!context->exception) {
      context->exception = std::current_exception();
    }
  }
  if (streaming) {
    context->pendingMoves.clear();
  }
  return context->exception ? 1 : 0;
}

// A streaming run's feed move: the context's feed event, handed to the sink
// with this target and feed (what deliver does, without making an event).
std::int32_t streamFeed(RunContext& context, double x, double y, double z, double feed) {
  ir::MachineEvent& event = context.feedEvent;
  event.x = x;
  event.y = y;
  event.z = z;
  event.feed = feed;
  notePosition(context, event);
  try {
    context.sink->event(event);
    return 0;
  } catch (...) {
    context.exception = std::current_exception();
    return 1;
  }
}

template <typename Fill> std::int32_t recordError(RunContext* context, Fill fill) {
  try {
    context->errorMessage = fill();
  } catch (...) {
    context->exception = std::current_exception();
  }
  return 1;
}

} // namespace

extern "C" {

static std::int32_t cncc_jit_rapid(RunContext* context, double x, double y, double z) {
  return record(context, [&] {
    ir::MachineEvent event;
    event.kind = ir::MachineEvent::Kind::Rapid;
    event.x = x;
    event.y = y;
    event.z = z;
    return event;
  });
}

static std::int32_t cncc_jit_climb(RunContext* context, double z) {
  return record(context, [&] { return ir::climbEvent(context->position, z); });
}

static std::int32_t cncc_jit_feed(RunContext* context, double x, double y, double z, double feed) {
  if (context->events == nullptr) {
    return streamFeed(*context, x, y, z, feed);
  }
  return record(context, [&] {
    ir::MachineEvent event;
    event.kind = ir::MachineEvent::Kind::Feed;
    event.x = x;
    event.y = y;
    event.z = z;
    event.feed = feed;
    return event;
  });
}

// `move.arc` from where the last move ended (the interpreter's arcMove
// checks and builds it); `turn` is its ArcTurn.
static std::int32_t cncc_jit_arc(RunContext* context, double turn, double x, double y, double z,
                                 double i, double j, double feed) {
  return record(context, [&] {
    return ir::arcMove(context->position, static_cast<ir::ArcTurn>(turn), x, y, z, i, j, feed);
  });
}

// One weight of the move.nurbs that follows; it cannot fail (an exception
// is kept for the move's call to report).
static std::int32_t cncc_jit_nurbs_weight(RunContext* context, double weight) {
  try {
    context->nurbsWeights.push_back(weight);
  } catch (...) {
    context->exception = std::current_exception();
  }
  return 0;
}

// `move.nurbs` with the weights passed before it, as the interpreter's
// nurbsMove records it.
static std::int32_t cncc_jit_nurbs(RunContext* context, std::uint32_t table, double z,
                                   double feed) {
  return recordMoves(context, [&](std::vector<ir::MachineEvent>& events) {
    std::vector<double> weights = std::move(context->nurbsWeights);
    context->nurbsWeights.clear();
    ir::nurbsMove(context->position, (*context->tables)[table], z, feed, weights, events);
  });
}

// `move.polynomial`, as the interpreter's polynomialMove records it.
static std::int32_t cncc_jit_polynomial(RunContext* context, double x, double y, double z,
                                        double k3x, double k2x, double k1x, double k3y, double k2y,
                                        double k1y, double k3z, double k2z, double k1z,
                                        double feed) {
  return recordMoves(context, [&](std::vector<ir::MachineEvent>& events) {
    std::array<double, 12> values{x, y, z, k3x, k2x, k1x, k3y, k2y, k1y, k3z, k2z, k1z};
    ir::polynomialMove(context->position, ir::polynomialMoveOf(values), feed, events);
  });
}

// `move.spline`, as the interpreter's splineMove records it.
static std::int32_t cncc_jit_spline(RunContext* context, std::uint32_t table, double z,
                                    double feed) {
  return recordMoves(
      context,
      [&](std::vector<ir::MachineEvent>& events) {
        ir::splineMove(table, (*context->tables)[table], z, feed, events);
      },
      true);
}

static std::int32_t cncc_jit_spindle(RunContext* context, double speed) {
  return record(context, [&] {
    ir::MachineEvent event;
    event.kind = ir::MachineEvent::Kind::Spindle;
    event.number = speed;
    return event;
  });
}

// `pass.begin`: the comment the interpreter records for it.
static std::int32_t cncc_jit_pass_begin(RunContext* context, double z) {
  return record(context, [&] {
    ir::MachineEvent event;
    event.kind = ir::MachineEvent::Kind::Comment;
    event.text = ir::passDepthComment(z);
    return event;
  });
}

static std::int32_t cncc_jit_corner_arc(RunContext* context, double dx, double dy) {
  return record(context, [&] {
    ir::MachineEvent event;
    event.kind = ir::MachineEvent::Kind::CornerArc;
    event.x = dx;
    event.y = dy;
    return event;
  });
}

static std::int32_t cncc_jit_tool(RunContext* context, double number, double diameter,
                                  std::uint32_t lengthRegister) {
  return record(context, [&] {
    ir::MachineEvent event;
    event.kind = ir::MachineEvent::Kind::Tool;
    event.number = number;
    event.diameter = diameter;
    event.offsetRegister = lengthRegister;
    return event;
  });
}

static std::int32_t cncc_jit_setting(RunContext* context, std::uint32_t opcode, double number,
                                     std::uint32_t index) {
  return record(context,
                [&] { return ir::settingEvent(static_cast<ir::Opcode>(opcode), number, index); });
}

static std::int32_t cncc_jit_comment(RunContext* context, std::uint32_t index) {
  return record(context, [&] {
    ir::MachineEvent event;
    event.kind = ir::MachineEvent::Kind::Comment;
    event.text = (*context->comments)[index];
    return event;
  });
}

// `alarm`: the run stops as the interpreter's does (the text is kept with
// the comments, by index).
static std::int32_t cncc_jit_alarm(RunContext* context, std::uint32_t index) {
  return record(context, [&]() -> ir::MachineEvent {
    throw ir::InterpreterError("alarm: " + (*context->comments)[index]);
  });
}

static std::int32_t cncc_jit_cut_begin(RunContext* context, std::uint32_t cut) {
  return record(context, [&] {
    ir::MachineEvent event;
    event.kind = ir::MachineEvent::Kind::CutBegin;
    event.number = cut;
    return event;
  });
}

// The errors, worded as the interpreter words them.
static std::int32_t cncc_jit_table_index_error(RunContext* context, double index,
                                               std::uint32_t table, std::uint64_t size) {
  return recordError(context, [&] {
    return fmt::format("index {} is outside table @{} of {} entries", index, table, size);
  });
}

static std::int32_t cncc_jit_loop_bound_error(RunContext* context) {
  return recordError(context, [] { return std::string("a loop bound is not a finite number"); });
}

static std::int32_t cncc_jit_loop_advance_error(RunContext* context, double next, double current) {
  return recordError(context, [&] {
    return fmt::format("a loop's variable does not advance: {} after {}", next, current);
  });
}

static std::int32_t cncc_jit_step_limit_error(RunContext* context, std::uint64_t maximumSteps) {
  return recordError(
      context, [&] { return fmt::format("the program takes more than {} steps", maximumSteps); });
}

} // extern "C"

namespace {

using Unary = double (*)(double);
using Binary = double (*)(double, double);

} // namespace

const std::vector<RuntimeSymbol>& runtimeSymbols() {
  static const std::vector<RuntimeSymbol> symbols = {
      {"cncc_jit_rapid", reinterpret_cast<void*>(&cncc_jit_rapid)},
      {"cncc_jit_climb", reinterpret_cast<void*>(&cncc_jit_climb)},
      {"cncc_jit_feed", reinterpret_cast<void*>(&cncc_jit_feed)},
      {"cncc_jit_arc", reinterpret_cast<void*>(&cncc_jit_arc)},
      {"cncc_jit_nurbs_weight", reinterpret_cast<void*>(&cncc_jit_nurbs_weight)},
      {"cncc_jit_nurbs", reinterpret_cast<void*>(&cncc_jit_nurbs)},
      {"cncc_jit_spline", reinterpret_cast<void*>(&cncc_jit_spline)},
      {"cncc_jit_polynomial", reinterpret_cast<void*>(&cncc_jit_polynomial)},
      {"cncc_jit_spindle", reinterpret_cast<void*>(&cncc_jit_spindle)},
      {"cncc_jit_pass_begin", reinterpret_cast<void*>(&cncc_jit_pass_begin)},
      {"cncc_jit_corner_arc", reinterpret_cast<void*>(&cncc_jit_corner_arc)},
      {"cncc_jit_tool", reinterpret_cast<void*>(&cncc_jit_tool)},
      {"cncc_jit_setting", reinterpret_cast<void*>(&cncc_jit_setting)},
      {"cncc_jit_comment", reinterpret_cast<void*>(&cncc_jit_comment)},
      {"cncc_jit_alarm", reinterpret_cast<void*>(&cncc_jit_alarm)},
      {"cncc_jit_cut_begin", reinterpret_cast<void*>(&cncc_jit_cut_begin)},
      {"cncc_jit_table_index_error", reinterpret_cast<void*>(&cncc_jit_table_index_error)},
      {"cncc_jit_loop_bound_error", reinterpret_cast<void*>(&cncc_jit_loop_bound_error)},
      {"cncc_jit_loop_advance_error", reinterpret_cast<void*>(&cncc_jit_loop_advance_error)},
      {"cncc_jit_step_limit_error", reinterpret_cast<void*>(&cncc_jit_step_limit_error)},
      // The C library's functions, as the interpreter's std:: calls reach them.
      {"sin", reinterpret_cast<void*>(static_cast<Unary>(&::sin))},
      {"cos", reinterpret_cast<void*>(static_cast<Unary>(&::cos))},
      {"tan", reinterpret_cast<void*>(static_cast<Unary>(&::tan))},
      {"asin", reinterpret_cast<void*>(static_cast<Unary>(&::asin))},
      {"acos", reinterpret_cast<void*>(static_cast<Unary>(&::acos))},
      {"atan", reinterpret_cast<void*>(static_cast<Unary>(&::atan))},
      {"exp", reinterpret_cast<void*>(static_cast<Unary>(&::exp))},
      {"log", reinterpret_cast<void*>(static_cast<Unary>(&::log))},
      {"pow", reinterpret_cast<void*>(static_cast<Binary>(&::pow))},
      {"fmod", reinterpret_cast<void*>(static_cast<Binary>(&::fmod))},
      {"atan2", reinterpret_cast<void*>(static_cast<Binary>(&::atan2))},
  };
  return symbols;
}

} // namespace cncc::backends::jit
