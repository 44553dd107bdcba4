#include "parallel_work.h"

namespace cncc::frontend {

namespace {

// Below this much part source (some 1,500 lines) starting a thread costs
// more than it saves.
constexpr std::size_t minimumParallelBytes = 64 * 1024;

std::size_t sourceBytes(const PartItem& part) {
  return part.span.end - part.span.begin;
}

} // namespace

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
