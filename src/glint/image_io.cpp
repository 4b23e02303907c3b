#include "glint/image_io.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <span>
#include <string>

#include <glm/common.hpp>
#include <stb_image.h>
#include <tinyexr.h>

#include "glint/decoder_checks.h"
#include "glint/error.h"
#include "glint/file_io.h"
#include "glint/kernel/tonemap.h"

namespace glint {

namespace {

constexpr std::array<std::uint8_t, 4> kPngMagic = {0x89, 0x50, 0x4E, 0x47};
constexpr std::array<std::uint8_t, 4> kExrMagic = {0x76, 0x2F, 0x31, 0x01};

std::string sizeText(int width, int height) { return std::to_string(width) + "x" + std::to_string(height); }

bool startsWith(std::span<const std::byte> bytes, const std::array<std::uint8_t, 4>& magic) {
  if (bytes.size() < magic.size()) return false;
  for (std::size_t i = 0; i < magic.size(); ++i) {
    if (std::to_integer<std::uint8_t>(bytes[i]) != magic[i]) return false;
  }
  return true;
}

// tinyexr's messages are heap strings that may hold newlines; errors here are one line.
std::string takeExrMessage(const char* message, const char* fallback) {
  std::string text = message ? message : fallback;
  FreeEXRErrorMessage(message);
  for (char& c : text) {
    if (c == '\n' || c == '\r' || c == '\t') c = ' ';
  }
  const auto end = text.find_last_not_of(' ');
  text.erase(end == std::string::npos ? 0 : end + 1);
  return text.empty() ? fallback : text;
}

struct StbiFree {
  void operator()(void* pixels) const { stbi_image_free(pixels); }
};
struct CFree {
  void operator()(void* memory) const { std::free(memory); }
};

ImageRgbF decodePng(const std::string& name, std::span<const std::byte> bytes, std::uint64_t maxPixels) {
  try {
    checkPngForDecoder(bytes, maxPixels);
  } catch (const Error& e) {
    throw Error(name + ": " + e.what());
  }
  const auto* data = reinterpret_cast<const stbi_uc*>(bytes.data());
  const int size = static_cast<int>(std::min<std::size_t>(bytes.size(), INT32_MAX));
  int width = 0;
  int height = 0;
  int channels = 0;
  // Always 16 bits per channel: stb widens 8-bit samples by v * 257, so v / 255 is kept exactly.
  // Three channels requested: grey is replicated and alpha dropped.
  std::unique_ptr<stbi_us, StbiFree> samples(stbi_load_16_from_memory(data, size, &width, &height, &channels, 3));
  if (!samples) {
    throw Error(name + ": truncated or corrupt PNG (" + decoderReason(stbi_failure_reason()) + ")");
  }
  if (width <= 0 || height <= 0) throw Error(name + ": zero-size image (" + sizeText(width, height) + ")");
  // One decode per code value: a table of the 65536 linear values keeps the decoder in one place
  // and the loop cheap.
  static const std::vector<float> table = [] {
    std::vector<float> values(65536);
    for (int v = 0; v < 65536; ++v) values[static_cast<std::size_t>(v)] = srgbToLinear(static_cast<float>(v / 65535.0));
    return values;
  }();
  ImageRgbF image = ImageRgbF::filled(width, height);
  const stbi_us* p = samples.get();
  for (glm::vec3& pixel : image.pixels) {
    pixel = glm::vec3(table[p[0]], table[p[1]], table[p[2]]);
    p += 3;
  }
  return image;
}

// tinyexr's LoadEXRFromMemory leaks its header and image on its error paths, and copies pixels
// with an int index that overflows for large images: glint parses the header itself, checks it,
// decodes the image with LoadEXRImageFromMemory, and copies the channels, freeing what tinyexr
// allocated on every path.
ImageRgbF decodeExr(const std::string& name, std::span<const std::byte> bytes, std::uint64_t maxPixels) {
  const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
  EXRVersion version;
  if (ParseEXRVersionFromMemory(&version, data, bytes.size()) != TINYEXR_SUCCESS) {
    throw Error(name + ": truncated or corrupt EXR (bad version field)");
  }
  if (version.multipart || version.non_image) {
    throw Error(name + ": unsupported EXR (multi-part or deep); expected a single RGB(A) or Y image");
  }
  try {
    checkExrForDecoder(bytes);
  } catch (const Error& e) {
    throw Error(name + ": " + e.what());
  }
  EXRHeader header;
  InitEXRHeader(&header);
  const char* message = nullptr;
  const int parsed = ParseEXRHeaderFromMemory(&header, &version, data, bytes.size(), &message);
  std::unique_ptr<EXRHeader, int (*)(EXRHeader*)> headerGuard(&header, FreeEXRHeader);
  if (parsed != TINYEXR_SUCCESS) {
    throw Error(name + ": truncated or corrupt EXR header (" + takeExrMessage(message, "unreadable") + ")");
  }
  // tinyexr computes max - min + 1 of the data window in int, which overflows for a crafted
  // window: its size is checked here in 64 bits first.
  const EXRBox2i& window = header.data_window;
  const std::int64_t width = std::int64_t{window.max_x} - window.min_x + 1;
  const std::int64_t height = std::int64_t{window.max_y} - window.min_y + 1;
  if (width < 1 || height < 1 || width > kMaxImageSide || height > kMaxImageSide) {
    throw Error(name + ": truncated or corrupt EXR (data window (" + std::to_string(window.min_x) + ", " +
                std::to_string(window.min_y) + ") to (" + std::to_string(window.max_x) + ", " +
                std::to_string(window.max_y) + "): expected 1 to " + std::to_string(kMaxImageSide) + " pixels a side)");
  }
  try {
    checkImagePixels(static_cast<std::uint64_t>(width), static_cast<std::uint64_t>(height), maxPixels);
  } catch (const Error& e) {
    throw Error(name + ": " + e.what());
  }
  // The channels read: R, G, B, or a single channel of any name as grey; alpha is ignored.
  int source[3] = {-1, -1, -1};
  for (int c = 0; c < header.num_channels; ++c) {
    // Unsigned-integer channels would be read as floats.
    if (header.pixel_types[c] == TINYEXR_PIXELTYPE_UINT) {
      throw Error(name + ": unsupported EXR channel '" + header.channels[c].name +
                  "' of unsigned-integer type; expected half or float");
    }
    header.requested_pixel_types[c] = TINYEXR_PIXELTYPE_FLOAT;
    const std::string channel = header.channels[c].name;
    if (channel == "R") source[0] = c;
    if (channel == "G") source[1] = c;
    if (channel == "B") source[2] = c;
  }
  if (header.num_channels == 1) source[0] = source[1] = source[2] = 0;
  for (int k = 0; k < 3; ++k) {
    if (source[k] < 0) {
      throw Error(name + ": unsupported EXR (" + "RGB"[k] + " channel not found; expected R, G and B, or a single channel)");
    }
  }
  EXRImage decoded;
  InitEXRImage(&decoded);
  // When decoding fails, tinyexr frees the image itself (without clearing its pointers, so glint
  // must not free it again), but only the planes of the channels the image says it has, which it
  // sets on success alone: set beforehand, its cleanup frees them too instead of leaking them.
  decoded.num_channels = header.num_channels;
  const int status = LoadEXRImageFromMemory(&decoded, &header, data, bytes.size(), &message);
  if (status != TINYEXR_SUCCESS) {
    const std::string reason = takeExrMessage(message, "unreadable");
    const bool unsupported = status == TINYEXR_ERROR_UNSUPPORTED_FORMAT || status == TINYEXR_ERROR_UNSUPPORTED_FEATURE;
    throw Error(name + (unsupported ? ": unsupported EXR (" : ": truncated or corrupt EXR (") + reason + ")");
  }
  std::unique_ptr<EXRImage, int (*)(EXRImage*)> imageGuard(&decoded, FreeEXRImage);
  FreeEXRErrorMessage(message);  // none is expected on success; free it if tinyexr left a warning
  if (decoded.width != width || decoded.height != height) {
    throw Error(name + ": truncated or corrupt EXR (decoded " + sizeText(decoded.width, decoded.height) +
                ", the data window says " + sizeText(static_cast<int>(width), static_cast<int>(height)) + ")");
  }
  ImageRgbF image = ImageRgbF::filled(decoded.width, decoded.height);
  // A block of pixels (the whole image, or one tile) at (x0, y0), `stride` pixels a row in its
  // planes, of which `blockWidth` x `blockHeight` are the image's; what lies outside the image
  // (a partial tile at its edge, or a crafted tile position) is skipped.
  auto copyBlock = [&](unsigned char* const* planes, std::int64_t x0, std::int64_t y0, std::int64_t stride,
                       std::int64_t blockWidth, std::int64_t blockHeight) {
    if (planes == nullptr) return;
    for (std::int64_t y = std::max<std::int64_t>(0, -y0); y < blockHeight && y0 + y < height; ++y) {
      for (std::int64_t x = std::max<std::int64_t>(0, -x0); x < blockWidth && x0 + x < width; ++x) {
        const auto at = static_cast<std::size_t>(y * stride + x);
        glm::vec3 value;
        for (int k = 0; k < 3; ++k) value[k] = reinterpret_cast<const float*>(planes[source[k]])[at];
        image.at(static_cast<int>(x0 + x), static_cast<int>(y0 + y)) = value;
      }
    }
  };
  if (header.tiled) {
    // Each tile's planes hold tile_size_x x tile_size_y pixels, of which its width x height are used.
    for (int t = 0; t < decoded.num_tiles; ++t) {
      const EXRTile& tile = decoded.tiles[t];
      copyBlock(tile.images, std::int64_t{tile.offset_x} * header.tile_size_x,
                std::int64_t{tile.offset_y} * header.tile_size_y, header.tile_size_x,
                std::min(tile.width, header.tile_size_x), std::min(tile.height, header.tile_size_y));
    }
  } else {
    copyBlock(decoded.images, 0, 0, width, width, height);
  }
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    const glm::vec3 value = image.pixels[i];
    if (!std::isfinite(value.x) || !std::isfinite(value.y) || !std::isfinite(value.z)) {
      const int x = static_cast<int>(i % static_cast<std::size_t>(width));
      const int y = static_cast<int>(i / static_cast<std::size_t>(width));
      throw Error(name + ": pixel (" + std::to_string(x) + ", " + std::to_string(y) + ") is not finite");
    }
  }
  return image;
}

void checkSameSize(const ImageRgbF& test, const ImageRgbF& reference) {
  if (test.width != reference.width || test.height != reference.height) {
    throw Error("image sizes differ: test " + sizeText(test.width, test.height) + ", reference " +
                sizeText(reference.width, reference.height));
  }
  if (test.pixels.empty()) throw Error("cannot compare empty images");
}

// Per pixel, the mean over channels of |a - b|.
std::vector<float> meanAbsoluteDifferences(const ImageRgbF& a, const ImageRgbF& b) {
  checkSameSize(a, b);
  std::vector<float> differences(a.pixels.size());
  for (std::size_t i = 0; i < differences.size(); ++i) {
    const glm::vec3 d = glm::abs(a.pixels[i] - b.pixels[i]);
    differences[i] = (d.x + d.y + d.z) / 3.0f;
  }
  return differences;
}

float percentileScale(std::vector<float> differences) {
  // Nearest-rank 99th percentile.
  const std::size_t rank = static_cast<std::size_t>(std::ceil(0.99 * static_cast<double>(differences.size())));
  const std::size_t index = std::min(differences.size() - 1, rank == 0 ? 0 : rank - 1);
  std::nth_element(differences.begin(), differences.begin() + static_cast<std::ptrdiff_t>(index), differences.end());
  const float percentile = differences[index];
  if (percentile > 0.0f && std::isfinite(percentile)) return percentile;
  // Under 1% of the pixels differ: scale to the largest finite difference so that they show.
  float largest = 0.0f;
  for (float d : differences) {
    if (std::isfinite(d)) largest = std::max(largest, d);
  }
  return largest > 0.0f ? largest : 1.0f;
}

// matplotlib's 'inferno' sampled at ten evenly spaced points (sRGB), interpolated linearly.
Rgb8 inferno(float t) {
  static constexpr std::array<Rgb8, 10> kStops = {{{0, 0, 4},
                                                   {27, 12, 66},
                                                   {75, 12, 107},
                                                   {120, 28, 109},
                                                   {165, 44, 96},
                                                   {207, 68, 70},
                                                   {237, 105, 37},
                                                   {251, 154, 6},
                                                   {247, 208, 60},
                                                   {252, 255, 164}}};
  const float position = std::clamp(t, 0.0f, 1.0f) * static_cast<float>(kStops.size() - 1);
  const int i = std::min(static_cast<int>(position), static_cast<int>(kStops.size()) - 2);
  const float f = position - static_cast<float>(i);
  const Rgb8 lo = kStops[static_cast<std::size_t>(i)];
  const Rgb8 hi = kStops[static_cast<std::size_t>(i) + 1];
  auto mix = [f](std::uint8_t a, std::uint8_t b) {
    return static_cast<std::uint8_t>(std::lround(static_cast<float>(a) + (static_cast<float>(b) - a) * f));
  };
  return {mix(lo.r, hi.r), mix(lo.g, hi.g), mix(lo.b, hi.b)};
}

template <typename Sample, typename Convert>
ImageRgbF fromRgba(int width, int height, const Sample* rgba, bool bottomUp, Convert convert) {
  assert(width >= 0 && height >= 0 && (rgba != nullptr || width == 0 || height == 0));
  ImageRgbF image = ImageRgbF::filled(width, height);
  for (int y = 0; y < height; ++y) {
    const int sourceRow = bottomUp ? height - 1 - y : y;
    const Sample* row = rgba + static_cast<std::size_t>(sourceRow) * width * 4;
    for (int x = 0; x < width; ++x) {
      image.at(x, y) = glm::vec3(convert(row[4 * x]), convert(row[4 * x + 1]), convert(row[4 * x + 2]));
    }
  }
  return image;
}

}  // namespace

ImageRgbF ImageRgbF::filled(int width, int height, glm::vec3 value) {
  assert(width >= 0 && height >= 0);
  return ImageRgbF{width, height, std::vector<glm::vec3>(static_cast<std::size_t>(width) * height, value)};
}

float srgbToLinear(float encoded) {
  const double c = encoded;
  return static_cast<float>(c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4));
}

float linearToSrgb(float linear) {
  if (!(linear > 0.0f)) return 0.0f;  // also NaN
  if (linear >= 1.0f) return 1.0f;
  return kernel::glintSrgbEncode(linear);  // the one sRGB encoding, shared with the shaders
}

std::uint8_t linearToSrgb8(float linear) {
  return static_cast<std::uint8_t>(std::lround(linearToSrgb(linear) * 255.0f));
}

ImageRgb8 displayEncode(const ImageRgbF& radiance, float exposure) {
  ImageRgb8 display(radiance.width, radiance.height, {0, 0, 0});
  for (int y = 0; y < radiance.height; ++y) {
    for (int x = 0; x < radiance.width; ++x) {
      const glm::vec3 code = kernel::glintDisplayCodeValues(radiance.at(x, y), exposure, glm::ivec2(x, y));
      display.at(x, y) = {static_cast<std::uint8_t>(code.r), static_cast<std::uint8_t>(code.g),
                          static_cast<std::uint8_t>(code.b)};
    }
  }
  return display;
}

std::string lowercaseExtension(const std::filesystem::path& path) {
  std::string extension = path.extension().string();
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return extension;
}

ImageRgbF decodeImage(std::span<const std::byte> bytes, const std::string& name, std::uint64_t maxPixels) {
  if (bytes.empty()) throw Error(name + ": empty file, expected a PNG or EXR image");
  if (startsWith(bytes, kPngMagic)) return decodePng(name, bytes, maxPixels);
  if (startsWith(bytes, kExrMagic)) return decodeExr(name, bytes, maxPixels);
  throw Error(name + ": not a PNG or EXR image (unrecognised content)");
}

ImageRgbF decodeExrImage(std::span<const std::byte> bytes, const std::string& name, std::uint64_t maxPixels) {
  if (!startsWith(bytes, kExrMagic)) throw Error(name + ": not an EXR image");
  return decodeExr(name, bytes, maxPixels);
}

ImageRgbF readImage(const std::filesystem::path& path) { return decodeImage(readFile(path), path.string()); }

std::vector<std::byte> encodeExr(const std::filesystem::path& path, const ImageRgbF& image) {
  if (image.width <= 0 || image.height <= 0) {
    throw Error(path.string() + ": cannot write a zero-size image (" + sizeText(image.width, image.height) + ")");
  }
  const std::size_t count = image.pixels.size();
  // EXR stores channels as planes in alphabetical order: B, G, R.
  std::vector<float> planes[3];
  for (auto& plane : planes) plane.resize(count);
  for (std::size_t i = 0; i < count; ++i) {
    const glm::vec3 p = image.pixels[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
      throw Error(path.string() + ": pixel (" + std::to_string(i % static_cast<std::size_t>(image.width)) + ", " +
                  std::to_string(i / static_cast<std::size_t>(image.width)) + ") is not finite");
    }
    planes[0][i] = p.z;
    planes[1][i] = p.y;
    planes[2][i] = p.x;
  }
  float* planePointers[3] = {planes[0].data(), planes[1].data(), planes[2].data()};

  EXRChannelInfo channels[3] = {};
  const char* names[3] = {"B", "G", "R"};
  int pixelTypes[3];
  int requestedTypes[3];
  for (int c = 0; c < 3; ++c) {
    std::strncpy(channels[c].name, names[c], sizeof channels[c].name - 1);
    channels[c].x_sampling = 1;
    channels[c].y_sampling = 1;
    pixelTypes[c] = TINYEXR_PIXELTYPE_FLOAT;
    requestedTypes[c] = TINYEXR_PIXELTYPE_FLOAT;
  }
  // The header points at these local arrays; it is not passed to FreeEXRHeader.
  EXRHeader header;
  InitEXRHeader(&header);
  header.num_channels = 3;
  header.channels = channels;
  header.pixel_types = pixelTypes;
  header.requested_pixel_types = requestedTypes;
  header.compression_type = TINYEXR_COMPRESSIONTYPE_ZIP;

  EXRImage exrImage;
  InitEXRImage(&exrImage);
  exrImage.num_channels = 3;
  exrImage.width = image.width;
  exrImage.height = image.height;
  exrImage.images = reinterpret_cast<unsigned char**>(planePointers);

  unsigned char* memory = nullptr;
  const char* message = nullptr;
  const std::size_t size = SaveEXRImageToMemory(&exrImage, &header, &memory, &message);
  std::unique_ptr<unsigned char, CFree> owned(memory);
  if (size == 0 || memory == nullptr) {
    throw Error(path.string() + ": EXR encoding failed (" + takeExrMessage(message, "unknown error") + ")");
  }
  FreeEXRErrorMessage(message);
  const auto* bytes = reinterpret_cast<const std::byte*>(memory);
  return std::vector<std::byte>(bytes, bytes + size);
}

void writeExr(const std::filesystem::path& path, const ImageRgbF& image) {
  writeFileAtomically(path, encodeExr(path, image));
}

void writePngSrgb(const std::filesystem::path& path, const ImageRgbF& image) {
  if (image.width <= 0 || image.height <= 0) {
    throw Error(path.string() + ": cannot write a zero-size image (" + sizeText(image.width, image.height) + ")");
  }
  ImageRgb8 encoded(image.width, image.height, Rgb8{0, 0, 0});
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const glm::vec3 p = image.at(x, y);
      encoded.at(x, y) = Rgb8{linearToSrgb8(p.x), linearToSrgb8(p.y), linearToSrgb8(p.z)};
    }
  }
  writePng(path, encoded);
}

void requireImageExtension(const std::filesystem::path& path) {
  const std::string extension = lowercaseExtension(path);
  if (extension != ".png" && extension != ".exr") {
    throw Error(path.string() + ": unsupported image extension '" + path.extension().string() +
                "' (supported: .png, .exr)");
  }
}

void writeImage(const std::filesystem::path& path, const ImageRgbF& image) {
  requireImageExtension(path);
  if (lowercaseExtension(path) == ".png") return writePngSrgb(path, image);
  return writeExr(path, image);
}

ImageRgbF fromRgba8Srgb(int width, int height, const std::uint8_t* rgba, bool bottomUp) {
  static const std::array<float, 256> table = [] {
    std::array<float, 256> values{};
    for (int v = 0; v < 256; ++v) values[static_cast<std::size_t>(v)] = srgbToLinear(static_cast<float>(v / 255.0));
    return values;
  }();
  return fromRgba(width, height, rgba, bottomUp, [](std::uint8_t v) { return table[v]; });
}

ImageRgbF fromRgbaFloat(int width, int height, const float* rgba, bool bottomUp) {
  return fromRgba(width, height, rgba, bottomUp, [](float v) { return v; });
}

ImageError compareImages(const ImageRgbF& test, const ImageRgbF& reference) {
  checkSameSize(test, reference);
  constexpr double kRelativeEpsilon = 1e-2;  // Rousselle et al. 2011
  double squared = 0.0;
  double relative = 0.0;
  double referenceSum = 0.0;
  for (std::size_t i = 0; i < test.pixels.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      const double t = test.pixels[i][c];
      const double r = reference.pixels[i][c];
      const double d2 = (t - r) * (t - r);
      squared += d2;
      relative += d2 / (r * r + kRelativeEpsilon);
      referenceSum += r;
    }
  }
  const double samples = 3.0 * static_cast<double>(test.pixels.size());
  return ImageError{std::sqrt(squared / samples), relative / samples, referenceSum / samples};
}

namespace {
// Rec. 709 luminance (scene::luminance, which this library sits below).
double rec709Luminance(glm::vec3 c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; }
}  // namespace

GlintRatioAgreement glintRatioAgreement(const ImageRgbF& glintA, const ImageRgbF& smoothA, const ImageRgbF& glintB,
                                        const ImageRgbF& smoothB, double minimumSmooth) {
  checkSameSize(glintA, smoothA);
  checkSameSize(glintA, glintB);
  checkSameSize(glintA, smoothB);
  if (!(minimumSmooth >= 0.0)) throw Error("the smallest smooth value compared must be a fraction >= 0");
  std::vector<double> smoothLuminance;
  smoothLuminance.reserve(smoothB.pixels.size());
  for (const glm::vec3& c : smoothB.pixels) smoothLuminance.push_back(rec709Luminance(c));
  std::sort(smoothLuminance.begin(), smoothLuminance.end());
  const double floor = std::max(minimumSmooth * smoothLuminance[smoothLuminance.size() * 99 / 100], 1e-6);
  std::vector<double> ratioA, ratioB;
  for (std::size_t i = 0; i < glintA.pixels.size(); ++i) {
    const double sa = rec709Luminance(smoothA.pixels[i]);
    const double sb = rec709Luminance(smoothB.pixels[i]);
    if (!(sa >= floor && sb >= floor)) continue;
    const double a = std::max(rec709Luminance(glintA.pixels[i]), 0.0) / sa;
    const double b = std::max(rec709Luminance(glintB.pixels[i]), 0.0) / sb;
    if (std::abs(a - 1.0) < 1e-6 && std::abs(b - 1.0) < 1e-6) continue;
    ratioA.push_back(a);
    ratioB.push_back(b);
  }
  if (ratioA.size() < 2) throw Error("no pixel has both a glint and a smooth image to compare");
  GlintRatioAgreement agreement;
  agreement.pixels = static_cast<int>(ratioA.size());
  const double n = static_cast<double>(ratioA.size());
  // Logs of ratios floored at 1e-3: a pixel whose glints reflect nothing is a large negative, not -inf.
  double meanLogA = 0.0, meanLogB = 0.0, meanA = 0.0, meanB = 0.0;
  for (std::size_t i = 0; i < ratioA.size(); ++i) {
    meanLogA += std::log(std::max(ratioA[i], 1e-3)) / n;
    meanLogB += std::log(std::max(ratioB[i], 1e-3)) / n;
    meanA += ratioA[i] / n;
    meanB += ratioB[i] / n;
    agreement.aboveTwiceA += ratioA[i] > 2.0 ? 1.0 / n : 0.0;
    agreement.aboveTwiceB += ratioB[i] > 2.0 ? 1.0 / n : 0.0;
  }
  double covariance = 0.0, varianceLogA = 0.0, varianceLogB = 0.0, varianceA = 0.0, varianceB = 0.0;
  for (std::size_t i = 0; i < ratioA.size(); ++i) {
    const double la = std::log(std::max(ratioA[i], 1e-3)) - meanLogA;
    const double lb = std::log(std::max(ratioB[i], 1e-3)) - meanLogB;
    covariance += la * lb;
    varianceLogA += la * la;
    varianceLogB += lb * lb;
    varianceA += (ratioA[i] - meanA) * (ratioA[i] - meanA) / n;
    varianceB += (ratioB[i] - meanB) * (ratioB[i] - meanB) / n;
  }
  agreement.logCorrelation = varianceLogA > 0.0 && varianceLogB > 0.0 ? covariance / std::sqrt(varianceLogA * varianceLogB) : 0.0;
  agreement.variationA = meanA > 0.0 ? std::sqrt(varianceA) / meanA : 0.0;
  agreement.variationB = meanB > 0.0 ? std::sqrt(varianceB) / meanB : 0.0;
  return agreement;
}

float automaticDifferenceScale(const ImageRgbF& a, const ImageRgbF& b) {
  return percentileScale(meanAbsoluteDifferences(a, b));
}

Rgb8 infernoColour(float t) { return inferno(t); }

ImageRgb8 falseColourDifference(const ImageRgbF& a, const ImageRgbF& b, float scale) {
  if (!(scale >= 0.0f) || !std::isfinite(scale)) {
    char text[64];
    std::snprintf(text, sizeof text, "%g", static_cast<double>(scale));
    throw Error(std::string("difference scale must be a finite number >= 0, got ") + text);
  }
  const std::vector<float> differences = meanAbsoluteDifferences(a, b);
  if (scale == 0.0f) scale = percentileScale(differences);

  constexpr int kLegendHeight = 24;
  constexpr int kMargin = 4;
  constexpr Rgb8 kBackground{32, 32, 32};
  constexpr Rgb8 kText{230, 230, 230};
  const int width = std::max(a.width, kMinDiffWidth);
  ImageRgb8 picture(width, a.height + kLegendHeight, kBackground);
  for (int y = 0; y < a.height; ++y) {
    for (int x = 0; x < a.width; ++x) {
      const float d = differences[static_cast<std::size_t>(y) * a.width + x];
      // A non-finite difference (a NaN in a rendered image) shows at the top of the scale.
      picture.at(x, y) = inferno(std::isfinite(d) ? d / scale : 1.0f);
    }
  }

  // Legend: "0", a colour bar, the value at its top end.
  char maxLabel[32];
  std::snprintf(maxLabel, sizeof maxLabel, "%.3g", static_cast<double>(scale));
  const char* minLabel = "0";
  const int textScale = width >= 512 ? 2 : 1;
  const int textY = a.height + (kLegendHeight - 7 * textScale) / 2;
  picture.drawText(kMargin, textY, minLabel, kText, textScale);
  const int maxWidth = ImageRgb8::textWidth(maxLabel, textScale);
  picture.drawText(width - kMargin - maxWidth, textY, maxLabel, kText, textScale);
  const int barX0 = kMargin + ImageRgb8::textWidth(minLabel, textScale) + 2 * kMargin;
  const int barX1 = width - kMargin - maxWidth - 2 * kMargin;
  const int barY0 = a.height + kLegendHeight / 2 - 5;
  for (int x = barX0; x < barX1; ++x) {
    const float t = barX1 - barX0 > 1 ? static_cast<float>(x - barX0) / static_cast<float>(barX1 - barX0 - 1) : 0.0f;
    picture.fillRect(x, barY0, x + 1, barY0 + 10, inferno(t));
  }
  return picture;
}

}  // namespace glint
