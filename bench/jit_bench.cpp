// The IR interpreter against the LLVM JIT on the S-profile NURBS of
// examples/s_profile.cdl (reference case 1), lowered with `samples=1000000`
// in place of `tolerance=0.01` and one pass (-D depth=1): one run evaluates
// the rational cubic at 1,000,000 parameter values (four span loops over
// tables of parameters) and records a feed move for each. Reported: points
// per second and ns per point for each; after the runs, the ratio.
//
//   build/bench/jit_bench                  (both, and the ratio)
//   build/bench/jit_bench --benchmark_filter=jit
#include "cncc/frontend/sema.h"
#include "cncc/frontend/source_manager.h"
#include "cncc/ir/interpreter.h"
#include "cncc/lowering/lowering.h"
#ifdef CNCC_HAVE_JIT
#include "cncc/backends/jit_compiler.h"
#endif

#include <benchmark/benchmark.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <map>
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
// faults for the 80 MB of events, only evaluating and appending.
void jitReusedPath(benchmark::State& state) {
  backends::CompiledFunction compiled(sProfileFunction());
  ir::ToolPath path;
  for (auto _ : state) {
    compiled.run({}, path);
    benchmark::DoNotOptimize(path.events.data());
  }
  reportPoints(state, feedMoves(path));
}
BENCHMARK(jitReusedPath)->Name("s_profile_1m/jit_reused_path")->Unit(benchmark::kMillisecond);

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

// Prints as the console does, and keeps each run's ns per point for the ratio.
class RatioReporter : public benchmark::ConsoleReporter {
public:
  void ReportRuns(const std::vector<Run>& runs) override {
    ConsoleReporter::ReportRuns(runs);
    for (const Run& run : runs) {
      auto found = run.counters.find("ns_per_point");
      if (found != run.counters.end() && run.run_type == Run::RT_Iteration) {
        nsPerPoint_[run.benchmark_name()] = found->second.value;
      }
    }
  }

  void printRatios() const {
    for (const char* name : {"s_profile_1m/jit", "s_profile_1m/jit_reused_path"}) {
      auto interpreted = nsPerPoint_.find("s_profile_1m/interpreter");
      auto compiled = nsPerPoint_.find(name);
      if (interpreted != nsPerPoint_.end() && compiled != nsPerPoint_.end()) {
        std::printf("interpreter %.2f ns/point, %s %.2f ns/point: %.1fx\n", interpreted->second,
                    name, compiled->second, interpreted->second / compiled->second);
      }
    }
  }

private:
  std::map<std::string, double> nsPerPoint_;
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
