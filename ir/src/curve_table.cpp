#include "cncc/ir/curve_table.h"

#include <algorithm>

namespace cncc::ir {

std::size_t CurveTableEntry::regionCount() const {
  std::size_t count = 0;
  for (const CurvePieceLayout& piece : pieces) {
    count += piece.regionCount();
  }
  return count;
}

std::size_t CurveTableEntry::computedRegionCount() const {
  return static_cast<std::size_t>(std::count(regionSteps.begin(), regionSteps.end(), 0));
}

std::size_t CurveTableEntry::lapOperandCount() const {
  return 3 + 3 * computedRegionCount() + (offsetGrowth ? 1 : 0);
}

// The lists are in order of region (the verifier keeps them so).
const ArcRegion* CurveTableEntry::arcRegion(std::size_t region) const {
  auto found = std::lower_bound(
      arcRegions.begin(), arcRegions.end(), region,
      [](const ArcRegion& arc, std::size_t wanted) { return arc.region < wanted; });
  return found != arcRegions.end() && found->region == region ? &*found : nullptr;
}

bool CurveTableEntry::isWalkRegion(std::size_t region) const {
  return std::binary_search(walkRegions.begin(), walkRegions.end(), region);
}

std::size_t CurveTableEntry::regionOf(std::size_t piece, std::size_t span) const {
  std::size_t region = 0;
  for (std::size_t p = 0; p < piece; ++p) {
    region += pieces[p].regionCount();
  }
  return region + span;
}

std::optional<CurveTableEntry::RegionPlace>
CurveTableEntry::placeOfRegion(std::size_t region) const {
  for (std::size_t piece = 0; piece < pieces.size(); ++piece) {
    if (region < pieces[piece].regionCount()) {
      return RegionPlace{piece, region};
    }
    region -= pieces[piece].regionCount();
  }
  return std::nullopt;
}

std::vector<CurveTableEntry::RegionPlace> CurveTableEntry::regionPlaces() const {
  std::vector<RegionPlace> places;
  for (std::size_t piece = 0; piece < pieces.size(); ++piece) {
    for (std::size_t span = 0; span < pieces[piece].regionCount(); ++span) {
      places.push_back({piece, span});
    }
  }
  return places;
}

std::pair<double, double> CurveTableEntry::regionRange(std::size_t region) const {
  std::optional<RegionPlace> place = placeOfRegion(region);
  return place ? regionRange(*place) : std::pair{0.0, 1.0};
}

std::pair<double, double> CurveTableEntry::regionRange(const RegionPlace& place) const {
  const CurvePieceLayout& piece = pieces[place.piece];
  if (!piece.spans.empty()) {
    return {0.0, 1.0};
  }
  return {piece.from, piece.to};
}

double CurveTableEntry::wholeParameter(std::size_t region, double local) const {
  std::optional<RegionPlace> place = placeOfRegion(region);
  return place ? wholeParameter(*place, local) : to;
}

double CurveTableEntry::wholeParameter(const RegionPlace& place, double local) const {
  const CurvePieceLayout& piece = pieces[place.piece];
  double own = local;
  if (!piece.spans.empty()) {
    auto [spanFrom, spanTo] = piece.spans[place.span];
    own = spanFrom + local * (spanTo - spanFrom);
  }
  return pieces.size() == 1 ? own : piece.start + (own - piece.from);
}

CurveLocation CurveTableEntry::locate(double t) const {
  CurveLocation location;
  std::size_t count = pieces.size();
  while (location.piece + 1 < count && pieces[location.piece + 1].start <= t) {
    ++location.piece;
  }
  const CurvePieceLayout& piece = pieces[location.piece];
  // A single piece is the whole curve: its own parameter is the curve's.
  double own = count == 1 ? t : piece.from + (t - piece.start);
  location.local = std::clamp(own, piece.from, piece.to);
  if (!piece.spans.empty()) {
    while (location.span + 1 < piece.spans.size() &&
           piece.spans[location.span + 1].first <= location.local) {
      ++location.span;
    }
    auto [spanFrom, spanTo] = piece.spans[location.span];
    location.local = std::clamp((location.local - spanFrom) / (spanTo - spanFrom), 0.0, 1.0);
  }
  location.region = regionOf(location.piece, location.span);
  return location;
}

} // namespace cncc::ir
