#include "curve_table_text.h"

#include "ir_text.h"

#include "cncc/ir/printer.h"

#include <array>
#include <cmath>
#include <fmt/format.h>
#include <memory>

namespace cncc::ir {

using namespace text;

namespace {

constexpr std::array<std::string_view, 3> splineKindNames = {"bspline", "cspline", "aspline"};
constexpr std::array<std::string_view, 3> splineEndsNames = {"automatic", "natural", "auto"};

std::string pieceText(const CurvePieceLayout& piece) {
  std::string line =
      fmt::format("    piece at {} over {} .. {}", piece.start, piece.from, piece.to);
  for (std::size_t k = 0; k < piece.spans.size(); ++k) {
    line += fmt::format("{}{} .. {}", k == 0 ? " spans " : ", ", piece.spans[k].first,
                        piece.spans[k].second);
  }
  return line + "\n";
}

std::string arcRegionsText(const std::vector<ArcRegion>& regions) {
  std::vector<std::string> arcs;
  for (const ArcRegion& arc : regions) {
    arcs.push_back(fmt::format("{} {}{}", arc.region, arc.counterClockwise ? "ccw" : "cw",
                               arc.wholeTurns ? " turns" : ""));
  }
  return fmt::format("    arcs {}\n", fmt::join(arcs, ", "));
}

// `counts 12, ?, 0`: `?` where the legalisation chooses the count.
std::string countsText(const std::vector<int>& counts) {
  std::vector<std::string> words;
  for (int count : counts) {
    words.push_back(count == stepsChosenByLegalisation ? "?" : fmt::format("{}", count));
  }
  return fmt::format("    counts {}\n", fmt::join(words, ", "));
}

int readCount(std::string_view word) {
  return word == "?" ? stepsChosenByLegalisation : static_cast<int>(parseWholeNumber(word));
}

// `left radius 1.5 largest 6.2`: an offset's counts that grow with the
// tool radius (side left: +1, right: -1).
OffsetStepGrowth readOffsetGrowth(std::string_view rest) {
  std::vector<std::string_view> words = splitWords(rest);
  if (words.size() != 5 || (words[0] != "left" && words[0] != "right") || words[1] != "radius" ||
      words[3] != "largest") {
    throw Failure{"expected 'offset left|right radius R largest L'"};
  }
  return {words[0] == "left" ? 1.0 : -1.0, parseNumber(words[2]), parseNumber(words[4])};
}

// `asks arcs within 0.0098 grid 0.001 [radius 99999.999]`: arcs in place
// of the lap's chords or steps where a fit keeps them (of a radius up to
// the last number).
ArcsAsked readArcsAsked(std::string_view rest) {
  std::vector<std::string_view> words = splitWords(rest);
  bool radius = words.size() == 7 && words[5] == "radius";
  if ((words.size() != 5 && !radius) || words[0] != "arcs" || words[1] != "within" ||
      words[3] != "grid") {
    throw Failure{"expected 'asks arcs within TOLERANCE grid GRID [radius LARGEST]'"};
  }
  ArcsAsked asked{parseNumber(words[2]), parseNumber(words[4])};
  if (radius) {
    asked.largestRadius = parseNumber(words[6]);
  }
  return asked;
}

std::string arcsAskedText(const ArcsAsked& asked) {
  std::string text = fmt::format("    asks arcs within {} grid {}", asked.tolerance, asked.grid);
  if (std::isfinite(asked.largestRadius)) {
    text += fmt::format(" radius {}", asked.largestRadius);
  }
  return text + "\n";
}

std::string offsetGrowthText(const OffsetStepGrowth& growth) {
  return fmt::format("    offset {} radius {} largest {}\n", growth.side > 0 ? "left" : "right",
                     growth.compiledRadius, growth.largestRadius);
}

// The entry's chosen parameters, or the earlier entry that holds the same.
std::string chosenText(std::span<const CurveTableEntry> curves, std::size_t index) {
  const auto& parameters = curves[index].chosenParameters;
  for (std::size_t other = 0; other < index; ++other) {
    if (curves[other].chosenParameters == parameters) {
      return fmt::format("    chosen as @{}\n", other);
    }
  }
  return fmt::format("    chosen {}\n", fmt::join(*parameters, ", "));
}

std::string splineFitText(const SplineBlocksFit& fit) {
  return fmt::format("    spline {} {}{}\n", splineKindNames[static_cast<std::size_t>(fit.kind)],
                     splineEndsNames[static_cast<std::size_t>(fit.ends)],
                     fit.afterRamp ? " after-ramp" : "");
}

// `2 ccw`, `0 cw turns`: a region cut as an arc, its turn, whole turns.
ArcRegion readArcRegion(std::string_view line) {
  std::vector<std::string_view> words = splitWords(line);
  bool turns = words.size() == 3 && words[2] == "turns";
  if ((words.size() != 2 && !turns) || (words[1] != "ccw" && words[1] != "cw")) {
    throw Failure{"expected 'arcs REGION ccw|cw [turns], ...'"};
  }
  return {parseWholeNumber(words[0]), words[1] == "ccw", turns};
}

// `spline bspline|cspline|aspline automatic|natural|auto [after-ramp]`
SplineBlocksFit readSplineFit(std::string_view rest) {
  std::vector<std::string_view> words = splitWords(rest);
  bool afterRamp = words.size() == 3 && words[2] == "after-ramp";
  if (words.size() != 2 && !afterRamp) {
    throw Failure{"expected 'spline bspline|cspline|aspline automatic|natural|auto [after-ramp]'"};
  }
  SplineBlocksFit fit;
  fit.kind = static_cast<SplineKind>(namedIndex(splineKindNames, words[0], "a spline kind"));
  fit.ends = static_cast<SplineEnds>(namedIndex(splineEndsNames, words[1], "how a spline ends"));
  fit.afterRamp = afterRamp;
  return fit;
}

template <typename Number, typename Read>
void readList(std::string_view text, std::vector<Number>& into, Read read) {
  for (std::string_view item : splitList(text)) {
    into.push_back(static_cast<Number>(read(item)));
  }
}

// `piece at start over from .. to [spans a .. b, ...]`
CurvePieceLayout readPiece(std::string_view line) {
  std::size_t spansAt = line.find(" spans ");
  std::vector<std::string_view> words = splitWords(line.substr(0, spansAt));
  if (words.size() != 7 || words[1] != "at" || words[3] != "over" || words[5] != "..") {
    throw Failure{"expected 'piece at start over from .. to [spans a .. b, ...]'"};
  }
  CurvePieceLayout piece;
  piece.start = parseNumber(words[2]);
  piece.from = parseNumber(words[4]);
  piece.to = parseNumber(words[6]);
  if (spansAt != std::string_view::npos) {
    for (std::string_view span : splitList(line.substr(spansAt + 7))) {
      std::size_t dots = span.find(" .. ");
      if (dots == std::string_view::npos) {
        throw Failure{"expected a knot span 'from .. to'"};
      }
      piece.spans.emplace_back(parseNumber(span.substr(0, dots)),
                               parseNumber(span.substr(dots + 4)));
    }
  }
  return piece;
}

// A `keyword rest` line of an entry other than a piece; false when the
// keyword is none of them.
bool readSetting(std::string_view line, CurveTableEntry& entry,
                 std::span<const CurveTableEntry> earlier) {
  std::size_t space = line.find(' ');
  std::string_view keyword = line.substr(0, space);
  std::string_view rest = space == std::string_view::npos ? "" : line.substr(space + 1);
  if (keyword == "numbers" && rest.empty()) {
    entry.pointsAsNumbers = true;
  } else if (keyword == "host") {
    readList(rest, entry.hostPointRegions, parseWholeNumber);
  } else if (keyword == "chosen" && startsWith(rest, "as @")) {
    std::uint32_t other = parseWholeNumber(rest.substr(4));
    if (other >= earlier.size() || !earlier[other].chosenParameters) {
      throw Failure{fmt::format("curve @{} before this one has no chosen parameters", other)};
    }
    entry.chosenParameters = earlier[other].chosenParameters;
  } else if (keyword == "chosen") {
    std::vector<double> parameters;
    readList(rest, parameters, parseNumber);
    entry.chosenParameters = std::make_shared<const std::vector<double>>(std::move(parameters));
  } else if (keyword == "counts") {
    readList(rest, entry.regionSteps, readCount);
  } else if (keyword == "offset") {
    entry.offsetGrowth = readOffsetGrowth(rest);
  } else if (keyword == "asks") {
    entry.arcsAsked = readArcsAsked(rest);
  } else if (keyword == "walks") {
    readList(rest, entry.walkRegions, parseWholeNumber);
  } else if (keyword == "arcs") {
    for (std::string_view arc : splitList(rest)) {
      entry.arcRegions.push_back(readArcRegion(arc));
    }
  } else if (keyword == "grid") {
    entry.grid = parseNumber(rest);
  } else if (keyword == "weights") {
    for (std::string_view weight : splitList(rest)) {
      std::vector<std::string_view> words = splitWords(weight);
      if (words.size() != 3 || words[1] != "param") {
        throw Failure{"expected 'weights POINT param P, ...'"};
      }
      entry.parameterWeights.push_back(
          {parseWholeNumber(words[0]), static_cast<std::uint32_t>(parseWholeNumber(words[2]))});
    }
  } else if (keyword == "blocks" && rest == "asked") {
    entry.blocksAsked = true;
  } else if (keyword == "blocks" && startsWith(rest, "@")) {
    entry.blockTable = parseWholeNumber(rest.substr(1));
  } else if (keyword == "spline") {
    entry.splineFit = readSplineFit(rest);
  } else if (keyword == "progress") {
    std::vector<std::string_view> words = splitWords(rest);
    if (words.size() != 3 || words[1] != "share") {
      throw Failure{"expected 'progress from share share'"};
    }
    entry.progressFrom = parseNumber(words[0]);
    entry.progressShare = parseNumber(words[2]);
  } else {
    return false;
  }
  return true;
}

} // namespace

std::string curveEntryText(std::span<const CurveTableEntry> curves, std::size_t index) {
  const CurveTableEntry& entry = curves[index];
  std::string out =
      fmt::format("  curve @{} {} {} over {} .. {} {{\n", index, curveSamplingName(entry.sampling),
                  entry.amount, entry.from, entry.to);
  for (const CurvePieceLayout& piece : entry.pieces) {
    out += pieceText(piece);
  }
  if (entry.grid != 0) {
    out += fmt::format("    grid {}\n", entry.grid);
  }
  if (entry.blockTable) {
    out += fmt::format("    blocks @{}\n", *entry.blockTable);
  }
  if (entry.blocksAsked) {
    out += "    blocks asked\n";
  }
  if (!entry.parameterWeights.empty()) {
    std::vector<std::string> weights;
    for (const CurveTableEntry::ParameterWeight& weight : entry.parameterWeights) {
      weights.push_back(fmt::format("{} param {}", weight.point, weight.parameter));
    }
    out += fmt::format("    weights {}\n", fmt::join(weights, ", "));
  }
  if (entry.splineFit) {
    out += splineFitText(*entry.splineFit);
  }
  if (!entry.regionSteps.empty()) {
    out += countsText(entry.regionSteps);
  }
  if (entry.offsetGrowth) {
    out += offsetGrowthText(*entry.offsetGrowth);
  }
  if (entry.arcsAsked) {
    out += arcsAskedText(*entry.arcsAsked);
  }
  if (!entry.arcRegions.empty()) {
    out += arcRegionsText(entry.arcRegions);
  }
  if (!entry.walkRegions.empty()) {
    out += fmt::format("    walks {}\n", fmt::join(entry.walkRegions, ", "));
  }
  if (entry.progressFrom != 0 || entry.progressShare != 1) {
    out += fmt::format("    progress {} share {}\n", entry.progressFrom, entry.progressShare);
  }
  if (!entry.hostPointRegions.empty()) {
    out += fmt::format("    host {}\n", fmt::join(entry.hostPointRegions, ", "));
  }
  if (entry.pointsAsNumbers) {
    out += "    numbers\n";
  }
  if (entry.chosenParameters) {
    out += chosenText(curves, index);
  }
  return out + "  }\n";
}

CurveTableEntry readCurveEntryHeader(std::string_view line, std::size_t index) {
  std::vector<std::string_view> words = splitWords(line);
  if (words.size() != 9 || words[4] != "over" || words[6] != ".." || words[8] != "{") {
    throw Failure{"expected 'curve @c chords|samples|spacing amount over from .. to {'"};
  }
  if (parseWholeNumber(words[1].substr(1)) != index) {
    throw Failure{fmt::format("expected curve @{} next", index)};
  }
  std::optional<CurveSampling> sampling = curveSamplingNamed(words[2]);
  if (!sampling) {
    throw Failure{"a curve's laps are cut by 'chords', 'samples', 'spacing', 'arcs', 'steps', "
                  "'nurbs-blocks', 'spline-blocks' or 'polynomial-blocks'"};
  }
  CurveTableEntry entry;
  entry.sampling = *sampling;
  entry.amount = parseNumber(words[3]);
  entry.from = parseNumber(words[5]);
  entry.to = parseNumber(words[7]);
  return entry;
}

bool readCurveEntryLine(std::string_view line, CurveTableEntry& entry,
                        std::span<const CurveTableEntry> earlier) {
  if (line == "}") {
    return true;
  }
  if (startsWith(line, "piece ")) {
    entry.pieces.push_back(readPiece(line));
  } else if (!readSetting(line, entry, earlier)) {
    throw Failure{"expected 'piece at start over from .. to', 'grid', 'blocks', 'spline', "
                  "'counts', 'offset', 'asks', 'arcs', 'walks', 'progress', 'host', "
                  "'numbers', 'chosen' or '}'"};
  }
  return false;
}

} // namespace cncc::ir
