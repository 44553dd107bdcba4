// Runs a Server over a byte stream: reads framed messages, hands them to
// the server, writes its answers framed. `cncc-lsp` and `cncc lsp` run it
// over standard input and output; the golden tests over string streams.
#pragma once

#include "cncc/lsp/server.h"

#include <istream>
#include <ostream>

namespace cncc::lsp {

// Returns the process exit code: the server's after `exit`, 1 when the
// input ends without one. Problems with the framing go to `log`.
int runServer(Server& server, std::istream& input, std::ostream& output, std::ostream& log);

} // namespace cncc::lsp
