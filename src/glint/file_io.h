// Whole-file reads and all-or-nothing writes: an output file either appears complete or not at all.
#pragma once

#include <cstddef>
#include <filesystem>
#include <map>
#include <set>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace glint {

// Reads a whole file; throws Error("<path>: cannot open ...") when it cannot.
std::vector<std::byte> readFile(const std::filesystem::path& path);

// A text's bytes, as the writes below take them.
std::vector<std::byte> textBytes(const std::string& text);

// Writes to a temporary file beside `path`, then renames it over `path`, so that a failure (disk
// full, interrupted process) never leaves a partial file under the final name; a device or a pipe
// is written directly. Throws Error naming the file and the system's reason ("<path>: cannot write
// (No space left on device)").
void writeFileAtomically(const std::filesystem::path& path, std::span<const std::byte> bytes);

// Several files as one output (an image and its preview): every one is written to its temporary
// first, and only when all are complete are they renamed over their names, so that a failed write
// (a full disk) leaves the previous files as they were, never a new one beside a stale one. Only a
// failing rename, after every write succeeded, could leave the files before it renamed.
struct FileContents {
  std::filesystem::path path;
  std::vector<std::byte> bytes;
};
void writeFilesAtomically(const std::vector<FileContents>& files);

// Throws the Error writing `path` would throw for its place, so that a command can refuse an output
// before the work that makes it: a folder in its place ("cannot write (is a directory)"), a
// folder to hold it that does not exist or is a file ("cannot create (...)"). Names written as
// they are (a device, /dev/stdout) pass.
void requireWritablePlace(const std::filesystem::path& path);

// Files that make one output but come one at a time (an orbit's frames): each is written to its
// temporary beside its name as it comes (add), and only commit() renames them all over their
// names, so that a failure at any of them leaves no new file and the files that were there as they
// were. What is not committed is removed when the object goes. A device, a pipe or a name in /dev
// or /proc (/dev/stdout) is no file to replace: add writes it at once. A name given twice is an
// error.
class StagedFiles {
 public:
  StagedFiles() = default;
  StagedFiles(const StagedFiles&) = delete;
  StagedFiles& operator=(const StagedFiles&) = delete;
  ~StagedFiles();

  // Throws Error naming the file (a folder in its place, a full disk) and leaves the others staged.
  void add(const std::filesystem::path& path, std::span<const std::byte> bytes);
  // Throws Error naming the file whose rename fails; the files before it are then in place.
  void commit();

 private:
  void removeTemporaries();
  std::vector<std::pair<std::filesystem::path, std::filesystem::path>> staged_;  // (name, temporary)
  std::set<std::filesystem::path> stagedNames_;  // each staged name as weakly_canonical spells it
  // Killed runs' temporaries by folder (listed once) and by the name of the file each was for.
  std::map<std::filesystem::path, std::multimap<std::string, std::filesystem::path>> staleTemporaries_;
};

}  // namespace glint
