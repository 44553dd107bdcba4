#include "atomic_output_file.h"

#include <cerrno>
#include <cstdio>
#include <fcntl.h>
#include <filesystem>
#include <sys/stat.h>
#include <unistd.h>
#include <vector>

namespace cncc::driver {

namespace {

namespace fs = std::filesystem;

std::error_code lastError() {
  return {errno, std::generic_category()};
}

// `dir/.name.tmp-XXXXXX`, the pattern mkstemp fills in.
std::string temporaryPattern(const fs::path& destination) {
  fs::path pattern = destination.parent_path() / ("." + destination.filename().string() + ".tmp-");
  return pattern.string() + "XXXXXX";
}

// What a newly created file would get: 0666 less the umask (mkstemp uses 0600).
mode_t defaultFileMode() {
  mode_t mask = ::umask(0);
  ::umask(mask);
  return 0666 & ~mask;
}

} // namespace

std::optional<AtomicOutputFile> AtomicOutputFile::create(const std::string& path,
                                                         std::error_code& error) {
  error.clear();
  if (path == "-") {
    return AtomicOutputFile(path, "", -1);
  }
  fs::path destination(path);
  std::error_code statusError;
  if (!destination.has_filename() || fs::is_directory(destination, statusError)) {
    error = std::make_error_code(std::errc::is_a_directory);
    return std::nullopt;
  }
  if (fs::exists(destination, statusError) && !fs::is_regular_file(destination, statusError)) {
    // A device or a pipe (/dev/null, /dev/stdout, a FIFO): written to as it
    // is, since renaming a file over it would replace the device itself.
    int descriptor = ::open(path.c_str(), O_WRONLY | O_TRUNC | O_CLOEXEC);
    if (descriptor < 0) {
      error = lastError();
      return std::nullopt;
    }
    return AtomicOutputFile(path, "", descriptor);
  }
  std::string pattern = temporaryPattern(destination);
  std::vector<char> buffer(pattern.begin(), pattern.end());
  buffer.push_back('\0');
  int descriptor = ::mkstemp(buffer.data());
  if (descriptor < 0) {
    error = lastError();
    return std::nullopt;
  }
  ::fchmod(descriptor, defaultFileMode());
  return AtomicOutputFile(path, buffer.data(), descriptor);
}

AtomicOutputFile::AtomicOutputFile(AtomicOutputFile&& other) noexcept
    : path_(std::move(other.path_)), temporaryPath_(std::move(other.temporaryPath_)),
      descriptor_(other.descriptor_), writeError_(other.writeError_), inMemory_(other.inMemory_),
      memory_(std::move(other.memory_)) {
  other.temporaryPath_.clear();
  other.descriptor_ = -1;
}

AtomicOutputFile::~AtomicOutputFile() {
  discard();
}

void AtomicOutputFile::write(std::string_view data) {
  if (writeError_) {
    return;
  }
  if (inMemory_) {
    memory_ += data;
    return;
  }
  if (isStandardOutput()) {
    if (std::fwrite(data.data(), 1, data.size(), stdout) != data.size()) {
      writeError_ = lastError();
    }
    return;
  }
  while (!data.empty()) {
    ssize_t written = ::write(descriptor_, data.data(), data.size());
    if (written < 0 && errno == EINTR) {
      continue;
    }
    if (written < 0) {
      writeError_ = lastError();
      return;
    }
    data.remove_prefix(static_cast<std::size_t>(written));
  }
}

bool AtomicOutputFile::commit(std::error_code& error) {
  error = writeError_;
  if (inMemory_) {
    return true;
  }
  if (isStandardOutput()) {
    if (!error && std::fflush(stdout) != 0) {
      error = lastError();
    }
    return !error;
  }
  if (!error && ::close(descriptor_) != 0) {
    error = lastError();
  }
  descriptor_ = -1;
  if (!error && !temporaryPath_.empty() &&
      std::rename(temporaryPath_.c_str(), path_.c_str()) != 0) {
    error = lastError();
  }
  if (error) {
    discard();
    return false;
  }
  temporaryPath_.clear();
  return true;
}

void AtomicOutputFile::discard() {
  if (descriptor_ >= 0) {
    ::close(descriptor_);
    descriptor_ = -1;
  }
  if (!temporaryPath_.empty()) {
    ::unlink(temporaryPath_.c_str());
    temporaryPath_.clear();
  }
}

bool writeFileAtomically(const std::string& path, std::string_view contents,
                         std::error_code& error) {
  std::optional<AtomicOutputFile> file = AtomicOutputFile::create(path, error);
  if (!file) {
    return false;
  }
  file->write(contents);
  return file->commit(error);
}

} // namespace cncc::driver
