#include "jit_runtime.h"

#include "cncc/ir/interpreter.h"
#include "cncc/ir/nurbs_move.h"
#include "cncc/ir/polynomial_move.h"
#include "cncc/ir/spline_move.h"

#include <fmt/format.h>

#include <array>
#include <cmath>

namespace cncc::backends::jit {

namespace {

// Records an event; an exception (out of memory) must not unwind through the
// native code, so it is kept for the caller and reported as a failure.
template <typename MakeEvent> std::int32_t record(RunContext* context, MakeEvent makeEvent) {
  try {
    context->events->push_back(makeEvent());
    return 0;
  } catch (...) {
    context->exception = std::current_exception();
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

// Where the last move ended (the origin before any).
std::array<double, 3> lastPosition(const RunContext& context) {
  for (auto event = context.events->rbegin(); event != context.events->rend(); ++event) {
    if (event->kind == ir::MachineEvent::Kind::Rapid ||
        event->kind == ir::MachineEvent::Kind::Feed || event->kind == ir::MachineEvent::Kind::Arc) {
      return {event->x, event->y, event->z};
    }
  }
  return {0, 0, 0};
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

static std::int32_t cncc_jit_feed(RunContext* context, double x, double y, double z, double feed) {
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
    return ir::arcMove(lastPosition(*context), static_cast<ir::ArcTurn>(turn), x, y, z, i, j, feed);
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
  if (context->exception) {
    return 1;
  }
  try {
    std::vector<double> weights = std::move(context->nurbsWeights);
    context->nurbsWeights.clear();
    ir::nurbsMove(lastPosition(*context), (*context->tables)[table], z, feed, weights,
                  *context->events);
    return 0;
  } catch (...) {
    context->exception = std::current_exception();
    return 1;
  }
}

// `move.polynomial`, as the interpreter's polynomialMove records it.
static std::int32_t cncc_jit_polynomial(RunContext* context, double x, double y, double z,
                                        double k3x, double k2x, double k1x, double k3y, double k2y,
                                        double k1y, double k3z, double k2z, double k1z,
                                        double feed) {
  if (context->exception) {
    return 1;
  }
  try {
    std::array<double, 12> values{x, y, z, k3x, k2x, k1x, k3y, k2y, k1y, k3z, k2z, k1z};
    ir::polynomialMove(lastPosition(*context), ir::polynomialMoveOf(values), feed,
                       *context->events);
    return 0;
  } catch (...) {
    context->exception = std::current_exception();
    return 1;
  }
}

// `move.spline`, as the interpreter's splineMove records it.
static std::int32_t cncc_jit_spline(RunContext* context, std::uint32_t table, double z,
                                    double feed) {
  if (context->exception) {
    return 1;
  }
  try {
    ir::splineMove(table, (*context->tables)[table], z, feed, *context->events);
    return 0;
  } catch (...) {
    context->exception = std::current_exception();
    return 1;
  }
}

static std::int32_t cncc_jit_spindle(RunContext* context, double speed) {
  return record(context, [&] {
    ir::MachineEvent event;
    event.kind = ir::MachineEvent::Kind::Spindle;
    event.number = speed;
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
      {"cncc_jit_feed", reinterpret_cast<void*>(&cncc_jit_feed)},
      {"cncc_jit_arc", reinterpret_cast<void*>(&cncc_jit_arc)},
      {"cncc_jit_nurbs_weight", reinterpret_cast<void*>(&cncc_jit_nurbs_weight)},
      {"cncc_jit_nurbs", reinterpret_cast<void*>(&cncc_jit_nurbs)},
      {"cncc_jit_spline", reinterpret_cast<void*>(&cncc_jit_spline)},
      {"cncc_jit_polynomial", reinterpret_cast<void*>(&cncc_jit_polynomial)},
      {"cncc_jit_spindle", reinterpret_cast<void*>(&cncc_jit_spindle)},
      {"cncc_jit_tool", reinterpret_cast<void*>(&cncc_jit_tool)},
      {"cncc_jit_setting", reinterpret_cast<void*>(&cncc_jit_setting)},
      {"cncc_jit_comment", reinterpret_cast<void*>(&cncc_jit_comment)},
      {"cncc_jit_alarm", reinterpret_cast<void*>(&cncc_jit_alarm)},
      {"cncc_jit_cut_begin", reinterpret_cast<void*>(&cncc_jit_cut_begin)},
      {"cncc_jit_table_index_error", reinterpret_cast<void*>(&cncc_jit_table_index_error)},
      {"cncc_jit_loop_bound_error", reinterpret_cast<void*>(&cncc_jit_loop_bound_error)},
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
