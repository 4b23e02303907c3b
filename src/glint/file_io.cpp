#include "glint/file_io.h"

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <fstream>
#include <string>
#include <signal.h>
#include <unistd.h>

#include "glint/error.h"

namespace glint {

std::vector<std::byte> readFile(const std::filesystem::path& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    throw Error(path.string() + ": is a directory, expected a file");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw Error(path.string() + ": cannot open (" + std::strerror(errno) + ")");
  }
  std::vector<std::byte> bytes;
  in.seekg(0, std::ios::end);
  const auto size = static_cast<std::streamoff>(in.tellg());
  in.seekg(0, std::ios::beg);
  bytes.resize(static_cast<std::size_t>(size));
  if (size > 0 && !in.read(reinterpret_cast<char*>(bytes.data()), size)) {
    throw Error(path.string() + ": read failed");
  }
  return bytes;
}

namespace {

// A temporary is OUT.tmpPID beside OUT. One left by a process that was killed is removed by the
// next write of OUT: its process no longer exists (kill(pid, 0) fails with ESRCH).
std::filesystem::path temporaryFor(const std::filesystem::path& path) {
  std::filesystem::path temporary = path;
  temporary += ".tmp" + std::to_string(::getpid());
  return temporary;
}

void removeStaleTemporaries(const std::filesystem::path& path) {
  const std::string prefix = path.filename().string() + ".tmp";
  std::error_code ec;
  const std::filesystem::path folder = path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
  for (std::filesystem::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0) continue;
    const std::string digits = name.substr(prefix.size());
    if (digits.size() > 9 || digits.find_first_not_of("0123456789") != std::string::npos) continue;
    const pid_t pid = static_cast<pid_t>(std::stol(digits));
    if (pid <= 0 || pid == ::getpid()) continue;
    if (::kill(pid, 0) == -1 && errno == ESRCH) {
      std::error_code ignored;
      std::filesystem::remove(it->path(), ignored);
    }
  }
}

// A device or a pipe (/dev/stdout, /dev/full), directly or through a symbolic link, is no file to
// replace, and renaming a temporary over it would replace the device: it is written as it is.
bool isDeviceOrPipe(const std::filesystem::path& path) {
  std::error_code ec;
  const std::filesystem::file_status status = std::filesystem::status(path, ec);
  return std::filesystem::is_character_file(status) || std::filesystem::is_fifo(status);
}

// Writes all of `bytes` to `file` (opened with `flags`: a temporary, or a device itself), then
// closes it; throws Error naming `path`, the name the user gave, with the system's reason ("No
// space left on device"). POSIX calls rather than a stream, whose errno after a failed flush need
// not be the write's.
void writeAndClose(const std::filesystem::path& path, const std::filesystem::path& file, int flags,
                   std::span<const std::byte> bytes) {
  const int descriptor = ::open(file.c_str(), flags | O_WRONLY | O_CLOEXEC, 0666);
  if (descriptor < 0) {
    const char* what = (flags & O_CREAT) ? ": cannot create (" : ": cannot open (";
    throw Error(path.string() + what + std::strerror(errno) + ")");
  }
  int failure = 0;
  for (std::size_t written = 0; written < bytes.size() && failure == 0;) {
    const ssize_t n = ::write(descriptor, bytes.data() + written, bytes.size() - written);
    if (n >= 0) {
      written += static_cast<std::size_t>(n);
    } else if (errno != EINTR) {
      failure = errno;
    }
  }
  // Some file systems report a full disk only when the file is closed.
  if (::close(descriptor) != 0 && failure == 0) failure = errno;
  if (failure != 0) throw Error(path.string() + ": cannot write (" + std::strerror(failure) + ")");
}

}  // namespace

void writeFileAtomically(const std::filesystem::path& path, std::span<const std::byte> bytes) {
  writeFilesAtomically({{path, std::vector<std::byte>(bytes.begin(), bytes.end())}});
}

void writeFilesAtomically(const std::vector<FileContents>& files) {
  StagedFiles staged;
  for (const FileContents& file : files) {
    if (!isDeviceOrPipe(file.path)) staged.add(file.path, file.bytes);
  }
  // Devices last among the writes: a failure there still leaves the files as they were.
  for (const FileContents& file : files) {
    if (isDeviceOrPipe(file.path)) writeAndClose(file.path, file.path, 0, file.bytes);
  }
  staged.commit();
}

StagedFiles::~StagedFiles() { removeTemporaries(); }

void StagedFiles::add(const std::filesystem::path& path, std::span<const std::byte> bytes) {
  if (isDeviceOrPipe(path)) {
    writeAndClose(path, path, 0, bytes);
    return;
  }
  // A folder in the file's place would fail its rename after the others': refused first.
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw Error(path.string() + ": cannot write (is a directory)");
  removeStaleTemporaries(path);
  const std::filesystem::path temporary = temporaryFor(path);
  try {
    writeAndClose(path, temporary, O_CREAT | O_TRUNC, bytes);
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw;
  }
  staged_.emplace_back(path, temporary);
}

void StagedFiles::commit() {
  for (const auto& [path, temporary] : staged_) {
    std::error_code ec;
    std::filesystem::rename(temporary, path, ec);
    if (ec) {
      removeTemporaries();
      throw Error(path.string() + ": cannot write (" + ec.message() + ")");
    }
  }
  staged_.clear();
}

void StagedFiles::removeTemporaries() {
  for (const auto& staged : staged_) {
    std::error_code ignored;
    std::filesystem::remove(staged.second, ignored);
  }
  staged_.clear();
}

}  // namespace glint
