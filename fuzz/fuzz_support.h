// What the fuzz targets share: the input as bytes, and a scratch folder of this process for the
// readers that take files or folders.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>

namespace glint::fuzz {

inline std::span<const std::byte> bytesOf(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const std::byte*>(data), size};
}

// An empty folder of this process under the system's temporary folder, made on first use and
// removed at exit.
const std::filesystem::path& scratchFolder();

}  // namespace glint::fuzz
