#include "cncc/lsp/cut_lenses.h"

#include "cncc/lsp/program_map.h"
#include "cncc/lsp/protocol_json.h"
#include "cncc/lsp/uri.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <limits>
#include <set>

namespace cncc::lsp {

namespace {

namespace fs = std::filesystem;

// The path's canonical form where it exists, so that one file has one name.
std::string canonicalPath(const std::string& path) {
  std::error_code error;
  fs::path canonical = fs::weakly_canonical(path, error);
  return error ? path : canonical.string();
}

double numberOrNaN(const Json& entry, const char* key) {
  auto found = entry.find(key);
  return found != entry.end() && found->is_number() ? found->get<double>()
                                                    : std::numeric_limits<double>::quiet_NaN();
}

std::optional<MappedCut> mappedCut(const Json& map, const Json& entry) {
  std::size_t source = entry.is_object() ? entry.value("source", std::size_t{0}) : 0;
  const Json& sources = map["sources"];
  if (!entry.is_object() || source >= sources.size() || !sources[source].is_string()) {
    return std::nullopt;
  }
  MappedCut cut;
  cut.source = canonicalPath(resolvedSourcePath(map, sources[source].get<std::string>()));
  cut.line = entry.value("line", 0u);
  cut.column = entry.value("column", 0u);
  cut.blocks = entry.value("blocks", std::size_t{0});
  cut.bytes = entry.value("bytes", std::size_t{0});
  cut.measured = entry.contains("deviation");
  cut.deviation = numberOrNaN(entry, "deviation");
  cut.tolerance = numberOrNaN(entry, "tolerance");
  return cut;
}

std::string lensTitle(const MapSummary& summary, const MappedCut& cut) {
  std::string program = fs::path(summary.program).filename().string();
  std::string title = fmt::format("{} ({}): {} block{}, {} bytes", program, summary.target,
                                  cut.blocks, cut.blocks == 1 ? "" : "s", cut.bytes);
  if (!cut.measured) {
    return title;
  }
  if (std::isnan(cut.deviation)) {
    return title + ", no feed move";
  }
  title += fmt::format(", largest deviation {:.4g} {}", cut.deviation, summary.unit);
  if (!std::isnan(cut.tolerance)) {
    title += fmt::format(" (tolerance {:g})", cut.tolerance);
  }
  return title;
}

} // namespace

std::optional<MapSummary> summariseMap(const Json& map) {
  if (!map.is_object() || map.value("version", 0) != 1 || !map.contains("sources") ||
      !map["sources"].is_array() || !map.contains("program") || !map["program"].is_string()) {
    return std::nullopt;
  }
  MapSummary summary;
  summary.program = canonicalPath(resolvedSourcePath(map, map["program"].get<std::string>()));
  summary.programHash = map.value("programHash", std::string());
  summary.target = map.value("target", std::string("?"));
  summary.unit = map.value("unit", std::string("mm"));
  if (map.contains("cuts") && map["cuts"].is_array()) {
    for (const Json& entry : map["cuts"]) {
      if (std::optional<MappedCut> cut = mappedCut(map, entry)) {
        summary.cuts.push_back(std::move(*cut));
      }
    }
  }
  return summary;
}

std::vector<std::string> CutLensIndex::mapFiles() const {
  std::set<std::string> found;
  std::size_t visited = 0;
  for (const std::string& directory : search_.directories) {
    std::error_code error;
    fs::recursive_directory_iterator entries(directory,
                                             fs::directory_options::skip_permission_denied, error);
    for (; !error && entries != fs::recursive_directory_iterator(); entries.increment(error)) {
      if (++visited > search_.maximumEntries || found.size() >= search_.maximumMaps) {
        return {found.begin(), found.end()};
      }
      if (entries.depth() >= search_.maximumDepth) {
        entries.disable_recursion_pending();
      }
      std::string name = entries->path().filename().string();
      if (name.starts_with(".")) {
        entries.disable_recursion_pending(); // .git and the like
      } else if (name.ends_with(".map.json") && entries->is_regular_file(error)) {
        found.insert(canonicalPath(entries->path().string()));
      }
    }
  }
  return {found.begin(), found.end()};
}

const std::optional<MapSummary>& CutLensIndex::summaryOf(const std::string& path) {
  std::error_code error;
  fs::file_time_type written = fs::last_write_time(path, error);
  std::uintmax_t size = error ? 0 : fs::file_size(path, error);
  CachedMap& cached = maps_[path];
  if (!error && cached.written == written && cached.size == size) {
    return cached.summary;
  }
  cached = CachedMap{written, size, std::nullopt};
  if (error || size > search_.maximumMapBytes) {
    return cached.summary;
  }
  std::ifstream file(path, std::ios::binary);
  Json map = Json::parse(file, nullptr, false);
  cached.summary = summariseMap(map);
  return cached.summary;
}

bool CutLensIndex::programIsCurrent(const MapSummary& summary) {
  std::error_code error;
  fs::file_time_type written = fs::last_write_time(summary.program, error);
  std::uintmax_t size = error ? 0 : fs::file_size(summary.program, error);
  if (error || size > search_.maximumProgramBytes) {
    return false;
  }
  CachedHash& cached = programs_[summary.program];
  if (cached.hash.empty() || cached.written != written || cached.size != size) {
    std::ifstream file(summary.program, std::ios::binary);
    std::string text{std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
    cached = CachedHash{written, size, programHash(text)};
  }
  return cached.hash == summary.programHash;
}

Json CutLensIndex::lenses(std::string_view uri) {
  Json lenses = Json::array();
  std::optional<std::string> path = pathFromUri(uri);
  if (!path) {
    return lenses;
  }
  std::string document = canonicalPath(*path);
  std::vector<const MapSummary*> current;
  for (const std::string& mapPath : mapFiles()) {
    const std::optional<MapSummary>& summary = summaryOf(mapPath);
    if (summary && programIsCurrent(*summary)) {
      current.push_back(&*summary);
    }
  }
  std::sort(current.begin(), current.end(),
            [](const MapSummary* a, const MapSummary* b) { return a->program < b->program; });
  for (const MapSummary* summary : current) {
    for (const MappedCut& cut : summary->cuts) {
      if (cut.source != document || cut.line == 0) {
        continue;
      }
      Position at{cut.line - 1, cut.column > 0 ? cut.column - 1 : 0};
      lenses.push_back({{"range", toJson(Range{at, at})},
                        {"command", {{"title", lensTitle(*summary, cut)}, {"command", ""}}}});
    }
  }
  return lenses;
}

} // namespace cncc::lsp
