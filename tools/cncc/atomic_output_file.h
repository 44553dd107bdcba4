// An output file that appears whole or not at all. Writes go to a temporary
// file in the destination's directory, and commit() renames it over the
// destination; if commit() is never reached (an error, an exception) the
// temporary is removed and the destination is left as it was. So a failed
// compile never leaves a partial program, nor half of an old one.
//
// The path "-" means standard output, written directly, and so is a path
// that is not a regular file (/dev/null, a pipe).
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <system_error>

namespace cncc::driver {

class AtomicOutputFile {
public:
  // Creates the temporary file. On failure returns nullopt and sets `error`.
  static std::optional<AtomicOutputFile> create(const std::string& path, std::error_code& error);
  // An output kept in memory (contents()), for a command that runs what a
  // backend writes rather than saving it; its path is empty.
  static AtomicOutputFile inMemory() { return AtomicOutputFile("", "", -1, true); }

  AtomicOutputFile(AtomicOutputFile&& other) noexcept;
  AtomicOutputFile& operator=(AtomicOutputFile&&) = delete;
  AtomicOutputFile(const AtomicOutputFile&) = delete;
  AtomicOutputFile& operator=(const AtomicOutputFile&) = delete;
  ~AtomicOutputFile();

  const std::string& path() const { return path_; }
  bool isStandardOutput() const { return path_ == "-"; }
  const std::string& contents() const { return memory_; }

  // Appends to the output. A failure is remembered and reported by commit().
  void write(std::string_view data);
  // Puts the output in place: flushes standard output, or closes the
  // temporary and renames it over the destination. False (and `error` set)
  // if anything failed, in which case the destination is untouched.
  bool commit(std::error_code& error);
  // Drops what was written (a no-op for standard output).
  void discard();

private:
  AtomicOutputFile(std::string path, std::string temporaryPath, int descriptor,
                   bool inMemory = false)
      : path_(std::move(path)), temporaryPath_(std::move(temporaryPath)), descriptor_(descriptor),
        inMemory_(inMemory) {}

  std::string path_;
  std::string temporaryPath_; // empty for standard output, or once committed
  int descriptor_ = -1;
  std::error_code writeError_;
  bool inMemory_ = false;
  std::string memory_;
};

// Writes `contents` to `path` through an AtomicOutputFile.
bool writeFileAtomically(const std::string& path, std::string_view contents,
                         std::error_code& error);

} // namespace cncc::driver
