#include "dependency_file.h"

namespace cncc::driver {

namespace {

// Make's escapes, which Ninja's depfile reader also reads: a space or `#`
// after a backslash, `$` doubled.
std::string escaped(const std::string& path) {
  std::string text;
  for (char c : path) {
    if (c == ' ' || c == '#') {
      text += '\\';
    } else if (c == '$') {
      text += '$';
    }
    text += c;
  }
  return text;
}

} // namespace

std::string dependencyFileText(const std::string& target,
                               const std::vector<std::string>& prerequisites) {
  std::string text = escaped(target) + ":";
  for (const std::string& prerequisite : prerequisites) {
    text += " \\\n  " + escaped(prerequisite);
  }
  return text + "\n";
}

} // namespace cncc::driver
