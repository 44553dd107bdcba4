// Loads the main file and everything it imports, once each, and reports
// imports that cannot be found or that form a cycle.
#include "cncc/frontend/parser.h"

#include "parallel_work.h"
#include "sema_context.h"

#include <filesystem>
#include <fmt/format.h>

namespace cncc::frontend {

namespace {

namespace fs = std::filesystem;

class ModuleLoader {
public:
  explicit ModuleLoader(SemaContext& context) : context_(context) {}

  void loadMain(FileId mainFile) { load(mainFile); }

private:
  // Parses a file unless it was parsed already; returns its module.
  Module& load(FileId file) {
    for (Module& module : context_.program.modules) {
      if (module.file == file) {
        return module;
      }
    }
    Module& module = context_.program.modules.emplace_back(
        parseModule(context_.sources, file, context_.diagnostics, context_.options));
    std::string canonicalPath = canonical(context_.sources.file(file).path());
    loadedFiles_[canonicalPath] = file;
    stack_.push_back({file, canonicalPath, nullptr});
    for (ItemPtr& item : module.items) {
      if (item->kind == ItemKind::Import) {
        loadImport(as<ImportItem>(*item), file);
      }
    }
    stack_.pop_back();
    return module;
  }

  void loadImport(ImportItem& import, FileId importingFile) {
    std::optional<std::string> path = resolve(std::string(import.path), importingFile);
    if (!path) {
      context_.report(DiagnosticKind::ImportNotFound, import.pathSpan,
                      fmt::format("cannot find module \"{}\" (searched beside this file{})",
                                  import.path,
                                  context_.options.importPaths.empty()
                                      ? ""
                                      : ", in -I directories and the standard library"));
      return;
    }
    std::string canonicalPath = canonical(*path);
    for (std::size_t i = 0; i < stack_.size(); ++i) {
      if (stack_[i].canonicalPath == canonicalPath) {
        reportCycle(import, i);
        return;
      }
    }
    std::optional<FileId> file = loadedFiles_.contains(canonicalPath)
                                     ? std::optional(loadedFiles_.at(canonicalPath))
                                     : context_.sources.loadFile(*path);
    if (!file) {
      context_.report(DiagnosticKind::ImportNotFound, import.pathSpan,
                      fmt::format("cannot read module \"{}\" at '{}'", import.path, *path));
      return;
    }
    import.resolvedFile = *file;
    stack_.back().import = &import;
    load(*file);
  }

  void reportCycle(const ImportItem& import, std::size_t cycleStart) {
    Diagnostic* diagnostic =
        context_.report(DiagnosticKind::ImportCycle, import.pathSpan,
                        fmt::format("importing \"{}\" forms a cycle", import.path));
    for (std::size_t i = cycleStart; i + 1 < stack_.size(); ++i) {
      const ImportItem* step = stack_[i].import;
      if (step != nullptr) {
        context_.diagnostics.addNote(diagnostic, step->pathSpan,
                                     fmt::format("\"{}\" is imported here", step->path));
      }
    }
  }

  std::optional<std::string> resolve(const std::string& name, FileId importingFile) const {
    std::string fileName = fs::path(name).has_extension() ? name : name + ".cdl";
    std::vector<fs::path> directories;
    fs::path importing(context_.sources.file(importingFile).path());
    directories.push_back(importing.parent_path());
    for (const std::string& directory : context_.options.importPaths) {
      directories.emplace_back(directory);
    }
    for (const fs::path& directory : directories) {
      fs::path candidate = directory / fileName;
      std::error_code error;
      if (fs::is_regular_file(candidate, error)) {
        // Keep the spelling relative when it was, so messages stay short.
        return candidate.lexically_normal().string();
      }
    }
    return std::nullopt;
  }

  static std::string canonical(const std::string& path) {
    std::error_code error;
    return fs::weakly_canonical(path, error).string();
  }

  struct Frame {
    FileId file;
    std::string canonicalPath;
    const ImportItem* import; // the import being followed from this file
  };

  SemaContext& context_;
  std::vector<Frame> stack_;
  std::map<std::string, FileId> loadedFiles_; // by canonical path
};

} // namespace

void loadModules(SemaContext& context, FileId mainFile) {
  ModuleLoader(context).loadMain(mainFile);
}

} // namespace cncc::frontend
