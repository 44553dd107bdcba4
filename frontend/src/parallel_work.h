// Work on two threads for large files (private to the front end). Each
// phase that uses it gives the result that doing the work in order gives;
// the second thread only shortens the wall time.
#pragma once

#include "cncc/frontend/sema.h"

#include <cstddef>
#include <exception>
#include <span>
#include <thread>
#include <vector>

namespace cncc::frontend {

// Runs `other` on a second thread while `here` runs on this one, and
// returns when both have finished; an exception from either is rethrown
// here after both have stopped.
template <typename Other, typename Here> void runAlongside(Other&& other, Here&& here) {
  std::exception_ptr otherFailure;
  {
    std::jthread thread([&] {
      try {
        other();
      } catch (...) {
        otherFailure = std::current_exception();
      }
    });
    here(); // the thread joins when it goes out of scope, also on an exception
  }
  if (otherFailure) {
    std::rethrow_exception(otherFailure);
  }
}

// Lexes and parses `file`; a large one as two halves on two threads, split
// before a file-level item near the middle. The module is the one parsing
// the whole file gives: when either half has a problem (which near the
// split could read differently), the whole file is parsed again here.
Module parseModule(const SourceManager& sources, FileId file, DiagnosticEngine& diagnostics,
                   const CheckOptions& options);

// Whether `options` and the machine allow a second thread.
bool twoThreadsAllowed(const CheckOptions& options);

// Where to split `parts` into two runs of about equal source size for two
// threads; 0 when they are too few or too small to be worth a thread.
std::size_t partSplit(std::span<const PartItem* const> parts, const CheckOptions& options);

} // namespace cncc::frontend
