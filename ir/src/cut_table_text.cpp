#include "cut_table_text.h"

#include "ir_text.h"

#include <fmt/format.h>

namespace cncc::ir {

using namespace text;

namespace {

constexpr std::string_view arcMovesNames[] = {"none", "native", "fitted"};
// What `prints` names: the blocks, and for Sinumerik's how they end.
constexpr std::string_view printedBlocksNames[] = {"nurbs", "polynomial", "spline-automatic",
                                                   "spline-natural", "spline-auto"};

std::string_view printedBlocksName(const CutGeometry& cut) {
  if (cut.printedBlocks == PrintedBlocks::Spline) {
    return printedBlocksNames[2 + static_cast<std::size_t>(cut.splineEnds)];
  }
  return printedBlocksNames[cut.printedBlocks == PrintedBlocks::Nurbs ? 0 : 1];
}

void readPrintedBlocks(std::string_view name, CutGeometry& cut) {
  std::size_t index = namedIndex(
      printedBlocksNames, name, "'prints' with nurbs, polynomial or spline-automatic|natural|auto");
  cut.printedBlocks = index == 0   ? PrintedBlocks::Nurbs
                      : index == 1 ? PrintedBlocks::Polynomial
                                   : PrintedBlocks::Spline;
  cut.splineEnds = static_cast<SplineEnds>(index < 2 ? 0 : index - 2);
}

} // namespace

std::string cutEntryText(std::size_t index, const CutGeometry& cut) {
  std::string line = fmt::format("  cut @{} tolerance {}", index, cut.tolerance);
  if (cut.increment != 0) {
    line += fmt::format(" increment {}", cut.increment);
  }
  if (cut.controllerDigits) {
    line += fmt::format(" controller {}", *cut.controllerDigits);
  }
  if (!cut.method.empty()) {
    line += fmt::format(" method {}", cut.method);
  }
  if (cut.printedBlocks != PrintedBlocks::None) {
    line += fmt::format(" prints {}", printedBlocksName(cut));
  }
  if (cut.arcMoves != CutArcs::None) {
    line += fmt::format(" arcs {}", arcMovesNames[static_cast<std::size_t>(cut.arcMoves)]);
  }
  if (cut.toolRadius != 0) {
    line += fmt::format(" beside {}", cut.toolRadius);
  }
  if (!cut.splineBlocks.empty()) {
    line += " blocks " + quoted(cut.splineBlocks);
  }
  return line + "\n";
}

CutGeometry readCutEntry(std::string_view line, std::size_t index) {
  std::string_view words = line;
  std::string_view blocks;
  if (std::size_t at = line.find(" blocks \""); at != std::string_view::npos) {
    words = line.substr(0, at);
    blocks = line.substr(at + 8);
  }
  std::vector<std::string_view> parts = splitWords(words);
  if (parts.size() < 4 || parts.size() % 2 != 0 || parts[2] != "tolerance") {
    throw Failure{"expected 'cut @n tolerance T [increment I] [controller D] [method M] "
                  "[prints BLOCKS] [arcs native|fitted] [beside R] [blocks \"...\"]'"};
  }
  if (parseWholeNumber(parts[1].substr(1)) != index) {
    throw Failure{fmt::format("expected cut @{} next", index)};
  }
  CutGeometry cut;
  cut.tolerance = parseNumber(parts[3]);
  for (std::size_t k = 4; k + 1 < parts.size(); k += 2) {
    if (parts[k] == "increment") {
      cut.increment = parseNumber(parts[k + 1]);
    } else if (parts[k] == "controller") {
      cut.controllerDigits = static_cast<int>(parseWholeNumber(parts[k + 1]));
    } else if (parts[k] == "method") {
      cut.method = parts[k + 1];
    } else if (parts[k] == "prints") {
      readPrintedBlocks(parts[k + 1], cut);
    } else if (parts[k] == "arcs") {
      cut.arcMoves = static_cast<CutArcs>(
          namedIndex(arcMovesNames, parts[k + 1], "'arcs' with native or fitted"));
    } else if (parts[k] == "beside") {
      cut.toolRadius = parseNumber(parts[k + 1]);
    } else {
      throw Failure{
          fmt::format("expected 'increment', 'controller', 'method', 'prints', 'arcs', 'beside' or "
                      "'blocks', found '{}'",
                      parts[k])};
    }
  }
  if (!blocks.empty()) {
    cut.splineBlocks = unquote(blocks);
  }
  return cut;
}

} // namespace cncc::ir
