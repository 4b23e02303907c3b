// zlib's crc32(), which the dictionary file's checksums use (src/glint/dictionary.cpp): Emscripten's
// zlib comes as a port, which Debian's frozen Emscripten cannot build. The same CRC-32 (ISO 3309,
// reflected polynomial 0xEDB88320) bit by bit; the page checks one file of 400 kB once.
#include <zlib.h>

extern "C" uLong crc32(uLong crc, const Bytef* data, uInt length) {
  if (data == nullptr) return 0;
  crc = ~crc & 0xFFFFFFFFul;
  for (uInt i = 0; i < length; ++i) {
    crc ^= data[i];
    for (int bit = 0; bit < 8; ++bit) crc = (crc >> 1) ^ (0xEDB88320ul & (0ul - (crc & 1ul)));
  }
  return ~crc & 0xFFFFFFFFul;
}
