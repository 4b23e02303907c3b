#include "glint/decoder_checks.h"

#include <optional>
#include <string>

#include "glint/error.h"

namespace glint {

namespace {

std::uint32_t byteAt(std::span<const std::byte> bytes, std::size_t at) {
  return at < bytes.size() ? std::to_integer<std::uint32_t>(bytes[at]) : 0u;
}

std::uint32_t bigEndian32(std::span<const std::byte> bytes, std::size_t at) {
  return byteAt(bytes, at) << 24 | byteAt(bytes, at + 1) << 16 | byteAt(bytes, at + 2) << 8 | byteAt(bytes, at + 3);
}

bool isType(std::span<const std::byte> bytes, std::size_t at, const char (&type)[5]) {
  for (std::size_t i = 0; i < 4; ++i) {
    if (byteAt(bytes, at + i) != static_cast<unsigned char>(type[i])) return false;
  }
  return true;
}

// One DHT segment as stb_image's stbi__process_marker reads it: `length` includes its own two
// bytes; tables follow (class and slot, 16 code counts, then the codes' values) until it is used
// up. stb_image reads a table's counts and builds it before comparing with the length, even past
// the segment's end (reading zeros past the file's end): so does this walk.
void checkHuffmanSegment(std::span<const std::byte> bytes, std::size_t at, std::uint32_t length) {
  long remaining = static_cast<long>(length) - 2;
  while (remaining > 0) {
    std::uint32_t codes = 0;
    for (std::size_t i = 0; i < 16; ++i) codes += byteAt(bytes, at + 1 + i);
    if (codes > 256) {
      throw Error("corrupt JPEG (a Huffman table with " + std::to_string(codes) + " codes, more than 256)");
    }
    remaining -= 17 + static_cast<long>(codes);
    at += 17 + codes;
  }
  if (remaining != 0) throw Error("corrupt JPEG (a Huffman table segment's length does not match its tables)");
}

}  // namespace

bool looksLikePng(std::span<const std::byte> bytes) {
  static constexpr unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  if (bytes.size() < sizeof kSignature) return false;
  for (std::size_t i = 0; i < sizeof kSignature; ++i) {
    if (byteAt(bytes, i) != kSignature[i]) return false;
  }
  return true;
}

bool looksLikeJpeg(std::span<const std::byte> bytes) {
  return bytes.size() >= 2 && byteAt(bytes, 0) == 0xFF && byteAt(bytes, 1) == 0xD8;
}

void checkImagePixels(std::uint64_t width, std::uint64_t height, std::uint64_t maxPixels) {
  // Sides are at most 2^32 - 1 in every format read, so the product fits in 64 bits.
  if (width * height > maxPixels) {
    throw Error("image too large (" + std::to_string(width) + "x" + std::to_string(height) + ", more than " +
                std::to_string(maxPixels) + " pixels)");
  }
}

void checkPngForDecoder(std::span<const std::byte> bytes, std::uint64_t maxPixels) {
  // Chunks: length (4 bytes, big-endian), type (4), data, CRC (4), after the 8-byte signature.
  std::size_t at = 8;
  if (bytes.size() < at + 8 + 13 || !isType(bytes, at + 4, "IHDR") || bigEndian32(bytes, at) != 13) {
    throw Error("truncated or corrupt PNG (no 13-byte IHDR chunk first)");
  }
  const std::uint32_t width = bigEndian32(bytes, at + 8);
  const std::uint32_t height = bigEndian32(bytes, at + 12);
  if (width == 0 || height == 0) {
    throw Error("zero-size image (" + std::to_string(width) + "x" + std::to_string(height) + ")");
  }
  if (width > kMaxImageSide || height > kMaxImageSide) {
    throw Error("image too large (" + std::to_string(width) + "x" + std::to_string(height) + ", at most " +
                std::to_string(kMaxImageSide) + " a side)");
  }
  checkImagePixels(width, height, maxPixels);
  bool seenData = false;
  while (at + 8 <= bytes.size()) {
    const std::uint32_t length = bigEndian32(bytes, at);
    if (length > 0x7FFFFFFFu) throw Error("corrupt PNG (a chunk of " + std::to_string(length) + " bytes)");
    if (isType(bytes, at + 4, "IEND")) break;
    // The decoder allocates what a chunk declares before it reads it: a length past the file's end
    // would have it ask for up to 2 GiB for a file of a few bytes.
    if (12 + static_cast<std::uint64_t>(length) > bytes.size() - at) {
      throw Error("truncated or corrupt PNG (a chunk declares " + std::to_string(length) + " bytes of data, which with its CRC need " +
                  std::to_string(static_cast<std::uint64_t>(length) + 4) + ", and " + std::to_string(bytes.size() - at - 8) +
                  " follow its header)");
    }
    if (isType(bytes, at + 4, "IDAT")) {
      if (length == 0 && !seenData) throw Error("corrupt PNG (an empty IDAT chunk before the image data)");
      seenData = true;
    }
    at += 12 + static_cast<std::size_t>(length);
  }
}

void checkJpegForDecoder(std::span<const std::byte> bytes, std::uint64_t maxPixels) {
  std::size_t at = 2;  // after the start-of-image marker
  while (at < bytes.size()) {
    // stb_image skips bytes that are not 0xFF between segments, then 0xFF fill bytes.
    if (byteAt(bytes, at) != 0xFF) {
      ++at;
      continue;
    }
    while (at < bytes.size() && byteAt(bytes, at) == 0xFF) ++at;
    if (at >= bytes.size()) break;
    const std::uint32_t marker = byteAt(bytes, at++);
    if (marker == 0xD9) break;                                           // end of image
    if (marker == 0x00 || marker == 0x01 || (marker >= 0xD0 && marker <= 0xD8)) continue;  // no length
    const std::uint32_t length = byteAt(bytes, at) << 8 | byteAt(bytes, at + 1);
    if (marker == 0xC4) checkHuffmanSegment(bytes, at + 2, length);
    // A frame header (baseline, extended or progressive, the frames stb_image decodes): length,
    // precision, then height and width, big-endian.
    if ((marker == 0xC0 || marker == 0xC1 || marker == 0xC2) && length >= 7) {
      checkImagePixels(byteAt(bytes, at + 5) << 8 | byteAt(bytes, at + 6), byteAt(bytes, at + 3) << 8 | byteAt(bytes, at + 4),
                       maxPixels);
    }
    if (length < 2) break;  // stb_image refuses the file here
    at += length;
    if (marker == 0xDA) {
      // A scan's entropy-coded data: 0xFF is followed by 0x00 (a stuffed byte) or a restart marker
      // within it; any other marker ends it, and stb_image goes on from there.
      while (at < bytes.size()) {
        if (byteAt(bytes, at) != 0xFF) {
          ++at;
          continue;
        }
        std::size_t next = at + 1;
        while (next < bytes.size() && byteAt(bytes, next) == 0xFF) ++next;
        const std::uint32_t following = byteAt(bytes, next);
        if (next < bytes.size() && (following == 0x00 || (following >= 0xD0 && following <= 0xD7))) {
          at = next + 1;
          continue;
        }
        break;  // at the marker's 0xFF (or the end): the outer walk reads it
      }
    }
  }
}

void checkExrForDecoder(std::span<const std::byte> bytes) {
  // A C string at `at` within the bytes, or nullopt when it runs past their end.
  auto cString = [&](std::size_t at) -> std::optional<std::string> {
    std::string text;
    for (std::size_t i = at; i < bytes.size(); ++i) {
      const char c = static_cast<char>(std::to_integer<unsigned char>(bytes[i]));
      if (c == '\0') return text;
      text += c;
    }
    return std::nullopt;
  };
  auto littleEndian32 = [&](std::size_t at) {
    return byteAt(bytes, at) | byteAt(bytes, at + 1) << 8 | byteAt(bytes, at + 2) << 16 | byteAt(bytes, at + 3) << 24;
  };
  // The version field's tiled flag (bit 9): tinyexr reads a "tiles" attribute only then.
  const bool tiledFile = (byteAt(bytes, 5) & 0x02u) != 0;
  bool tiled = false;  // what tinyexr has set once it has read a valid "tiles" attribute
  // tinyexr reads the attributes in order until the header's end or one it cannot read, and then,
  // even after an error, converts what it has read: each attribute is checked as it comes.
  std::size_t at = 8;  // after the magic number and the version field
  while (true) {
    const std::optional<std::string> name = cString(at);
    if (!name || name->empty()) return;  // past the end, or the header's end
    const std::optional<std::string> type = cString(at + name->size() + 1);
    if (!type) return;
    const std::size_t sizeAt = at + name->size() + 1 + type->size() + 1;
    if (sizeAt + 4 > bytes.size()) return;
    const std::uint32_t size = littleEndian32(sizeAt);
    const std::size_t valueAt = sizeAt + 4;
    if (size > bytes.size() - valueAt || (size == 0 && *type != "string")) return;  // tinyexr stops here
    if (tiledFile && *name == "tiles") {
      if (size != 9) throw Error("corrupt EXR (its tiles attribute holds " + std::to_string(size) + " bytes, not 9)");
      tiled = tiled || (littleEndian32(valueAt) <= 0x7fffffffu && littleEndian32(valueAt + 4) <= 0x7fffffffu);
    }
    if (*name == "type" && size > 0 && byteAt(bytes, valueAt) != 0) {
      std::string kind;  // tinyexr keeps the value up to its first zero byte
      for (std::size_t i = valueAt; i < valueAt + size && byteAt(bytes, i) != 0; ++i) kind += static_cast<char>(byteAt(bytes, i));
      // A single-part image: scanlines in a file without the tiled flag, or tiles after a valid
      // "tiles" attribute (OpenEXR writes attributes sorted by name, "tiles" before "type").
      const bool consistent = (kind == "scanlineimage" && !tiledFile) || (kind == "tiledimage" && tiled);
      if (!consistent) {
        throw Error("unsupported EXR (its type attribute is \"" + kind + "\" in a " + (tiledFile ? "tiled" : "scanline") +
                    " file; expected a single-part scanline or tiled image)");
      }
    }
    at = valueAt + size;
  }
}

void checkGltfImageForDecoder(std::span<const std::byte> bytes, std::uint64_t maxPixels) {
  if (looksLikePng(bytes)) return checkPngForDecoder(bytes, maxPixels);
  if (looksLikeJpeg(bytes)) return checkJpegForDecoder(bytes, maxPixels);
  throw Error("not a PNG or JPEG image (the formats glTF 2.0 allows)");
}

std::string decoderReason(const char* reason, const std::string& otherwise) {
  if (reason == nullptr || *reason == '\0') return otherwise;
  std::string text = reason;
  for (char& c : text) {
    if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) > 0x7e) c = '?';
  }
  return text;
}

}  // namespace glint
