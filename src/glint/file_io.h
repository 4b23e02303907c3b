// Whole-file reads and all-or-nothing writes: an output file either appears complete or not at all.
#pragma once

#include <cstddef>
#include <filesystem>
#include <span>
#include <vector>

namespace glint {

// Reads a whole file; throws Error("<path>: cannot open ...") when it cannot.
std::vector<std::byte> readFile(const std::filesystem::path& path);

// Writes to a temporary file beside `path`, then renames it over `path`, so that a failure (disk
// full, interrupted process) never leaves a partial file under the final name.
void writeFileAtomically(const std::filesystem::path& path, std::span<const std::byte> bytes);

}  // namespace glint
