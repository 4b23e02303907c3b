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

// The temporaries in `folder` left by processes that no longer exist, by the name of the file each
// was for: NAME.tmpPID where kill(PID, 0) fails with ESRCH (not this process's own).
std::multimap<std::string, std::filesystem::path> staleTemporariesIn(const std::filesystem::path& folder) {
  std::multimap<std::string, std::filesystem::path> stale;
  std::error_code ec;
  for (std::filesystem::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    const std::size_t tmp = name.rfind(".tmp");
    if (tmp == std::string::npos || tmp == 0) continue;
    const std::string digits = name.substr(tmp + 4);
    if (digits.empty() || digits.size() > 9 || digits.find_first_not_of("0123456789") != std::string::npos) continue;
    const pid_t pid = static_cast<pid_t>(std::stol(digits));
    if (pid <= 0 || pid == ::getpid()) continue;
    if (::kill(pid, 0) == -1 && errno == ESRCH) stale.emplace(name.substr(0, tmp), it->path());
  }
  return stale;
}

// What is written as it is, not through a temporary renamed over it: a device or a pipe
// (/dev/full, /dev/stdout on a terminal), directly or through a symbolic link, and any name in or
// linked into /dev or /proc (/dev/stdout when the shell sends it to a file is a link to
// /proc/self/fd/1, which names a regular file: a rename would replace /dev/stdout itself).
bool writtenInPlace(const std::filesystem::path& path) {
  std::error_code ec;
  const std::filesystem::file_status status = std::filesystem::status(path, ec);
  if (std::filesystem::is_character_file(status) || std::filesystem::is_fifo(status)) return true;
  const auto isSystemName = [](const std::filesystem::path& name) {
    std::error_code ignored;
    const std::string text = std::filesystem::absolute(name, ignored).lexically_normal().string();
    return text.rfind("/dev/", 0) == 0 || text.rfind("/proc/", 0) == 0;
  };
  std::filesystem::path link = path;
  for (int depth = 0; depth < 8; ++depth) {  // a link's own links, as far as the kernel follows them
    if (isSystemName(link)) return true;
    if (!std::filesystem::is_symlink(std::filesystem::symlink_status(link, ec))) return false;
    const std::filesystem::path target = std::filesystem::read_symlink(link, ec);
    if (ec) return false;
    link = target.is_absolute() ? target : link.parent_path() / target;
  }
  return false;
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

void requireWritablePlace(const std::filesystem::path& path) {
  if (writtenInPlace(path)) return;
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw Error(path.string() + ": cannot write (is a directory)");
  const std::filesystem::path folder = path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
  const std::filesystem::file_status status = std::filesystem::status(folder, ec);
  if (!std::filesystem::exists(status)) throw Error(path.string() + ": cannot create (" + std::strerror(ENOENT) + ")");
  if (!std::filesystem::is_directory(status)) throw Error(path.string() + ": cannot create (" + std::strerror(ENOTDIR) + ")");
}

std::vector<std::byte> textBytes(const std::string& text) {
  const auto* first = reinterpret_cast<const std::byte*>(text.data());
  return {first, first + text.size()};
}

void writeFileAtomically(const std::filesystem::path& path, std::span<const std::byte> bytes) {
  writeFilesAtomically({{path, std::vector<std::byte>(bytes.begin(), bytes.end())}});
}

void writeFilesAtomically(const std::vector<FileContents>& files) {
  StagedFiles staged;
  for (const FileContents& file : files) {
    if (!writtenInPlace(file.path)) staged.add(file.path, file.bytes);
  }
  // Devices last among the writes: a failure there still leaves the files as they were.
  for (const FileContents& file : files) {
    if (writtenInPlace(file.path)) writeAndClose(file.path, file.path, 0, file.bytes);
  }
  staged.commit();
}

StagedFiles::~StagedFiles() { removeTemporaries(); }

void StagedFiles::add(const std::filesystem::path& path, std::span<const std::byte> bytes) {
  if (writtenInPlace(path)) {
    writeAndClose(path, path, 0, bytes);
    return;
  }
  // A folder in the file's place would fail its rename after the others': refused first. So is a
  // name given twice (`-o a.png --plot ./a.png`): both would share one temporary.
  requireWritablePlace(path);
  std::error_code ec;
  std::filesystem::path canonical = std::filesystem::weakly_canonical(path, ec);
  if (ec) canonical = std::filesystem::absolute(path, ec).lexically_normal();
  if (stagedNames_.count(canonical) > 0) throw Error(path.string() + ": given twice as an output");
  // A killed run's temporary of this very name goes; the folder is listed once, not once a file
  // (an orbit of N frames would otherwise read it N times).
  const std::filesystem::path folder = path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
  auto stale = staleTemporaries_.find(folder);
  if (stale == staleTemporaries_.end()) stale = staleTemporaries_.emplace(folder, staleTemporariesIn(folder)).first;
  const auto [first, last] = stale->second.equal_range(path.filename().string());
  for (auto it = first; it != last; ++it) {
    std::error_code ignored;
    std::filesystem::remove(it->second, ignored);
  }
  const std::filesystem::path temporary = temporaryFor(path);
  staged_.reserve(staged_.size() + 1);  // so that recording it below cannot throw and lose it
  const auto name = stagedNames_.insert(canonical).first;
  try {
    writeAndClose(path, temporary, O_CREAT | O_TRUNC, bytes);
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    stagedNames_.erase(name);
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
  stagedNames_.clear();
}

void StagedFiles::removeTemporaries() {
  for (const auto& staged : staged_) {
    std::error_code ignored;
    std::filesystem::remove(staged.second, ignored);
  }
  staged_.clear();
  stagedNames_.clear();
}

}  // namespace glint
