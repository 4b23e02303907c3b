// The dictionary readers: glint's binary format (Dictionary::deserialise, src/glint/dictionary.cpp)
// and one EXR file of the authors' dictionary folder (loadAuthorsExrDictionary,
// src/glint/dictionary_exr.cpp).
#include <cstring>
#include <fstream>
#include <vector>

#include <zlib.h>

#include "glint/dictionary.h"
#include "glint/dictionary_exr.h"
#include "glint/error.h"
#include "fuzz_support.h"

namespace {

void putU32(std::vector<std::byte>& bytes, std::size_t at, std::uint32_t value) {
  for (int i = 0; i < 4; ++i) bytes[at + i] = static_cast<std::byte>(value >> (8 * i));
}

std::uint32_t crc32Of(const std::byte* data, std::size_t size) {
  return static_cast<std::uint32_t>(crc32(0L, reinterpret_cast<const Bytef*>(data), static_cast<uInt>(size)));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using glint::Dictionary;
  const auto bytes = glint::fuzz::bytesOf(data, size);
  if (size >= 8 && std::memcmp(data, "GLINTDIC", 8) == 0) {
    try {
      Dictionary::deserialise(bytes, "fuzz.gdict");
    } catch (const glint::Error&) {
    }
    // Again with both checksums made to match (docs/dictionary.md, "File format": the payload's at
    // byte 56, the header's over bytes 0 to 59 at 60): a mutation otherwise stops at a checksum and
    // never reaches the header's fields, the sizes or the texels.
    if (size >= 64) {
      std::vector<std::byte> fixed(bytes.begin(), bytes.end());
      putU32(fixed, 56, crc32Of(fixed.data() + 64, fixed.size() - 64));
      putU32(fixed, 60, crc32Of(fixed.data(), 60));
      try {
        Dictionary::deserialise(fixed, "fuzz.gdict");
      } catch (const glint::Error&) {
      }
    }
    return 0;
  }
  // Anything else is the one file of a folder of 1 level, 3 distributions (one RGB file) of 4
  // texels: the folder's name is the authors' convention, dict_<L>_<N>_<R>_<alpha>_<s>.
  static const std::filesystem::path folder = glint::fuzz::scratchFolder() / "dict_1_3_4_0p5_0p02";
  static const bool made = std::filesystem::create_directories(folder);
  (void)made;
  {
    std::ofstream file(folder / "dict_1_3_4_0p5_0p02_0000_0000.exr", std::ios::binary | std::ios::trunc);
    file.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  try {
    glint::loadAuthorsExrDictionary(folder);
  } catch (const glint::Error&) {
  }
  return 0;
}
