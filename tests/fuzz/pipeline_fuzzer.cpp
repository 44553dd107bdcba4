// libFuzzer entry point for the whole pipeline: the fuzzed source is
// compiled for a target as `cncc FILE -t TARGET` does (each input picks one,
// so every target is fuzzed), and where the target has an executor, run and
// measured as `cncc verify` does (LinuxCNC's rs274 is another program: its
// target is compiled only).
//
// The contract under test (issue: every run is bounded): no input crashes
// the compiler, ends in an internal error, or runs a target longer than the
// budget below; a bad input is refused with a diagnostic. The custom mutator
// (cdl_mutator.h) makes the changes a user's typo makes: extreme numbers,
// dropped arguments, swapped statements.
//
// The input is written to a file of its own in a temporary directory and
// the standard library is the only other import path; an input whose
// imports are absolute or climb with ".." is skipped, so a run never reads
// files of the machine it runs on. Run it with -close_fd_mask=3: the driver
// prints its programs and diagnostics, and libFuzzer keeps the sanitizers'
// reports visible.
#include "cdl_mutator.h"
#include "commands.h"
#include "contained_imports.h"
#include "driver_options.h"

#include "cncc/frontend/diagnostics.h"
#include "cncc/frontend/lexer.h"
#include "cncc/frontend/source_manager.h"

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <functional>
#include <iterator>
#include <random>
#include <string>
#include <string_view>
#include <vector>

#include <unistd.h>

extern "C" std::size_t LLVMFuzzerMutate(std::uint8_t* data, std::size_t size, std::size_t maxSize);
// Writes to the sanitizers' report file, which -close_fd_mask leaves open.
extern "C" void __sanitizer_report_error_summary(const char* summary) __attribute__((weak));

namespace {

using namespace cncc;

// A run of one target that takes longer than this is a runaway: the goal is
// 5 s on the test machine; sanitizers and coverage make it several times
// slower (20-30 times for the measurement of a long path), so CI, which runs
// the fuzzer under them, sets a larger budget in CNCC_PIPELINE_BUDGET_SECONDS.
double budgetSeconds() {
  static const double seconds = [] {
    const char* text = std::getenv("CNCC_PIPELINE_BUDGET_SECONDS");
    double value = text != nullptr ? std::atof(text) : 0.0;
    return value > 0 ? value : 30.0;
  }();
  return seconds;
}
// Larger inputs are not parts a user writes; they only slow the fuzzer down.
constexpr std::size_t largestInput = 16 * 1024;

constexpr const char* targets[] = {"m80",        "fanuc", "sinumerik", "gcode",
                                   "heidenhain", "jit",   "linuxcnc"};

[[noreturn]] void fail(const std::string& what) {
  std::string message = "pipeline_fuzzer: invariant broken: " + what;
  if (__sanitizer_report_error_summary != nullptr) {
    __sanitizer_report_error_summary(message.c_str());
  }
  std::fprintf(stderr, "%s\n", message.c_str());
  std::abort();
}

const std::string& inputPath() {
  static const std::string path = [] {
    char directory[] = "/tmp/cncc-pipeline-fuzzer-XXXXXX";
    if (mkdtemp(directory) == nullptr) {
      fail("cannot create a temporary directory");
    }
    return std::string(directory) + "/input.cdl";
  }();
  return path;
}

// The imports stay in the repository, and the first part's name (compiling
// needs one when a file has several).
struct SourceFacts {
  bool importsContained = true;
  std::string firstPart;
};

SourceFacts sourceFacts(const std::string& text) {
  frontend::SourceManager sources;
  frontend::FileId file = sources.addFile(inputPath(), text);
  frontend::DiagnosticEngine diagnostics(50);
  std::vector<frontend::Token> tokens = frontend::lex(sources, file, diagnostics);
  SourceFacts facts;
  for (std::size_t i = 0; i + 1 < tokens.size(); ++i) {
    if (tokens[i].kind == frontend::TokenKind::KwImport &&
        tokens[i + 1].kind == frontend::TokenKind::String &&
        !fuzz::isContainedImport(tokens[i + 1].text)) {
      facts.importsContained = false;
    }
    if (facts.firstPart.empty() && tokens[i].kind == frontend::TokenKind::KwPart &&
        tokens[i + 1].kind == frontend::TokenKind::Identifier) {
      facts.firstPart = std::string(tokens[i + 1].text);
    }
  }
  return facts;
}

// Runs the driver on `arguments` as `cncc` would, within the budget.
void runDriver(std::vector<std::string> arguments, const char* target) {
  std::vector<const char*> argv;
  for (const std::string& argument : arguments) {
    argv.push_back(argument.c_str());
  }
  auto start = std::chrono::steady_clock::now();
  driver::ParsedCommandLine commandLine =
      driver::parseCommandLine(static_cast<int>(argv.size()), argv.data());
  if (!commandLine.options) {
    fail(std::string("the driver refused its own command line for -t ") + target);
  }
  try {
    driver::runCommand(*commandLine.options);
  } catch (const driver::InternalError& error) {
    fail(std::string("internal error for -t ") + target + ": " + error.what());
  }
  double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (seconds > budgetSeconds()) {
    fail(std::string(arguments[1]) + " -t " + target + " took " + std::to_string(seconds) +
         " s, over the budget of " + std::to_string(budgetSeconds()) + " s");
  }
}

// Compiles the input for `target`, and verifies it where the target has an
// executor of its own.
void runTarget(const char* target, const SourceFacts& facts) {
  std::vector<std::string> arguments;
  if (driver::canVerify(target) && std::strcmp(target, "linuxcnc") != 0) {
    arguments = {"cncc", "verify", inputPath(), "-t", target};
  } else {
    arguments = {"cncc", inputPath(), "-t", target, "-o", "/dev/null"};
  }
  if (!facts.firstPart.empty()) {
    arguments.insert(arguments.end(), {"-p", facts.firstPart});
  }
  runDriver(std::move(arguments), target);
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > largestInput) {
    return 0;
  }
  std::string text(reinterpret_cast<const char*>(data), size);
  SourceFacts facts = sourceFacts(text);
  if (!facts.importsContained) {
    return 0;
  }
  {
    std::ofstream file(inputPath(), std::ios::binary | std::ios::trunc);
    file << text;
  }
  // One target per input, chosen by the input's bytes: a mutation moves it
  // to another target, so the targets share the executions, and one input
  // costs at most one target's budget. CNCC_PIPELINE_ALL_TARGETS=1 (the
  // seeds' test) runs every target on each input.
  if (std::getenv("CNCC_PIPELINE_ALL_TARGETS") != nullptr) {
    for (const char* target : targets) {
      runTarget(target, facts);
    }
  } else {
    runTarget(targets[std::hash<std::string>{}(text) % std::size(targets)], facts);
  }
  return 0;
}

// Three mutations in four are structured (cdl_mutator.h), the rest
// libFuzzer's own byte-level ones.
extern "C" std::size_t LLVMFuzzerCustomMutator(std::uint8_t* data, std::size_t size,
                                               std::size_t maxSize, unsigned int seed) {
  std::mt19937 random(seed);
  if (random() % 4 == 0) {
    return LLVMFuzzerMutate(data, size, maxSize);
  }
  std::string mutated =
      fuzz::mutateCdl(std::string_view(reinterpret_cast<const char*>(data), size), random);
  if (mutated.size() > maxSize) {
    return LLVMFuzzerMutate(data, size, maxSize);
  }
  std::memcpy(data, mutated.data(), mutated.size());
  return mutated.size();
}
