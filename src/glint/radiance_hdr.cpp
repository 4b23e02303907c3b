#include "glint/radiance_hdr.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "glint/decoder_checks.h"
#include "glint/error.h"
#include "glint/file_io.h"

namespace glint {

namespace {

constexpr int kMinRunLengthWidth = 8;       // the "new" run-length encoding's range of widths
constexpr int kMaxRunLengthWidth = 0x7fff;

std::uint8_t byteAt(std::span<const std::byte> bytes, std::size_t i) { return std::to_integer<std::uint8_t>(bytes[i]); }

glm::vec3 fromRgbe(const std::uint8_t* rgbe) {
  if (rgbe[3] == 0) return glm::vec3(0.0f);
  const float scale = std::ldexp(1.0f, static_cast<int>(rgbe[3]) - 136);
  return glm::vec3(rgbe[0], rgbe[1], rgbe[2]) * scale;
}

// Reads the header and resolution lines; `position` ends at the first scanline byte.
struct Reader {
  std::span<const std::byte> bytes;
  const std::string& name;
  std::size_t position = 0;

  [[noreturn]] void fail(const std::string& problem) const {
    throw Error(name + ": truncated or corrupt Radiance HDR (" + problem + ")");
  }

  std::string line() {
    std::string text;
    while (true) {
      if (position >= bytes.size()) fail("the header ends before the resolution line");
      const char c = static_cast<char>(byteAt(bytes, position++));
      if (c == '\n') {
        if (!text.empty() && text.back() == '\r') text.pop_back();  // a header written with CRLF lines
        return text;
      }
      if (text.size() > 4096) fail("a header line longer than 4096 characters");
      text += c;
    }
  }
};

}  // namespace

bool looksLikeRadianceHdr(std::span<const std::byte> bytes) {
  return bytes.size() >= 2 && byteAt(bytes, 0) == '#' && byteAt(bytes, 1) == '?';
}

ImageRgbF decodeRadianceHdr(std::span<const std::byte> bytes, const std::string& name, std::uint64_t maxPixels) {
  if (!looksLikeRadianceHdr(bytes)) throw Error(name + ": not a Radiance HDR image (it does not start with '#?')");
  Reader reader{bytes, name};
  reader.line();  // "#?RADIANCE", "#?RGBE", ...
  while (true) {
    const std::string header = reader.line();
    if (header.empty()) break;
    if (header.rfind("FORMAT=", 0) == 0 && header != "FORMAT=32-bit_rle_rgbe") {
      throw Error(name + ": unsupported Radiance HDR format '" + header.substr(7) + "' (glint reads 32-bit_rle_rgbe)");
    }
  }
  const std::string resolution = reader.line();
  long long height = 0;
  long long width = 0;
  char tail = 0;
  if (std::sscanf(resolution.c_str(), "-Y %lld +X %lld%c", &height, &width, &tail) != 2) {
    throw Error(name + ": unsupported Radiance HDR orientation or resolution line '" + resolution.substr(0, 64) +
                "' (glint reads '-Y height +X width')");
  }
  if (width <= 0 || height <= 0 || width > kMaxImageSide || height > kMaxImageSide) {
    throw Error(name + ": Radiance HDR size " + std::to_string(width) + "x" + std::to_string(height) +
                " is out of range (1 to " + std::to_string(kMaxImageSide) + " a side)");
  }
  try {
    checkImagePixels(static_cast<std::uint64_t>(width), static_cast<std::uint64_t>(height), maxPixels);
  } catch (const Error& e) {
    throw Error(name + ": " + e.what());
  }
  // Each scanline takes at least 4 bytes a pixel flat, or the 4-byte marker and one run of at most
  // 127 pixels per 2 bytes per channel encoded: a size the remaining bytes cannot hold is refused
  // before anything is allocated.
  const auto w = static_cast<std::size_t>(width);
  const auto h = static_cast<std::size_t>(height);
  const bool encodable = width >= kMinRunLengthWidth && width <= kMaxRunLengthWidth;
  const std::size_t smallestScanline = encodable ? 4 + 8 * ((w + 126) / 127) : 4 * w;
  const std::size_t remaining = bytes.size() - reader.position;
  if (remaining / smallestScanline < h) reader.fail("fewer bytes than " + std::to_string(h) + " scanlines need");

  ImageRgbF image = ImageRgbF::filled(static_cast<int>(width), static_cast<int>(height));
  std::vector<std::uint8_t> channels(4 * w);
  std::size_t& p = reader.position;
  for (std::size_t y = 0; y < h; ++y) {
    const std::string row = "scanline " + std::to_string(y);
    if (p + 4 > bytes.size()) reader.fail(row + " is missing");
    const bool encoded = encodable && byteAt(bytes, p) == 2 && byteAt(bytes, p + 1) == 2 && byteAt(bytes, p + 2) < 128;
    if (!encoded) {
      if (p + 4 * w > bytes.size()) reader.fail(row + " is cut short");
      for (std::size_t x = 0; x < w; ++x) {
        std::uint8_t rgbe[4];
        for (int c = 0; c < 4; ++c) rgbe[c] = byteAt(bytes, p + 4 * x + static_cast<std::size_t>(c));
        image.at(static_cast<int>(x), static_cast<int>(y)) = fromRgbe(rgbe);
      }
      p += 4 * w;
      continue;
    }
    const std::size_t declared = (static_cast<std::size_t>(byteAt(bytes, p + 2)) << 8) | byteAt(bytes, p + 3);
    if (declared != w) reader.fail(row + " declares width " + std::to_string(declared) + ", not " + std::to_string(w));
    p += 4;
    // Four planes (R, G, B, E), each a sequence of runs: a count above 128 repeats the next byte
    // count - 128 times, a count of 1 to 128 copies that many bytes.
    for (std::size_t c = 0; c < 4; ++c) {
      std::size_t x = 0;
      while (x < w) {
        if (p >= bytes.size()) reader.fail(row + " is cut short");
        std::size_t count = byteAt(bytes, p++);
        const bool run = count > 128;
        if (run) count -= 128;
        if (count == 0 || x + count > w) reader.fail(row + " has a run past its end");
        if (p + (run ? 1 : count) > bytes.size()) reader.fail(row + " is cut short");
        for (std::size_t k = 0; k < count; ++k) channels[4 * (x + k) + c] = byteAt(bytes, run ? p : p + k);
        p += run ? 1 : count;
        x += count;
      }
    }
    for (std::size_t x = 0; x < w; ++x) image.at(static_cast<int>(x), static_cast<int>(y)) = fromRgbe(&channels[4 * x]);
  }
  return image;
}

std::vector<std::byte> encodeRadianceHdr(const std::filesystem::path& path, const ImageRgbF& image) {
  if (image.width <= 0 || image.height <= 0) {
    throw Error(path.string() + ": cannot write a zero-size image (" + std::to_string(image.width) + "x" +
                std::to_string(image.height) + ")");
  }
  const std::string header = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y " + std::to_string(image.height) + " +X " +
                             std::to_string(image.width) + "\n";
  std::vector<std::byte> bytes(header.size());
  std::memcpy(bytes.data(), header.data(), header.size());
  bytes.reserve(header.size() + 4 * image.pixels.size());
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    const glm::vec3 v = image.pixels[i];
    if (!(v.x >= 0.0f && v.y >= 0.0f && v.z >= 0.0f) || !std::isfinite(v.x + v.y + v.z)) {
      throw Error(path.string() + ": pixel " + std::to_string(i) + " is negative or not finite; RGBE cannot hold it");
    }
    // The shared exponent of the largest channel: v = m 2^e with m in [0.5, 1), stored as m 256.
    const float largest = std::max({v.x, v.y, v.z});
    std::uint8_t rgbe[4] = {0, 0, 0, 0};
    if (largest >= 1e-32f) {
      int exponent = 0;
      const float mantissa = std::frexp(largest, &exponent);
      const float scale = mantissa * 256.0f / largest;
      for (int c = 0; c < 3; ++c) rgbe[c] = static_cast<std::uint8_t>(std::min(255.0f, v[c] * scale));
      rgbe[3] = static_cast<std::uint8_t>(exponent + 128);
    }
    for (std::uint8_t b : rgbe) bytes.push_back(static_cast<std::byte>(b));
  }
  return bytes;
}

void writeRadianceHdr(const std::filesystem::path& path, const ImageRgbF& image) {
  writeFileAtomically(path, encodeRadianceHdr(path, image));
}

ImageRgbF readRadianceImage(const std::filesystem::path& path) {
  const std::vector<std::byte> bytes = readFile(path);
  const std::string name = path.string();
  ImageRgbF image;
  if (looksLikeRadianceHdr(bytes)) {
    image = decodeRadianceHdr(bytes, name);
  } else {
    try {
      image = decodeExrImage(bytes, name);
    } catch (const Error& e) {
      if (std::string(e.what()) == name + ": not an EXR image") {
        throw Error(name + ": not a Radiance HDR (.hdr) or EXR image (unrecognised content)");
      }
      throw;
    }
  }
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    const glm::vec3 v = image.pixels[i];
    if (!(v.x >= 0.0f && v.y >= 0.0f && v.z >= 0.0f)) {
      throw Error(name + ": pixel (" + std::to_string(i % static_cast<std::size_t>(image.width)) + ", " +
                  std::to_string(i / static_cast<std::size_t>(image.width)) + ") is negative; radiance cannot be");
    }
  }
  return image;
}

}  // namespace glint
