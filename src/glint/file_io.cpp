#include "file_io.h"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <string>
#include <signal.h>
#include <unistd.h>

#include "error.h"

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

void writeTemporary(const std::filesystem::path& path, const std::filesystem::path& temporary,
                    std::span<const std::byte> bytes) {
  std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
  if (!out) {
    throw Error(path.string() + ": cannot create (" + std::strerror(errno) + ")");
  }
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  out.flush();
  if (!out) {
    out.close();
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw Error(path.string() + ": write failed");
  }
}

}  // namespace

void writeFileAtomically(const std::filesystem::path& path, std::span<const std::byte> bytes) {
  writeFilesAtomically({{path, std::vector<std::byte>(bytes.begin(), bytes.end())}});
}

void writeFilesAtomically(const std::vector<FileContents>& files) {
  std::vector<std::filesystem::path> temporaries;
  const auto removeTemporaries = [&] {
    for (const std::filesystem::path& temporary : temporaries) {
      std::error_code ignored;
      std::filesystem::remove(temporary, ignored);
    }
  };
  try {
    for (const FileContents& file : files) {
      // A folder in a file's place would fail its rename after the others': refused first.
      std::error_code ec;
      if (std::filesystem::is_directory(file.path, ec)) throw Error(file.path.string() + ": cannot write (is a directory)");
      removeStaleTemporaries(file.path);
      temporaries.push_back(temporaryFor(file.path));
      writeTemporary(file.path, temporaries.back(), file.bytes);
    }
  } catch (...) {
    removeTemporaries();
    throw;
  }
  for (std::size_t i = 0; i < files.size(); ++i) {
    std::error_code ec;
    std::filesystem::rename(temporaries[i], files[i].path, ec);
    if (ec) {
      removeTemporaries();
      throw Error(files[i].path.string() + ": cannot write (" + ec.message() + ")");
    }
  }
}

}  // namespace glint
