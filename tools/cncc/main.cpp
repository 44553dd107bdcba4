// cncc: the CDL compiler driver. Parses the command line and runs the
// command it names; see commands.h for the commands and their exit codes.
#include "commands.h"
#include "driver_options.h"

#include <cstdio>

int main(int argc, char** argv) {
  cncc::driver::ParsedCommandLine commandLine = cncc::driver::parseCommandLine(argc, argv);
  if (!commandLine.options) {
    return commandLine.exitCode;
  }
  try {
    return cncc::driver::runCommand(*commandLine.options);
  } catch (const cncc::driver::InternalError& error) {
    std::fprintf(stderr, "cncc: internal error: %s\n", error.what());
    return 1;
  }
}
