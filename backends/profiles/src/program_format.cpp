#include "cncc/backends/program_format.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <map>
#include <optional>
#include <utility>

namespace cncc::backends {

namespace {

struct Span {
  std::size_t begin = 0;
  std::size_t end = 0; // one past the last character
};

bool isSinumerik(const MachineSetup& setup) {
  return setup.dialect == "sinumerik";
}

bool isMacroDialect(const MachineSetup& setup) {
  return setup.dialect == "fanuc" || setup.dialect == "m80";
}

bool isDigit(char c) {
  return std::isdigit(static_cast<unsigned char>(c)) != 0;
}

std::string_view trimmedLeft(std::string_view line) {
  std::size_t first = line.find_first_not_of(" \t");
  return first == std::string_view::npos ? std::string_view() : line.substr(first);
}

std::string lowerCase(std::string_view text) {
  std::string lower(text);
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return lower;
}

// The comments of a line: ( ) on the ISO dialects (and `;` to the end of
// the line on LinuxCNC), `;` outside "strings" on Sinumerik.
std::vector<Span> commentSpans(std::string_view line, const MachineSetup& setup) {
  std::vector<Span> spans;
  bool semicolonComments = isSinumerik(setup) || setup.dialect == "linuxcnc";
  bool inString = false;
  for (std::size_t at = 0; at < line.size(); ++at) {
    char c = line[at];
    if (isSinumerik(setup) && c == '"') {
      inString = !inString;
    } else if (inString) {
      continue;
    } else if (c == ';' && semicolonComments) {
      spans.push_back({at, line.size()});
      break;
    } else if (c == '(' && !isSinumerik(setup)) {
      std::size_t close = line.find(')', at);
      std::size_t end = close == std::string_view::npos ? line.size() : close + 1;
      spans.push_back({at, end});
      at = end - 1;
    }
  }
  return spans;
}

// A comment the controller acts on, which stays when comments are off: a
// macro alarm's message, LinuxCNC's (abort, ...) and friends, Sinumerik's
// ;$PATH file directive.
bool isActiveComment(std::string_view line, Span span, const MachineSetup& setup) {
  std::string_view text = line.substr(span.begin, span.end - span.begin);
  if (isMacroDialect(setup)) {
    return trimmedLeft(line).starts_with("#3000");
  }
  if (isSinumerik(setup)) {
    return text.starts_with(";$");
  }
  if (setup.dialect == "linuxcnc" && text.starts_with("(")) {
    std::string body = lowerCase(trimmedLeft(text.substr(1)));
    constexpr std::array<std::string_view, 6> active = {"abort,", "debug,", "print,",
                                                        "msg,",   "log",    "probe"};
    return std::any_of(active.begin(), active.end(),
                       [&](std::string_view word) { return body.starts_with(word); });
  }
  return false;
}

// The line with its comments in capitals or dropped; nullopt when nothing
// is left of it.
std::optional<std::string> withComments(std::string line, const MachineSetup& setup) {
  std::vector<Span> spans = commentSpans(line, setup);
  if (spans.empty()) {
    return line;
  }
  for (auto span = spans.rbegin(); span != spans.rend(); ++span) {
    if (setup.comments || isActiveComment(line, *span, setup)) {
      if (setup.commentCase == CommentCase::Upper) {
        std::transform(line.begin() + static_cast<std::ptrdiff_t>(span->begin),
                       line.begin() + static_cast<std::ptrdiff_t>(span->end),
                       line.begin() + static_cast<std::ptrdiff_t>(span->begin),
                       [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
      }
      continue;
    }
    std::size_t begin = span->begin;
    while (begin > 0 && (line[begin - 1] == ' ' || line[begin - 1] == '\t')) {
      --begin;
    }
    line.erase(begin, span->end - begin);
  }
  if (trimmedLeft(line).empty()) {
    return std::nullopt;
  }
  return line;
}

// Blocks that take no line number: the tape marks, program and subprogram
// headers (O numbers, LinuxCNC o-words, Sinumerik PROC), comment lines.
bool takesLineNumber(std::string_view line, const MachineSetup& setup) {
  std::string_view code = trimmedLeft(line);
  if (code.empty() || code.front() == '%' || code.front() == '(' || code.front() == ';') {
    return false;
  }
  if (isSinumerik(setup)) {
    return !code.starts_with("PROC");
  }
  bool oWord = code.front() == 'O' || (setup.dialect == "linuxcnc" && code.front() == 'o');
  return !(oWord && code.size() > 1 && (isDigit(code[1]) || code[1] == '<'));
}

// A macro jump target: a block of nothing but `N<label>`.
std::optional<int> jumpLabel(std::string_view line) {
  // At most 9 digits: a number an int holds (controllers stop at 8).
  if (line.size() < 2 || line.size() > 10 || line.front() != 'N' ||
      !std::all_of(line.begin() + 1, line.end(), isDigit)) {
    return std::nullopt;
  }
  return std::stoi(std::string(line.substr(1)));
}

// Where the label of a `... GOTO <label>` block is, outside its comments.
std::optional<Span> jumpTarget(std::string_view line, const MachineSetup& setup) {
  std::size_t codeEnd = line.size();
  if (std::vector<Span> spans = commentSpans(line, setup); !spans.empty()) {
    codeEnd = spans.front().begin;
  }
  std::size_t jump = line.substr(0, codeEnd).rfind("GOTO");
  if (jump == std::string_view::npos) {
    return std::nullopt;
  }
  std::size_t begin = line.find_first_not_of(' ', jump + 4);
  std::size_t end = begin;
  while (end < codeEnd && isDigit(line[end])) {
    ++end;
  }
  return end == begin || end - begin > 9 ? std::nullopt : std::optional<Span>({begin, end});
}

class LineNumberer {
public:
  LineNumberer(const MachineSetup& setup, std::vector<std::string>& errors)
      : setup_(setup), numbering_(setup.lineNumbers), errors_(errors), next_(numbering_.start) {}

  void number(std::vector<std::string>& lines) {
    for (std::string& line : lines) {
      if (!takesLineNumber(line, setup_)) {
        continue;
      }
      int number = take();
      if (std::optional<int> label = isMacroDialect(setup_) ? jumpLabel(line) : std::nullopt) {
        labels_[*label] = number;
        line = fmt::format("N{}", number);
      } else {
        line = fmt::format("N{} {}", number, line);
      }
    }
    if (!labels_.empty()) {
      renumberJumps(lines);
    }
  }

private:
  int take() {
    int number = next_;
    if (next_ > numbering_.maximum - numbering_.increment) {
      next_ = numbering_.start;
      wrapped_ = true;
    } else {
      next_ += numbering_.increment;
    }
    return number;
  }

  void renumberJumps(std::vector<std::string>& lines) {
    if (wrapped_) {
      errors_.push_back(fmt::format(
          "the line numbers start again at N{} after N{}, and the program jumps to line numbers "
          "(GOTO), which would then not be unique; raise the machine's line number maximum or "
          "turn line numbers off",
          numbering_.start, numbering_.maximum));
      return;
    }
    for (std::string& line : lines) {
      std::optional<Span> target = jumpTarget(line, setup_);
      if (!target) {
        continue;
      }
      int label = std::stoi(line.substr(target->begin, target->end - target->begin));
      if (auto found = labels_.find(label); found != labels_.end()) {
        line.replace(target->begin, target->end - target->begin, std::to_string(found->second));
      }
    }
  }

  const MachineSetup& setup_;
  const LineNumbering& numbering_;
  std::vector<std::string>& errors_;
  int next_;
  bool wrapped_ = false;
  std::map<int, int> labels_; // printed label -> its line number
};

} // namespace

FormattedProgram formatProgram(std::vector<std::string> lines, const MachineSetup& setup,
                               std::vector<std::string>& errors) {
  FormattedProgram program;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (std::optional<std::string> line = withComments(std::move(lines[i]), setup)) {
      program.lines.push_back(std::move(*line));
      program.printedLine.push_back(i);
    }
  }
  if (setup.lineNumbers.enabled) {
    LineNumberer(setup, errors).number(program.lines);
  }
  return program;
}

} // namespace cncc::backends
