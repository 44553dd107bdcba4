// cncc-lsp: the CDL language server, speaking the Language Server Protocol
// over standard input and output. `cncc lsp` runs the same server.
#include "cncc/lsp/server_loop.h"

#include <iostream>

int main() {
  std::ios::sync_with_stdio(false);
  cncc::lsp::Server server({cncc::lsp::defaultStdlibDirectory()});
  return cncc::lsp::runServer(server, std::cin, std::cout, std::cerr);
}
