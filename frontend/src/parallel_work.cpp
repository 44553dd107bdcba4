#include "parallel_work.h"

#include "cncc/frontend/parser.h"

#include <algorithm>
#include <array>
#include <string_view>

namespace cncc::frontend {

namespace {

// Below this much part source (some 1,500 lines) starting a thread costs
// more than it saves.
constexpr std::size_t minimumParallelBytes = 64 * 1024;

// Below this size a file is parsed on one thread.
constexpr std::size_t minimumParallelFileBytes = 128 * 1024;
// How far past the middle a split is looked for.
constexpr std::size_t splitSearchBytes = 64 * 1024;

std::size_t sourceBytes(const PartItem& part) {
  return part.span.end - part.span.begin;
}

// Whether a line starts a file-level item: no token of the item before it
// can go on with these words, so parsing the text before the line and the
// text from it apart gives the items of parsing them together (when
// neither has a problem: a split inside a comment or a part's braces has
// one).
bool startsItem(std::string_view line) {
  static constexpr std::array<std::string_view, 4> words = {"part ", "fn ", "const ", "import "};
  for (std::string_view word : words) {
    if (line.starts_with(word)) {
      return true;
    }
  }
  return false;
}

// The offset of a line past the middle of `text` that starts an item, or 0.
std::size_t itemLineNearMiddle(std::string_view text) {
  std::size_t limit = std::min(text.size(), text.size() / 2 + splitSearchBytes);
  for (std::size_t newline = text.find('\n', text.size() / 2);
       newline != std::string_view::npos && newline < limit;
       newline = text.find('\n', newline + 1)) {
    if (startsItem(text.substr(newline + 1, 8))) {
      return newline + 1;
    }
  }
  return 0;
}

} // namespace

Module parseModule(const SourceManager& sources, FileId file, DiagnosticEngine& diagnostics,
                   const CheckOptions& options) {
  std::string_view text = sources.file(file).text();
  bool large = text.size() >= minimumParallelFileBytes || options.threads >= 2;
  std::size_t split = large && twoThreadsAllowed(options) ? itemLineNearMiddle(text) : 0;
  if (split == 0) {
    return parseFile(sources, file, diagnostics);
  }
  auto middle = static_cast<std::uint32_t>(split);
  auto end = static_cast<std::uint32_t>(text.size());
  DiagnosticEngine firstDiagnostics(0);
  DiagnosticEngine secondDiagnostics(0);
  Module first;
  Module second;
  runAlongside([&] { second = parseFileRange(sources, file, middle, end, secondDiagnostics); },
               [&] { first = parseFileRange(sources, file, 0, middle, firstDiagnostics); });
  if (!firstDiagnostics.diagnostics().empty() || !secondDiagnostics.diagnostics().empty()) {
    return parseFile(sources, file, diagnostics);
  }
  appendModule(first, std::move(second));
  return first;
}

bool twoThreadsAllowed(const CheckOptions& options) {
  if (options.threads != 0) {
    return options.threads >= 2;
  }
  return std::thread::hardware_concurrency() >= 2;
}

std::size_t partSplit(std::span<const PartItem* const> parts, const CheckOptions& options) {
  if (parts.size() < 2 || !twoThreadsAllowed(options)) {
    return 0;
  }
  std::size_t total = 0;
  for (const PartItem* part : parts) {
    total += sourceBytes(*part);
  }
  if (total < minimumParallelBytes && options.threads == 0) {
    return 0;
  }
  std::size_t firstBytes = 0;
  std::size_t split = 0;
  while (split + 1 < parts.size() && 2 * (firstBytes + sourceBytes(*parts[split])) <= total) {
    firstBytes += sourceBytes(*parts[split++]);
  }
  return split == 0 ? 1 : split;
}

} // namespace cncc::frontend
