#include "cncc/ir/tool_centre_path.h"

#include "cncc/geom/composite_curve.h"
#include "cncc/geom/line_arc_curves.h"
#include "cncc/geom/offset_curve.h"
#include "cncc/ir/interpreter.h"

#include <fmt/format.h>

#include <cmath>
#include <memory>
#include <optional>

namespace cncc::ir {

namespace {

using Kind = MachineEvent::Kind;

// The programmed moves of one compensated stretch.
struct CompensatedStretch {
  double offset = 0;
  std::vector<MachineEvent> moves;    // start-up, offset moves, cancel
  std::vector<MachineEvent> settings; // what else happened on the way
};

std::shared_ptr<const geom::Curve> pieceOf(const Eigen::Vector3d& from, const MachineEvent& move) {
  Eigen::Vector3d to(move.x, move.y, move.z);
  if (move.kind != Kind::Arc) {
    return std::make_shared<geom::LineCurve>(from, to);
  }
  return std::make_shared<geom::ArcCurve>(geom::ArcCurve::fromCentre(
      from, to, {move.centreX, move.centreY},
      move.clockwise ? geom::ArcDirection::Clockwise : geom::ArcDirection::CounterClockwise));
}

MachineEvent lineTo(const Eigen::Vector3d& point, const MachineEvent& model) {
  MachineEvent line = model;
  line.kind = model.kind == Kind::Rapid ? Kind::Rapid : Kind::Feed;
  line.x = point.x();
  line.y = point.y();
  line.z = point.z();
  return line;
}

// The offset path's lines and arcs as moves at `model`'s feed.
void appendOffsetMoves(const geom::Curve& offset, const MachineEvent& model,
                       std::vector<MachineEvent>& out) {
  std::vector<const geom::Curve*> parts = geom::piecesOf(offset);
  for (const geom::Curve* part : parts) {
    MachineEvent move = lineTo(part->point(part->domain().t1), model);
    if (const auto* arc = dynamic_cast<const geom::ArcCurve*>(part)) {
      move.kind = Kind::Arc;
      move.centreX = arc->centre().x();
      move.centreY = arc->centre().y();
      move.clockwise = arc->sweep() < 0;
    }
    out.push_back(move);
  }
}

void appendCompensated(const CompensatedStretch& stretch, std::vector<MachineEvent>& out) {
  out.insert(out.end(), stretch.settings.begin(), stretch.settings.end());
  if (stretch.moves.size() < 3 || stretch.moves.front().kind == Kind::Arc ||
      stretch.moves.back().kind == Kind::Arc) {
    throw InterpreterError("cutter radius compensation needs a linear start-up move, a move "
                           "it offsets and a linear cancel move");
  }
  std::vector<std::shared_ptr<const geom::Curve>> pieces;
  Eigen::Vector3d at(stretch.moves.front().x, stretch.moves.front().y, stretch.moves.front().z);
  for (std::size_t i = 1; i + 1 < stretch.moves.size(); ++i) {
    const MachineEvent& move = stretch.moves[i];
    Eigen::Vector3d to(move.x, move.y, move.z);
    if (to.z() != at.z()) {
      throw InterpreterError(fmt::format(
          "a move out of the plane to ({:g}, {:g}, {:g}) with cutter radius compensation on",
          move.x, move.y, move.z));
    }
    if ((to - at).head<2>().norm() > 0 || move.kind == Kind::Arc) {
      pieces.push_back(pieceOf(at, move));
    }
    at = to;
  }
  std::shared_ptr<const geom::Curve> offset;
  try {
    offset = geom::offsetOfPieces(pieces, stretch.offset);
  } catch (const geom::GeometryError& error) {
    throw InterpreterError(
        fmt::format("cutter radius compensation of {:g} cannot follow the path: {}",
                    std::fabs(stretch.offset), error.what()));
  }
  const MachineEvent& startUp = stretch.moves.front();
  out.push_back(lineTo(offset->point(offset->domain().t0), startUp));
  appendOffsetMoves(*offset, stretch.moves[1], out);
  out.push_back(stretch.moves.back()); // cancel: to its uncompensated end
}

} // namespace

ToolPath toolCentrePath(const ToolPath& programmed) {
  ToolPath centre;
  std::optional<CompensatedStretch> stretch;
  bool cancelling = false;
  for (const MachineEvent& event : programmed.events) {
    if (event.kind == Kind::Compensation) {
      if (event.number != 0 && !stretch) {
        stretch = CompensatedStretch{event.number, {}, {}};
      } else if (event.number == 0 && stretch) {
        cancelling = true;
      } else {
        throw InterpreterError("cutter radius compensation switched on twice or off twice");
      }
      continue;
    }
    if (event.kind == Kind::CornerArc) {
      // The offset pieces already go round every convex corner on an arc of
      // the radius about it, which G39 runs.
      if (!stretch || cancelling || stretch->moves.size() < 2) {
        throw InterpreterError("a corner arc (G39) needs cutter radius compensation on and a "
                               "compensated move before it");
      }
      continue;
    }
    if (!stretch) {
      centre.events.push_back(event);
      continue;
    }
    if (!isMove(event)) {
      stretch->settings.push_back(event);
      continue;
    }
    stretch->moves.push_back(event);
    if (cancelling) {
      appendCompensated(*stretch, centre.events);
      stretch.reset();
      cancelling = false;
    }
  }
  if (stretch) {
    throw InterpreterError("cutter radius compensation is still on at the end of the program");
  }
  return centre;
}

} // namespace cncc::ir
