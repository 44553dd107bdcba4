// cncc: the CDL compiler driver. Parses the command line and runs the
// command it names; see commands.h for the commands and their exit codes.
#include "commands.h"
#include "driver_options.h"

int main(int argc, char** argv) {
  cncc::driver::ParsedCommandLine commandLine = cncc::driver::parseCommandLine(argc, argv);
  if (!commandLine.options) {
    return commandLine.exitCode;
  }
  return cncc::driver::runCommand(*commandLine.options);
}
