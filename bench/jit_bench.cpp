// The IR interpreter against the LLVM JIT on the S-profile NURBS of
// examples/s_profile.cdl (reference case 1), lowered with `samples=1000000`
// in place of `tolerance=0.01` and one pass (-D depth=1): one run evaluates
// the rational cubic at 1,000,000 parameter values (four span loops over
// tables of parameters) and records a feed move for each. The JIT runs into
// a fresh tool path, into a reused one, and streamed to a consumer that
// measures the path (length and bounding box) without storing it. When
// OpenCASCADE was found at build time, its Geom_BSplineCurve::D0 evaluates
// the same curve at the same parameter values into the same measure.
// Reported: points per second and ns per point for each; after the runs,
// the ratios.
//
//   build/bench/jit_bench                  (all, and the ratios)
//   build/bench/jit_bench --benchmark_filter=jit
#include "cncc/frontend/sema.h"
#include "cncc/frontend/source_manager.h"
#include "cncc/ir/interpreter.h"
#include "cncc/ir/machine_event_sink.h"
#include "cncc/lowering/lowering.h"
#ifdef CNCC_HAVE_JIT
#include "cncc/backends/jit_compiler.h"
#endif
#ifdef CNCC_HAVE_OCCT
#include <Geom_BSplineCurve.hxx>
#include <Standard_Handle.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColgp_Array1OfPnt.hxx>
#include <gp_Pnt.hxx>
#endif

#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>

namespace {

using namespace cncc;

constexpr int kSamples = 1'000'000;

std::string sProfileSource() {
  std::ifstream file(std::string(CNCC_SOURCE_DIR) + "/examples/s_profile.cdl");
  std::stringstream text;
  text << file.rdbuf();
  std::string source = text.str();
  std::string tolerance = "tolerance=0.01";
  std::size_t at = source.find(tolerance);
  if (at == std::string::npos) {
    throw std::runtime_error("examples/s_profile.cdl has no `tolerance=0.01` to replace");
  }
  return source.replace(at, tolerance.size(), "samples=" + std::to_string(kSamples));
}

const ir::Function& sProfileFunction() {
  static const ir::Function function = [] {
    frontend::SourceManager sources;
    frontend::DiagnosticEngine diagnostics;
    frontend::FileId file = sources.addFile("s_profile_1m.cdl", sProfileSource());
    frontend::CheckOptions options;
    options.importPaths = {CNCC_STDLIB_DIR};
    options.requirePart = true;
    options.defines["depth"] = 1;
    frontend::CheckedProgram program = frontend::checkProgram(sources, file, options, diagnostics);
    std::optional<ir::Function> lowered =
        diagnostics.hasErrors() || program.selectedPart == nullptr
            ? std::nullopt
            : ir::lowerPart(program, *program.selectedPart, diagnostics);
    if (!lowered) {
      throw std::runtime_error("the 1,000,000-sample S-profile does not lower");
    }
    return *lowered;
  }();
  return function;
}

std::size_t feedMoves(const ir::ToolPath& path) {
  std::size_t count = 0;
  for (const ir::MachineEvent& event : path.events) {
    count += event.kind == ir::MachineEvent::Kind::Feed ? 1 : 0;
  }
  return count;
}

// The cheap, real work a consumer of the points does: the length of the
// feed path and its bounding box (so that no evaluation is optimised away).
struct PathMeasure {
  std::size_t points = 0;
  double length = 0;
  std::array<double, 3> last{0, 0, 0};
  std::array<double, 3> low{HUGE_VAL, HUGE_VAL, HUGE_VAL};
  std::array<double, 3> high{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};

  void add(double x, double y, double z) {
    if (points > 0) {
      length += std::sqrt((x - last[0]) * (x - last[0]) + (y - last[1]) * (y - last[1]) +
                          (z - last[2]) * (z - last[2]));
    }
    last = {x, y, z};
    low = {std::min(low[0], x), std::min(low[1], y), std::min(low[2], z)};
    high = {std::max(high[0], x), std::max(high[1], y), std::max(high[2], z)};
    ++points;
  }
};

// Measures a run's feed moves as they are made.
class MeasuringSink : public ir::MachineEventSink {
public:
  void event(const ir::MachineEvent& event) override {
    if (event.kind == ir::MachineEvent::Kind::Feed) {
      measure.add(event.x, event.y, event.z);
    }
  }
  PathMeasure measure;
};

void reportMeasure(benchmark::State& state, const PathMeasure& measure) {
  state.counters["length_mm"] = measure.length;
  state.counters["box_x_mm"] = measure.high[0] - measure.low[0];
  state.counters["box_y_mm"] = measure.high[1] - measure.low[1];
}

void reportPoints(benchmark::State& state, std::size_t pointsPerRun) {
  double points = static_cast<double>(pointsPerRun) * static_cast<double>(state.iterations());
  state.counters["points"] = static_cast<double>(pointsPerRun);
  state.counters["points_per_second"] = benchmark::Counter(points, benchmark::Counter::kIsRate);
  state.counters["ns_per_point"] =
      benchmark::Counter(points / 1e9, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void interpreter(benchmark::State& state) {
  const ir::Function& function = sProfileFunction();
  std::size_t points = 0;
  for (auto _ : state) {
    ir::ToolPath path = ir::interpret(function);
    points = feedMoves(path);
    benchmark::DoNotOptimize(path.events.data());
  }
  reportPoints(state, points);
}
BENCHMARK(interpreter)->Name("s_profile_1m/interpreter")->Unit(benchmark::kMillisecond);

#ifdef CNCC_HAVE_JIT
void jit(benchmark::State& state) {
  backends::CompiledFunction compiled(sProfileFunction());
  std::size_t points = 0;
  for (auto _ : state) {
    ir::ToolPath path = compiled.run();
    points = feedMoves(path);
    benchmark::DoNotOptimize(path.events.data());
  }
  reportPoints(state, points);
}
BENCHMARK(jit)->Name("s_profile_1m/jit")->Unit(benchmark::kMillisecond);

// The same into one tool path reused across runs: no allocation and no page
// faults for the 144 MB of events, only evaluating and appending. One run
// before the timed ones faults the storage in (on this machine's virtual
// machine a first touch of memory can take a second for 144 MB, and
// would be the whole measurement of a benchmark that runs once).
void jitReusedPath(benchmark::State& state) {
  backends::CompiledFunction compiled(sProfileFunction());
  ir::ToolPath path;
  compiled.run({}, path);
  for (auto _ : state) {
    compiled.run({}, path);
    benchmark::DoNotOptimize(path.events.data());
  }
  reportPoints(state, feedMoves(path));
}
BENCHMARK(jitReusedPath)->Name("s_profile_1m/jit_reused_path")->Unit(benchmark::kMillisecond);

// The same streamed to a consumer that measures the path as the events are
// made: none stored, so no memory traffic for them.
void jitStream(benchmark::State& state) {
  backends::CompiledFunction compiled(sProfileFunction());
  MeasuringSink sink;
  for (auto _ : state) {
    sink = MeasuringSink();
    compiled.run({}, sink);
    benchmark::DoNotOptimize(&sink.measure);
    benchmark::ClobberMemory();
  }
  reportPoints(state, sink.measure.points);
  reportMeasure(state, sink.measure);
}
BENCHMARK(jitStream)->Name("s_profile_1m/jit_stream")->Unit(benchmark::kMillisecond);

// Compiling once (LLVM O2 and code generation, the 8 MB of tables included).
void jitCompile(benchmark::State& state) {
  const ir::Function& function = sProfileFunction();
  for (auto _ : state) {
    backends::CompiledFunction compiled(function);
    benchmark::DoNotOptimize(&compiled);
  }
}
BENCHMARK(jitCompile)->Name("s_profile_1m/jit_compile")->Unit(benchmark::kMillisecond);
#endif

#ifdef CNCC_HAVE_OCCT
// examples/s_profile.cdl's curve as OpenCASCADE's B-spline: degree 3, the
// seven control points, weight w6 = 3 (the default) on the sixth, clamped
// uniform knots on [0, 1] (the parameters of cncc's NURBS).
Handle(Geom_BSplineCurve) occtSProfile() {
  const double points[7][2] = {{25, 50},           {42.8735, 24.1467},  {70.5832, 72.3597},
                               {86.608, 165.3624}, {112.4532, 38.3852}, {132.4671, 35.1148},
                               {175, 150}};
  TColgp_Array1OfPnt poles(1, 7);
  TColStd_Array1OfReal weights(1, 7);
  for (int i = 0; i < 7; ++i) {
    poles.SetValue(i + 1, gp_Pnt(points[i][0], points[i][1], -1));
    weights.SetValue(i + 1, i == 5 ? 3.0 : 1.0);
  }
  TColStd_Array1OfReal knots(1, 5);
  TColStd_Array1OfInteger multiplicities(1, 5);
  for (int i = 0; i < 5; ++i) {
    knots.SetValue(i + 1, i / 4.0);
    multiplicities.SetValue(i + 1, i == 0 || i == 4 ? 4 : 1);
  }
  return new Geom_BSplineCurve(poles, weights, knots, multiplicities, 3);
}

// The parameter of sample i of kSamples, as samples= spaces them
// (geom::sampleUniformParameter): equal steps, the last exactly the end.
double sampleParameter(int i) {
  return i + 1 == kSamples ? 1.0 : static_cast<double>(i) / static_cast<double>(kSamples - 1);
}

// The largest distance between OpenCASCADE's points and the feed moves the
// interpreter records (the plunge onto the start, then the curve): shows
// that both evaluate the same curve at the same parameters.
double largestDeviationFromInterpreter(const Geom_BSplineCurve& curve) {
  static const ir::ToolPath path = ir::interpret(sProfileFunction());
  double largest = 0;
  int i = 0;
  for (const ir::MachineEvent& event : path.events) {
    if (event.kind != ir::MachineEvent::Kind::Feed) {
      continue;
    }
    if (i == kSamples) {
      return HUGE_VAL;
    }
    gp_Pnt point;
    curve.D0(sampleParameter(i++), point);
    largest = std::max({largest, std::abs(point.X() - event.x), std::abs(point.Y() - event.y),
                        std::abs(point.Z() - event.z)});
  }
  return i == kSamples ? largest : HUGE_VAL;
}

void occtD0(benchmark::State& state) {
  Handle(Geom_BSplineCurve) curve = occtSProfile();
  double deviation = largestDeviationFromInterpreter(*curve);
  if (!(deviation < 1e-9)) {
    state.SkipWithError("OpenCASCADE's curve is not the S-profile the interpreter evaluates");
    return;
  }
  PathMeasure measure;
  for (auto _ : state) {
    measure = PathMeasure();
    gp_Pnt point;
    for (int i = 0; i < kSamples; ++i) {
      curve->D0(sampleParameter(i), point);
      measure.add(point.X(), point.Y(), point.Z());
    }
    benchmark::DoNotOptimize(&measure);
    benchmark::ClobberMemory();
  }
  reportPoints(state, measure.points);
  reportMeasure(state, measure);
  state.counters["deviation_mm"] = deviation;
}
BENCHMARK(occtD0)->Name("s_profile_1m/occt_d0")->Unit(benchmark::kMillisecond);
#endif

// Prints as the console does, and keeps each run's ns per point for the ratio.
class RatioReporter : public benchmark::ConsoleReporter {
public:
  void ReportRuns(const std::vector<Run>& runs) override {
    ConsoleReporter::ReportRuns(runs);
    for (const Run& run : runs) {
      auto found = run.counters.find("ns_per_point");
      if (found != run.counters.end() && run.run_type == Run::RT_Iteration) {
        nsPerPoint_[run.run_name.function_name].push_back(found->second.value);
      }
    }
  }

  void printRatios() const {
    for (const char* name :
         {"s_profile_1m/jit", "s_profile_1m/jit_reused_path", "s_profile_1m/jit_stream"}) {
      printRatio("s_profile_1m/interpreter", name);
    }
    printRatio("s_profile_1m/occt_d0", "s_profile_1m/jit_stream");
  }

private:
  // Runs of one benchmark (repetitions) compare by their median.
  void printRatio(const std::string& slower, const std::string& faster) const {
    std::optional<double> slow = median(slower);
    std::optional<double> fast = median(faster);
    if (slow && fast) {
      std::printf("%s %.2f ns/point, %s %.2f ns/point: %.1fx\n", slower.c_str(), *slow,
                  faster.c_str(), *fast, *slow / *fast);
    }
  }

  std::optional<double> median(const std::string& name) const {
    auto found = nsPerPoint_.find(name);
    if (found == nsPerPoint_.end() || found->second.empty()) {
      return std::nullopt;
    }
    std::vector<double> values = found->second;
    std::sort(values.begin(), values.end());
    return values[values.size() / 2];
  }

  std::map<std::string, std::vector<double>> nsPerPoint_;
};

} // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) {
    return 1;
  }
  RatioReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  reporter.printRatios();
  benchmark::Shutdown();
  return 0;
}
