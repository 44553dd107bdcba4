// Runs scripted language-server sessions and compares what the server
// sends with the expectations beside them.
//
//   lsp_golden_runner --root SOURCE_DIR --stdlib DIR [--update] NAME.session...
//
// NAME.session holds one message per line, sent in order through the real
// framing and server loop (blank lines and `#` comments are skipped):
//
//   {"jsonrpc": "2.0", ...}   a JSON message, framed
//   raw: TEXT                 TEXT framed as a message body (malformed JSON)
//   bytes: TEXT               TEXT written as is, `\r` and `\n` unescaped
//                             (broken framing)
//
// In JSON messages "${ROOT}" inside a string is the source directory, and a
// string "@text:PATH" is replaced by the contents of PATH (under the root).
//
// NAME.responses holds each message the server sent, one compact JSON per
// line with the root written as ${ROOT}, then what the server logged
// (`log: ...`) and its exit code (`exit: N`).
#include "cncc/lsp/framing.h"
#include "cncc/lsp/json_rpc.h"
#include "cncc/lsp/server_loop.h"

#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace {

using cncc::lsp::Json;

struct Settings {
  std::string root;
  std::string stdlib;
  bool update = false;
  std::vector<std::string> sessions;
};

std::string readFile(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) {
    throw std::runtime_error("cannot read " + path);
  }
  std::ostringstream text;
  text << file.rdbuf();
  return text.str();
}

std::string replaceAll(std::string text, const std::string& from, const std::string& to) {
  for (std::size_t at = text.find(from); !from.empty() && at != std::string::npos;
       at = text.find(from, at + to.size())) {
    text.replace(at, from.size(), to);
  }
  return text;
}

void substitute(Json& value, const Settings& settings) {
  if (value.is_string()) {
    std::string text = value.get<std::string>();
    value = text.rfind("@text:", 0) == 0 ? readFile(settings.root + "/" + text.substr(6))
                                         : replaceAll(text, "${ROOT}", settings.root);
  } else if (value.is_structured()) {
    for (Json& child : value) {
      substitute(child, settings);
    }
  }
}

std::string frame(const std::string& body) {
  std::ostringstream framed;
  cncc::lsp::writeMessage(framed, body);
  return framed.str();
}

// The byte stream a session sends.
std::string clientStream(const std::string& sessionPath, const Settings& settings) {
  std::istringstream lines(readFile(sessionPath));
  std::string stream;
  for (std::string line; std::getline(lines, line);) {
    if (line.empty() || line[0] == '#') {
      continue;
    }
    if (line.rfind("raw: ", 0) == 0) {
      stream += frame(line.substr(5));
    } else if (line.rfind("bytes: ", 0) == 0) {
      stream += replaceAll(replaceAll(line.substr(7), "\\r", "\r"), "\\n", "\n");
    } else {
      Json message = Json::parse(line);
      substitute(message, settings);
      stream += frame(cncc::lsp::serialize(message));
    }
  }
  return stream;
}

std::string runSession(const std::string& sessionPath, const Settings& settings) {
  std::istringstream input(clientStream(sessionPath, settings));
  std::ostringstream output;
  std::ostringstream log;
  cncc::lsp::Server server({settings.stdlib});
  int exitCode = cncc::lsp::runServer(server, input, output, log);
  std::istringstream sent(output.str());
  std::string transcript;
  while (true) {
    cncc::lsp::ReadResult message = cncc::lsp::readMessage(sent);
    if (message.status != cncc::lsp::ReadStatus::Message) {
      break;
    }
    transcript += Json::parse(message.body).dump() + "\n";
  }
  std::istringstream logLines(log.str());
  for (std::string line; std::getline(logLines, line);) {
    transcript += "log: " + line + "\n";
  }
  transcript += "exit: " + std::to_string(exitCode) + "\n";
  return replaceAll(transcript, settings.root, "${ROOT}");
}

// Reports the first line where `expected` and `actual` differ.
void reportDifference(const std::string& expected, const std::string& actual) {
  std::istringstream a(expected);
  std::istringstream b(actual);
  std::string left;
  std::string right;
  for (int line = 1;; ++line) {
    bool moreLeft = static_cast<bool>(std::getline(a, left));
    bool moreRight = static_cast<bool>(std::getline(b, right));
    if (!moreLeft && !moreRight) {
      return;
    }
    if (left != right || moreLeft != moreRight) {
      std::cerr << "  line " << line << "\n  expected: " << (moreLeft ? left : "(nothing)")
                << "\n  actual:   " << (moreRight ? right : "(nothing)") << "\n";
      return;
    }
  }
}

bool check(const std::string& sessionPath, const Settings& settings) {
  std::string expectedPath =
      sessionPath.substr(0, sessionPath.size() - std::string(".session").size()) + ".responses";
  std::string actual = runSession(sessionPath, settings);
  if (settings.update) {
    std::ofstream(expectedPath, std::ios::binary) << actual;
    return true;
  }
  std::ifstream file(expectedPath, std::ios::binary);
  std::string expected = file ? readFile(expectedPath) : "";
  if (actual == expected) {
    return true;
  }
  std::cerr << "FAIL " << sessionPath << (file ? "" : " (no .responses; run with --update)")
            << "\n";
  reportDifference(expected, actual);
  return false;
}

Settings parseArguments(int argc, char** argv) {
  Settings settings;
  for (int i = 1; i < argc; ++i) {
    std::string argument = argv[i];
    if (argument == "--update") {
      settings.update = true;
    } else if ((argument == "--root" || argument == "--stdlib") && i + 1 < argc) {
      (argument == "--root" ? settings.root : settings.stdlib) = argv[++i];
    } else {
      settings.sessions.push_back(argument);
    }
  }
  return settings;
}

} // namespace

int main(int argc, char** argv) {
  Settings settings = parseArguments(argc, argv);
  if (settings.root.empty() || settings.stdlib.empty() || settings.sessions.empty()) {
    std::cerr << "usage: lsp_golden_runner --root DIR --stdlib DIR [--update] NAME.session...\n";
    return 2;
  }
  bool passed = true;
  for (const std::string& session : settings.sessions) {
    try {
      passed &= check(session, settings);
    } catch (const std::exception& error) {
      std::cerr << "FAIL " << session << ": " << error.what() << "\n";
      passed = false;
    }
  }
  return passed ? 0 : 1;
}
