#include "source_map.h"

#include "cncc/frontend/ast.h"
#include "cncc/lsp/program_map.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <tuple>
#include <utility>

namespace cncc::driver {

namespace {

using frontend::SourceSpan;

std::string_view statementName(frontend::StmtKind kind) {
  switch (kind) {
  case frontend::StmtKind::Units:
    return "units";
  case frontend::StmtKind::Tool:
    return "tool";
  case frontend::StmtKind::Feed:
    return "feed";
  case frontend::StmtKind::Spindle:
    return "spindle";
  case frontend::StmtKind::Safe:
    return "safe";
  case frontend::StmtKind::Origin:
    return "origin";
  case frontend::StmtKind::Coolant:
    return "coolant";
  case frontend::StmtKind::Let:
    return "let";
  case frontend::StmtKind::Cut:
    return "cut";
  case frontend::StmtKind::For:
    return "for";
  case frontend::StmtKind::If:
    return "if";
  case frontend::StmtKind::Error:
    break;
  }
  return "statement";
}

using StatementKinds = std::map<std::pair<std::uint32_t, std::uint32_t>, std::string_view>;

void collectStatements(const frontend::Block& block, StatementKinds& kinds) {
  for (const frontend::StmtPtr& statement : block.statements) {
    kinds[{statement->span.file.index, statement->span.begin}] = statementName(statement->kind);
    if (statement->kind == frontend::StmtKind::For) {
      collectStatements(frontend::as<frontend::ForStmt>(*statement).body, kinds);
    } else if (statement->kind == frontend::StmtKind::If) {
      const auto& conditional = frontend::as<frontend::IfStmt>(*statement);
      collectStatements(conditional.thenBlock, kinds);
      collectStatements(conditional.elseBlock, kinds);
    }
  }
}

std::vector<std::string_view> programLines(std::string_view text) {
  std::vector<std::string_view> lines;
  while (!text.empty()) {
    std::size_t newline = text.find('\n');
    lines.push_back(text.substr(0, newline));
    text = newline == std::string_view::npos ? std::string_view() : text.substr(newline + 1);
  }
  return lines;
}

// The words of a line's code: its comments ( ) and after ';' dropped, split
// at anything but letters, digits and '_'.
std::vector<std::string> codeWords(std::string_view line) {
  std::vector<std::string> words;
  std::string word;
  bool inComment = false;
  for (char c : line) {
    if (c == ';' && !inComment) {
      break;
    }
    inComment = (inComment && c != ')') || c == '(';
    if (!inComment && (std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_')) {
      word += c;
    } else if (!word.empty()) {
      words.push_back(std::move(word));
      word.clear();
    }
  }
  if (!word.empty()) {
    words.push_back(std::move(word));
  }
  if (!words.empty() && words.front().size() > 1 && words.front()[0] == 'N' &&
      std::all_of(words.front().begin() + 1, words.front().end(),
                  [](char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; })) {
    words.erase(words.begin()); // a block number
  }
  return words;
}

bool isOWord(const std::string& word) {
  return word.size() > 1 && word[0] == 'o' && std::all_of(word.begin() + 1, word.end(), [](char c) {
           return std::isdigit(static_cast<unsigned char>(c)) != 0;
         });
}

bool isFanucEnd(const std::string& word) {
  return word.size() > 3 && word.starts_with("END") &&
         std::all_of(word.begin() + 3, word.end(),
                     [](char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; });
}

// How many controller loops hold each line (the loop's first and last
// lines count as inside it): WHILE .. DOn / ENDn, o-word while / endwhile
// and do / while, Sinumerik WHILE / ENDWHILE.
std::vector<int> loopDepths(const std::vector<std::string_view>& lines) {
  std::vector<int> depths;
  std::vector<std::string> doLabels; // LinuxCNC `oN do` loops open
  int depth = 0;
  for (std::string_view line : lines) {
    std::vector<std::string> words = codeWords(line);
    bool oWord = words.size() > 1 && isOWord(words[0]);
    if (oWord && words[1] == "while" && !doLabels.empty() && doLabels.back() == words[0]) {
      depths.push_back(depth--); // the `while` that closes a do loop
      doLabels.pop_back();
      continue;
    }
    if (oWord && words[1] == "do") {
      doLabels.push_back(words[0]);
    }
    bool opens = (oWord && (words[1] == "while" || words[1] == "do")) ||
                 std::find(words.begin(), words.end(), "WHILE") != words.end();
    bool closes = (oWord && words[1] == "endwhile") ||
                  std::any_of(words.begin(), words.end(), [](const std::string& word) {
                    return isFanucEnd(word) || word == "ENDWHILE";
                  });
    depth += opens ? 1 : 0;
    depths.push_back(depth);
    if (closes && depth > 0) {
      --depth;
    }
  }
  return depths;
}

nlohmann::json parameterValues(const frontend::PartItem& part) {
  nlohmann::json values = nlohmann::json::object();
  for (const frontend::Parameter& parameter : part.parameters) {
    const frontend::Declaration* declaration = parameter.declaration;
    if (declaration != nullptr && declaration->value &&
        declaration->value->type.kind == frontend::TypeKind::Num) {
      values[std::string(parameter.name)] = declaration->value->number;
    }
  }
  return values;
}

// What the map says of one cut statement (see source_map.h).
struct CutSummary {
  std::size_t blocks = 0;
  std::size_t bytes = 0;
  bool measured = false;
  double deviation = std::numeric_limits<double>::quiet_NaN();
  double tolerance = std::numeric_limits<double>::quiet_NaN();

  void addMeasurement(const MeasuredCutDeviation& measurement) {
    measured = true;
    if (!(deviation >= measurement.deviation)) { // NaN counts as nothing measured
      deviation = std::isnan(measurement.deviation) ? deviation : measurement.deviation;
    }
    if (!(tolerance <= measurement.tolerance)) {
      tolerance = std::isnan(measurement.tolerance) ? tolerance : measurement.tolerance;
    }
  }
};

// `,\n "name": [` and an element per line.
std::string compactArray(std::string_view name, const nlohmann::json& elements) {
  std::string text = fmt::format(",\n \"{}\": [", name);
  for (std::size_t i = 0; i < elements.size(); ++i) {
    text += (i == 0 ? "\n  " : ",\n  ") + elements[i].dump();
  }
  return text + (elements.empty() ? "]" : "\n ]");
}

// What made a controller loop: "passes", "curve", else the kind of the
// statement it prints ("for").
std::string_view loopKindName(ir::LoopRole role, std::string_view statement) {
  switch (role) {
  case ir::LoopRole::Passes:
    return "passes";
  case ir::LoopRole::Curve:
    return "curve";
  case ir::LoopRole::Statement:
    break;
  }
  return statement;
}

// {"number": 2, "count": 3}, with "ramp": true on a ramp lap (number 0 and
// count 0 on a ramp lap in a pass loop).
nlohmann::json passJson(const ir::SweepPass& pass) {
  nlohmann::json json = {{"number", pass.number}, {"count", pass.count}};
  if (pass.ramp) {
    json["ramp"] = true;
  }
  return json;
}

// A number, or null for NaN (JSON has no NaN).
nlohmann::json numberOrNull(double value) {
  return std::isnan(value) ? nlohmann::json(nullptr) : nlohmann::json(value);
}

} // namespace

std::string programHash(std::string_view text) {
  return lsp::programHash(text);
}

std::string sourceMapJson(const SourceMapInput& input) {
  const frontend::PartItem& part = *input.program->selectedPart;
  StatementKinds kinds;
  collectStatements(part.body, kinds);
  std::vector<std::string> sources;
  std::map<std::uint32_t, std::size_t> sourceIndex; // FileId -> index in sources
  auto sourceOf = [&](frontend::FileId file) {
    auto [found, added] = sourceIndex.try_emplace(file.index, sources.size());
    if (added) {
      sources.push_back(input.sources->file(file).path());
    }
    return found->second;
  };
  std::vector<std::string_view> lines = programLines(input.programText);
  std::vector<int> depths = loopDepths(lines);
  auto located = [&](SourceSpan span) {
    frontend::LineColumn at = input.sources->file(span.file).lineColumn(span.begin);
    return nlohmann::json{
        {"source", sourceOf(span.file)}, {"line", at.line}, {"column", at.column}};
  };
  // The loops some line names, numbered in the order lines first name them.
  nlohmann::json loopEntries = nlohmann::json::array();
  std::map<std::uint32_t, std::size_t> loopNumber; // printer's index -> entry
  auto loopsHolding = [&](std::uint32_t innermost) {
    std::vector<std::size_t> numbers;
    for (std::uint32_t loop = innermost;
         loop != backends::noControllerLoop && loop < input.lines.loops.size();
         loop = input.lines.loops[loop].outer) {
      auto [found, added] = loopNumber.try_emplace(loop, loopEntries.size());
      if (added) {
        const backends::ControllerLoop& printed = input.lines.loops[loop];
        SourceSpan span = printed.span.valid() ? printed.span : part.nameSpan;
        auto kind = kinds.find({span.file.index, span.begin});
        std::string_view statement = kind == kinds.end() ? "part" : kind->second;
        nlohmann::json entry = located(span);
        entry["statement"] = statement;
        entry["kind"] = loopKindName(printed.role, statement);
        loopEntries.push_back(std::move(entry));
      }
      numbers.push_back(found->second);
    }
    std::reverse(numbers.begin(), numbers.end()); // outermost first
    return numbers;
  };
  nlohmann::json mapped = nlohmann::json::array();
  // Keyed by (source, line, column), in the order the statements are written.
  std::map<std::tuple<std::size_t, std::uint32_t, std::uint32_t>, CutSummary> cuts;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    backends::LineOrigin origin =
        i < input.lines.lines.size() ? input.lines.lines[i] : backends::LineOrigin{};
    SourceSpan span = origin.span;
    if (!span.valid()) {
      span = part.nameSpan;
    }
    frontend::LineColumn at = input.sources->file(span.file).lineColumn(span.begin);
    auto kind = kinds.find({span.file.index, span.begin});
    std::string_view statement = kind == kinds.end() ? "part" : kind->second;
    nlohmann::json entry = {{"source", sourceOf(span.file)},
                            {"line", at.line},
                            {"column", at.column},
                            {"statement", statement},
                            {"loopDepth", depths[i]}};
    if (origin.pass.any()) {
      entry["pass"] = passJson(origin.pass);
    }
    if (std::vector<std::size_t> loops = loopsHolding(origin.loop); !loops.empty()) {
      entry["loops"] = loops;
    }
    mapped.push_back(std::move(entry));
    if (statement == "cut") {
      CutSummary& cut = cuts[{sourceOf(span.file), at.line, at.column}];
      cut.blocks += codeWords(lines[i]).empty() ? 0 : 1;
      cut.bytes += lines[i].size() + 1;
    }
  }
  for (const MeasuredCutDeviation& measurement : input.deviations) {
    frontend::LineColumn at =
        input.sources->file(measurement.statement.file).lineColumn(measurement.statement.begin);
    cuts[{sourceOf(measurement.statement.file), at.line, at.column}].addMeasurement(measurement);
  }
  nlohmann::json cutEntries = nlohmann::json::array();
  for (const auto& [where, cut] : cuts) {
    nlohmann::json entry = {{"source", std::get<0>(where)},
                            {"line", std::get<1>(where)},
                            {"column", std::get<2>(where)},
                            {"blocks", cut.blocks},
                            {"bytes", cut.bytes}};
    if (cut.measured) {
      entry["deviation"] = numberOrNull(cut.deviation);
      entry["tolerance"] = numberOrNull(cut.tolerance);
    }
    cutEntries.push_back(std::move(entry));
  }
  nlohmann::json header = {{"version", 1},
                           {"program", input.programPath},
                           {"programHash", programHash(input.programText)},
                           {"target", input.target},
                           {"part", std::string(part.name)},
                           {"parameters", parameterValues(part)},
                           {"sources", sources},
                           {"directory", std::filesystem::current_path().string()}};
  if (!input.variables.empty()) {
    nlohmann::json variables = nlohmann::json::object();
    for (const auto& [variable, meaning] : input.variables) {
      nlohmann::json statements = nlohmann::json::array();
      for (SourceSpan span : meaning.spans) {
        frontend::LineColumn at = input.sources->file(span.file).lineColumn(span.begin);
        statements.push_back(
            {{"source", sourceOf(span.file)}, {"line", at.line}, {"column", at.column}});
      }
      variables[std::to_string(variable)] = {{"meaning", meaning.meaning},
                                             {"statements", statements}};
    }
    header["variables"] = std::move(variables);
  }
  header["unit"] = input.inches ? "in" : "mm";
  header["sources"] = sources; // the variables' and cuts' statements may add some
  // One line per program line, so that the map reads (and diffs) as the
  // program does.
  std::string text = header.dump(1);
  text.erase(text.find_last_not_of(" \n", text.rfind('}') - 1) + 1);
  text += compactArray("cuts", cutEntries);
  if (!loopEntries.empty()) {
    text += compactArray("loops", loopEntries);
  }
  text += compactArray("lines", mapped);
  return text + "\n}\n";
}

} // namespace cncc::driver

namespace cncc::driver {

std::string annotatedProgram(std::string_view text, std::vector<backends::LineOrigin>& lineOrigins,
                             const frontend::CheckedProgram& program,
                             const frontend::SourceManager& sources,
                             const backends::MachineSetup& setup) {
  StatementKinds kinds;
  collectStatements(program.selectedPart->body, kinds);
  bool semicolon = setup.dialect == "sinumerik" || setup.dialect == "linuxcnc";
  std::vector<std::string_view> lines = programLines(text);
  std::string annotated;
  std::vector<backends::LineOrigin> origins;
  frontend::SourceSpan previous; // the last cut annotated
  for (std::size_t i = 0; i < lines.size(); ++i) {
    backends::LineOrigin origin = i < lineOrigins.size() ? lineOrigins[i] : backends::LineOrigin{};
    SourceSpan span = origin.span;
    auto kind = kinds.find({span.file.index, span.begin});
    // Once per run of one cut statement's lines, even where the lines of
    // the loop around it come between; in each Sinumerik subprogram again,
    // after its header, which must open its file.
    bool header = lines[i].starts_with('%') || lines[i].starts_with(";$PATH");
    if (header) {
      previous = {};
    }
    if (span.valid() && span != previous && kind != kinds.end() && kind->second == "cut" &&
        !header) {
      previous = span;
      std::string path = sources.file(span.file).path();
      std::string where = fmt::format("{}:{}", path.substr(path.find_last_of('/') + 1),
                                      sources.file(span.file).lineColumn(span.begin).line);
      if (setup.commentCase == backends::CommentCase::Upper) {
        std::transform(where.begin(), where.end(), where.begin(),
                       [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
      }
      annotated += semicolon ? fmt::format("; {}\n", where) : fmt::format("({})\n", where);
      origins.push_back(origin);
    }
    annotated += lines[i];
    annotated += '\n';
    origins.push_back(origin);
  }
  lineOrigins = std::move(origins);
  return annotated;
}

} // namespace cncc::driver
