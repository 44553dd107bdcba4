// A Make/Ninja dependency file (`-MD -MF FILE -MT TARGET`): the program
// depends on its source, every file the source imports and the machine
// file, so a build tool rebuilds exactly the programs a change touches.
#pragma once

#include <string>
#include <vector>

namespace cncc::driver {

// `target: prerequisite ...` with the characters Make and Ninja treat
// specially escaped (spaces, `#`, `$`), one prerequisite per continued line.
std::string dependencyFileText(const std::string& target,
                               const std::vector<std::string>& prerequisites);

} // namespace cncc::driver
