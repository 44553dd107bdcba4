// Code lenses on the cut statements of a CDL file: what the last compile of
// each program made from the file did with the cut (blocks, bytes and, when
// that compile measured it with --stats, the largest deviation from the
// curve), read from the programs' source maps (`cncc --source-map`). A map
// counts only while its program is the one it was written with.
#pragma once

#include "cncc/lsp/json_rpc.h"

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace cncc::lsp {

// Where maps are looked for, and how much looking a request may do.
struct CutLensSearch {
  std::vector<std::string> directories; // searched for *.map.json
  int maximumDepth = 3;                 // of subdirectories below each
  std::size_t maximumEntries = 4096;    // directory entries visited in all
  std::size_t maximumMaps = 32;         // maps read
  std::uintmax_t maximumMapBytes = 8u << 20;
  std::uintmax_t maximumProgramBytes = 64u << 20;
};

// One cut statement of a map, and what its program made of it.
struct MappedCut {
  std::string source; // the CDL file, absolute
  std::uint32_t line = 0;
  std::uint32_t column = 0;
  std::size_t blocks = 0;
  std::size_t bytes = 0;
  bool measured = false;
  double deviation = 0; // NaN: no feed move
  double tolerance = 0; // NaN: samples= or spacing= chose the points
};

// What a lens needs of one map: its program and its cuts.
struct MapSummary {
  std::string program; // absolute
  std::string programHash;
  std::string target;
  std::string unit;
  std::vector<MappedCut> cuts;
};

// The maps found so far, read again only when they change on disk.
class CutLensIndex {
public:
  explicit CutLensIndex(CutLensSearch search) : search_(std::move(search)) {}

  // `textDocument/codeLens` for the CDL file at `uri`: a lens per cut
  // statement and current program, in program name order.
  Json lenses(std::string_view uri);

  void setDirectories(std::vector<std::string> directories) {
    search_.directories = std::move(directories);
  }

private:
  struct CachedMap {
    std::filesystem::file_time_type written;
    std::uintmax_t size = 0;
    std::optional<MapSummary> summary; // nullopt: not a map cncc reads
  };
  struct CachedHash {
    std::filesystem::file_time_type written;
    std::uintmax_t size = 0;
    std::string hash;
  };

  std::vector<std::string> mapFiles() const;
  const std::optional<MapSummary>& summaryOf(const std::string& path);
  bool programIsCurrent(const MapSummary& summary);

  CutLensSearch search_;
  std::map<std::string, CachedMap> maps_;
  std::map<std::string, CachedHash> programs_;
};

// The summary of a map's JSON (`directory` resolves relative paths), or
// nullopt when it is not a version 1 map.
std::optional<MapSummary> summariseMap(const Json& map);

} // namespace cncc::lsp
