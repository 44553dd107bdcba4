// Parts compiled for the sinumerik target in tests: CDL text checked,
// lowered for a spline target, run on the host and written as a program.
#pragma once

#include "cncc/backends/sinumerik_controller.h"
#include "cncc/backends/sinumerik_writer.h"
#include "cncc/frontend/sema.h"
#include "cncc/frontend/source_manager.h"
#include "cncc/geom/curve_deviation.h"
#include "cncc/ir/interpreter.h"
#include "cncc/lowering/lowering.h"

#include <gtest/gtest.h>

#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

namespace cncc::testing {

// The program stays alive because analytic cut curves evaluate its expressions.
struct SinumerikPart {
  frontend::SourceManager sources;
  frontend::DiagnosticEngine diagnostics;
  std::optional<frontend::CheckedProgram> program;
  std::vector<ir::CutGeometry> cuts;
  ir::Function function; // as lowered
  ir::ToolPath path;
  backends::SinumerikProgram output;
};

inline std::string exampleText(const std::string& name) {
  std::ifstream file(std::string(CNCC_SOURCE_DIR) + "/examples/" + name);
  std::stringstream text;
  text << file.rdbuf();
  return text.str();
}

// `text` with the first `from` replaced by `to`.
inline std::string replaced(std::string text, const std::string& from, const std::string& to) {
  std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return at == std::string::npos ? text : text.replace(at, from.size(), to);
}

inline std::unique_ptr<SinumerikPart> compileForSinumerik(const std::string& text,
                                                          backends::SinumerikOptions options = {},
                                                          const std::string& partName = {}) {
  auto part = std::make_unique<SinumerikPart>();
  frontend::FileId file = part->sources.addFile("part.cdl", text);
  frontend::CheckOptions check;
  check.importPaths = {CNCC_STDLIB_DIR};
  check.requirePart = true;
  check.partName = partName;
  part->program = frontend::checkProgram(part->sources, file, check, part->diagnostics);
  if (part->diagnostics.hasErrors() || part->program->selectedPart == nullptr) {
    ADD_FAILURE() << "the part does not check";
    return nullptr;
  }
  ir::LoweringOptions lowering = backends::sinumerikLoweringOptions(options);
  std::optional<ir::LoweredPart> lowered = ir::lowerPartWithCuts(
      *part->program, *part->program->selectedPart, part->diagnostics, lowering);
  if (!lowered) {
    ADD_FAILURE() << "the part does not lower";
    return nullptr;
  }
  part->function = lowered->function;
  part->path = ir::interpret(lowered->function);
  part->cuts = std::move(lowered->function.cuts);
  part->output =
      backends::writeSinumerik(part->path, part->function.tables, part->cuts.size(), options);
  return part;
}

// Lines of `text` that start with `prefix`.
inline std::size_t countLines(const std::string& text, const std::string& prefix) {
  std::size_t count = 0;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    count += line.rfind(prefix, 0) == 0 ? 1 : 0;
  }
  return count;
}

// A curve seen from above: z = 0.
class PlanView : public geom::Curve {
public:
  explicit PlanView(const geom::Curve& curve) : curve_(curve) {}
  geom::ParameterRange domain() const override { return curve_.domain(); }
  Eigen::Vector3d point(double t) const override { return flat(curve_.point(t)); }
  Eigen::Vector3d derivative(double t) const override { return flat(curve_.derivative(t)); }
  Eigen::Vector3d secondDerivative(double t) const override {
    return flat(curve_.secondDerivative(t));
  }
  std::vector<double> breakpoints() const override { return curve_.breakpoints(); }

private:
  static Eigen::Vector3d flat(Eigen::Vector3d v) {
    v.z() = 0;
    return v;
  }
  const geom::Curve& curve_;
};

// The largest deviation in XY of the splines the run cut from `curve` (both ways).
inline double splineDeviation(const backends::sinumerik::SinumerikRun& run,
                              const geom::Curve& curve, double accuracy) {
  double largest = 0;
  for (const backends::sinumerik::ExecutedSpline& spline : run.splines) {
    PlanView plan(*spline.curve);
    largest =
        std::max(largest, geom::measureCurveDeviation(plan, curve, {accuracy}).maxDeviation());
  }
  return largest;
}

} // namespace cncc::testing
