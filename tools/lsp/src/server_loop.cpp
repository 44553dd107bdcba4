#include "cncc/lsp/server_loop.h"

#include "cncc/lsp/framing.h"

namespace cncc::lsp {

int runServer(Server& server, std::istream& input, std::ostream& output, std::ostream& log) {
  while (true) {
    ReadResult read = readMessage(input);
    if (read.status == ReadStatus::EndOfInput) {
      return server.exitRequested() ? server.exitCode() : 1;
    }
    if (read.status == ReadStatus::BadHeader) {
      log << "cncc-lsp: skipped a message: " << read.problem << '\n';
      continue;
    }
    for (const Json& message : server.handleText(read.body)) {
      writeMessage(output, serialize(message));
    }
    server.releaseRetired();
    if (server.exitRequested()) {
      return server.exitCode();
    }
  }
}

} // namespace cncc::lsp
