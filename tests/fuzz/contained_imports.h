// Whether a fuzzed source's imports stay inside the import directory, so a
// fuzzer never reads files of the machine it runs on.
#pragma once

#include <string_view>

namespace cncc::fuzz {

// An import the checker may follow: relative, inside the import directory.
inline bool isContainedImport(std::string_view path) {
  if (path.empty() || path.front() == '/' || path.find('\0') != std::string_view::npos ||
      path.find('\\') != std::string_view::npos) {
    return false;
  }
  std::size_t begin = 0;
  while (begin <= path.size()) {
    std::size_t end = path.find('/', begin);
    if (end == std::string_view::npos) {
      end = path.size();
    }
    if (path.substr(begin, end - begin) == "..") {
      return false;
    }
    begin = end + 1;
  }
  return true;
}

} // namespace cncc::fuzz
