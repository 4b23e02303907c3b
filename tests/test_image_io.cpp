// Float images: PNG and EXR reading and writing, sRGB decoding, GL readback conversion, error
// metrics and the false-colour difference picture; `glint diff` as a user meets it.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <tinyexr.h>

#include "glint/error.h"
#include "glint/file_io.h"
#include "glint/image_io.h"
#include "glint/kernel/tonemap.h"
#include "glint/pcg.h"
#include "test_support.h"

namespace glint {
namespace {

using namespace glint::test;

// linear(128 / 255) = ((128 / 255 + 0.055) / 1.055)^2.4, computed independently (bc -l).
constexpr float kLinear128 = 0.2158605f;

// --- Fixtures written without the code under test ---------------------------------------------

void writeBytes(const std::filesystem::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

std::string bigEndian32(std::uint32_t value) {
  return {static_cast<char>(value >> 24), static_cast<char>(value >> 16), static_cast<char>(value >> 8),
          static_cast<char>(value)};
}

std::string pngChunk(const std::string& type, const std::string& payload) {
  return bigEndian32(static_cast<std::uint32_t>(payload.size())) + type + payload + bigEndian32(crc32Ieee(type + payload));
}

// A minimal PNG encoder (stored deflate blocks, filter 0) so that the reader is tested against an
// independent writer, for every bit depth and colour type. `samples` are row-major, channel-
// interleaved, `channels` per pixel: 1 grey (type 0), 2 grey-alpha (4), 3 RGB (2), 4 RGBA (6).
std::string encodePng(int width, int height, int channels, int bitDepth, const std::vector<std::uint16_t>& samples) {
  const std::array<int, 5> colourType = {0, 0, 4, 2, 6};
  std::string raw;
  for (int y = 0; y < height; ++y) {
    raw += '\0';  // filter: none
    for (int i = 0; i < width * channels; ++i) {
      const std::uint16_t v = samples[static_cast<std::size_t>(y) * width * channels + i];
      if (bitDepth == 16) raw += static_cast<char>(v >> 8);
      raw += static_cast<char>(v & 0xFF);
    }
  }
  std::string zlib = "\x78\x01";
  std::uint32_t a = 1, b = 0;  // Adler-32
  for (unsigned char c : raw) {
    a = (a + c) % 65521;
    b = (b + a) % 65521;
  }
  for (std::size_t offset = 0; offset == 0 || offset < raw.size(); offset += 65535) {
    const std::size_t length = std::min<std::size_t>(65535, raw.size() - offset);
    const bool last = offset + length >= raw.size();
    zlib += static_cast<char>(last ? 1 : 0);
    zlib += static_cast<char>(length & 0xFF);
    zlib += static_cast<char>(length >> 8);
    zlib += static_cast<char>(~length & 0xFF);
    zlib += static_cast<char>((~length >> 8) & 0xFF);
    zlib += raw.substr(offset, length);
  }
  zlib += bigEndian32(b << 16 | a);
  const std::string header = bigEndian32(static_cast<std::uint32_t>(width)) +
                             bigEndian32(static_cast<std::uint32_t>(height)) + static_cast<char>(bitDepth) +
                             static_cast<char>(colourType[static_cast<std::size_t>(channels)]) + std::string(3, '\0');
  return std::string("\x89PNG\r\n\x1a\n", 8) + pngChunk("IHDR", header) + pngChunk("IDAT", zlib) +
         pngChunk("IEND", "");
}

// An EXR with the given channel names and planes (float input, stored as `pixelType`), via
// tinyexr directly.
void writeExrChannels(const std::filesystem::path& path, int width, int height, const std::vector<std::string>& names,
                      std::vector<std::vector<float>> planes, int pixelType) {
  const int count = static_cast<int>(names.size());
  std::vector<EXRChannelInfo> channels(names.size());
  std::vector<int> inputTypes(names.size(), TINYEXR_PIXELTYPE_FLOAT);
  std::vector<int> storedTypes(names.size(), pixelType);
  std::vector<float*> pointers;
  for (int c = 0; c < count; ++c) {
    std::memset(&channels[c], 0, sizeof channels[c]);
    std::strncpy(channels[c].name, names[c].c_str(), 255);
    pointers.push_back(planes[c].data());
  }
  EXRHeader header;
  InitEXRHeader(&header);
  header.num_channels = count;
  header.channels = channels.data();
  header.pixel_types = inputTypes.data();
  header.requested_pixel_types = storedTypes.data();
  header.compression_type = TINYEXR_COMPRESSIONTYPE_NONE;
  EXRImage image;
  InitEXRImage(&image);
  image.num_channels = count;
  image.width = width;
  image.height = height;
  image.images = reinterpret_cast<unsigned char**>(pointers.data());
  const char* message = nullptr;
  ASSERT_EQ(SaveEXRImageToFile(&image, &header, path.string().c_str(), &message), TINYEXR_SUCCESS)
      << (message ? message : "");
}

ImageRgbF image2x1(glm::vec3 left, glm::vec3 right) { return ImageRgbF{2, 1, {left, right}}; }

void expectBitIdentical(const ImageRgbF& a, const ImageRgbF& b) {
  ASSERT_EQ(a.width, b.width);
  ASSERT_EQ(a.height, b.height);
  ASSERT_EQ(a.pixels.size(), b.pixels.size());
  EXPECT_EQ(std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(glm::vec3)), 0);
}

// An Error whose one-line message contains every one of `parts`.
template <typename Function>
void expectError(Function function, const std::vector<std::string>& parts) {
  try {
    function();
    ADD_FAILURE() << "no Error thrown; expected '" << parts.front() << "'";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    for (const std::string& part : parts) EXPECT_NE(message.find(part), std::string::npos) << message;
  }
}

// --- sRGB --------------------------------------------------------------------------------------

TEST(ImageIoSrgb, DecodesKnownCodes) {
  EXPECT_EQ(srgbToLinear(0.0f), 0.0f);
  EXPECT_EQ(srgbToLinear(1.0f), 1.0f);
  EXPECT_NEAR(srgbToLinear(128.0f / 255.0f), kLinear128, 1e-7f);
  EXPECT_NEAR(srgbToLinear(10.0f / 255.0f), 10.0f / 255.0f / 12.92f, 1e-9f);  // the linear segment
  const std::uint8_t rgba[4] = {0, 128, 255, 17};
  const ImageRgbF decoded = fromRgba8Srgb(1, 1, rgba, false);
  EXPECT_EQ(decoded.at(0, 0).x, 0.0f);
  EXPECT_NEAR(decoded.at(0, 0).y, kLinear128, 1e-7f);
  EXPECT_EQ(decoded.at(0, 0).z, 1.0f);
}

TEST(ImageIoSrgb, EveryEightBitCodeSurvivesDecodeAndEncode) {
  for (int code = 0; code < 256; ++code) {
    EXPECT_EQ(linearToSrgb8(srgbToLinear(static_cast<float>(code) / 255.0f)), code);
  }
  EXPECT_EQ(linearToSrgb8(-1.0f), 0);
  EXPECT_EQ(linearToSrgb8(7.0f), 255);
  EXPECT_EQ(linearToSrgb8(std::numeric_limits<float>::quiet_NaN()), 0);
}

TEST(ImageIoSrgb, ReadbackRowsAreFlippedWhenBottomUp) {
  const std::uint8_t rgba8[8] = {255, 255, 255, 255, 0, 0, 0, 255};  // bottom row white, top black
  const ImageRgbF flipped = fromRgba8Srgb(1, 2, rgba8, true);
  EXPECT_EQ(flipped.at(0, 0), glm::vec3(0.0f));
  EXPECT_EQ(flipped.at(0, 1), glm::vec3(1.0f));
  EXPECT_EQ(fromRgba8Srgb(1, 2, rgba8, false).at(0, 0), glm::vec3(1.0f));
  const float rgbaF[16] = {1, 2, 3, 0, 4, 5, 6, 0, 7, 8, 9, 0, 10, 11, 12, 0};  // 2x2, floats kept as they are
  const ImageRgbF floats = fromRgbaFloat(2, 2, rgbaF, true);
  EXPECT_EQ(floats.at(0, 0), glm::vec3(7, 8, 9));
  EXPECT_EQ(floats.at(1, 0), glm::vec3(10, 11, 12));
  EXPECT_EQ(floats.at(0, 1), glm::vec3(1, 2, 3));
  EXPECT_EQ(fromRgbaFloat(2, 2, rgbaF, false).at(1, 1), glm::vec3(10, 11, 12));
}

// --- PNG ---------------------------------------------------------------------------------------

TEST(ImageIoPng, ReadsEveryBitDepthAndColourTypeAsLinear) {
  const auto folder = temporaryFolder("image_png_types");
  // Three pixels of codes 0, 128 and 255 (8 bit), or 0, 128 * 257 and 65535 (16 bit: the same
  // fractions), laid out per channel so that each channel sees each value; alpha is arbitrary.
  for (int bitDepth : {8, 16}) {
    const std::uint16_t lo = 0;
    const std::uint16_t mid = bitDepth == 8 ? 128 : 128 * 257;
    const std::uint16_t hi = bitDepth == 8 ? 255 : 65535;
    const std::uint16_t alpha = bitDepth == 8 ? 7 : 7000;
    struct Case {
      int channels;
      std::vector<std::uint16_t> samples;
      std::array<glm::vec3, 3> expected;
    };
    const float m = kLinear128;
    const std::vector<Case> cases = {
        {1, {lo, mid, hi}, {glm::vec3(0), glm::vec3(m), glm::vec3(1)}},
        {2, {lo, alpha, mid, alpha, hi, alpha}, {glm::vec3(0), glm::vec3(m), glm::vec3(1)}},
        {3, {lo, mid, hi, mid, hi, lo, hi, lo, mid}, {glm::vec3(0, m, 1), glm::vec3(m, 1, 0), glm::vec3(1, 0, m)}},
        {4,
         {lo, mid, hi, alpha, mid, hi, lo, alpha, hi, lo, mid, alpha},
         {glm::vec3(0, m, 1), glm::vec3(m, 1, 0), glm::vec3(1, 0, m)}},
    };
    for (const Case& c : cases) {
      SCOPED_TRACE("bit depth " + std::to_string(bitDepth) + ", channels " + std::to_string(c.channels));
      const auto path = folder / ("image_" + std::to_string(bitDepth) + "_" + std::to_string(c.channels) + ".png");
      writeBytes(path, encodePng(3, 1, c.channels, bitDepth, c.samples));
      const ImageRgbF image = readImage(path);
      ASSERT_EQ(image.width, 3);
      ASSERT_EQ(image.height, 1);
      for (int x = 0; x < 3; ++x) {
        for (int k = 0; k < 3; ++k) EXPECT_NEAR(image.at(x, 0)[k], c.expected[x][k], 1e-7f) << "pixel " << x;
      }
    }
  }
  // A 16-bit code off the 8-bit grid, on the linear segment: 1000 / 65535 / 12.92.
  writeBytes(folder / "fine.png", encodePng(1, 1, 1, 16, {1000}));
  EXPECT_NEAR(readImage(folder / "fine.png").at(0, 0).x, 0.00118103885f, 1e-9f);
  // 2640 / 65535 = 0.040284, just below the 0.04045 breakpoint: still the linear segment (the
  // power segment would give 2e-7 less).
  writeBytes(folder / "breakpoint.png", encodePng(1, 1, 1, 16, {2640}));
  EXPECT_NEAR(readImage(folder / "breakpoint.png").at(0, 0).x, 0.00311794255f, 1e-9f);
}

TEST(ImageIoPng, RowsAreTopFirst) {
  const auto folder = temporaryFolder("image_png_rows");
  writeBytes(folder / "rows.png", encodePng(1, 2, 1, 8, {255, 0}));
  const ImageRgbF image = readImage(folder / "rows.png");
  EXPECT_EQ(image.at(0, 0), glm::vec3(1.0f));
  EXPECT_EQ(image.at(0, 1), glm::vec3(0.0f));
}

TEST(ImageIoPng, RoundTripIsWithinEightBitQuantisation) {
  // Writing rounds the sRGB-encoded value to the nearest of 255 steps: at most half a step, 0.5/255,
  // in encoded units. The EOTF's steepest slope on [0, 1] is at 1: 2.4 / 1.055 = 2.2749, so the
  // linear error is at most 2.2749 * 0.5 / 255 = 0.0044606 (plus float rounding).
  constexpr float kTolerance = 2.4f / 1.055f * 0.5f / 255.0f + 1e-6f;
  const auto folder = temporaryFolder("image_png_round_trip");
  Pcg32 rng(11, 3);
  ImageRgbF image = ImageRgbF::filled(31, 17);
  for (glm::vec3& p : image.pixels) p = glm::vec3(uniform(rng, 0, 1), uniform(rng, 0, 1), uniform(rng, 0, 1));
  image.at(0, 0) = glm::vec3(-0.5f, 1.5f, 0.0f);  // out of range: clamped
  writePngSrgb(folder / "image.png", image);
  const ImageRgbF back = readImage(folder / "image.png");
  ASSERT_EQ(back.width, 31);
  ASSERT_EQ(back.height, 17);
  EXPECT_EQ(back.at(0, 0), glm::vec3(0.0f, 1.0f, 0.0f));
  float worst = 0.0f;
  for (std::size_t i = 1; i < image.pixels.size(); ++i) {
    for (int k = 0; k < 3; ++k) worst = std::max(worst, std::abs(back.pixels[i][k] - image.pixels[i][k]));
  }
  EXPECT_LE(worst, kTolerance);
  EXPECT_GT(worst, 0.0f);  // it really was quantised
}

// --- EXR ---------------------------------------------------------------------------------------

TEST(ImageIoExr, RoundTripIsBitExact) {
  const auto folder = temporaryFolder("image_exr_round_trip");
  Pcg32 rng(5, 9);
  for (auto [width, height] : {std::pair{2, 1}, std::pair{37, 23}, std::pair{1, 40}}) {
    ImageRgbF image = ImageRgbF::filled(width, height);
    for (glm::vec3& p : image.pixels) {
      p = glm::vec3(uniform(rng, -2, 2), std::exp(uniform(rng, -80, 80)), uniform(rng, 0, 1) * 1e-3f);
    }
    image.pixels.front() = glm::vec3(0.0f, -0.0f, std::numeric_limits<float>::denorm_min());
    image.pixels.back() = glm::vec3(std::numeric_limits<float>::max(), 1.0f / 3.0f, -1e-30f);
    writeExr(folder / "image.exr", image);
    expectBitIdentical(readImage(folder / "image.exr"), image);
  }
}

TEST(ImageIoExr, ReadsHalfRgbaAndSingleChannelY) {
  const auto folder = temporaryFolder("image_exr_kinds");
  // Half-float RGBA, channels in the usual A, B, G, R order; values exact in binary16.
  writeExrChannels(folder / "half.exr", 2, 1, {"A", "B", "G", "R"}, {{1, 1}, {0.25f, -4}, {0.5f, 0}, {2, 1024}},
                   TINYEXR_PIXELTYPE_HALF);
  const ImageRgbF half = readImage(folder / "half.exr");
  ASSERT_EQ(half.width, 2);
  EXPECT_EQ(half.at(0, 0), glm::vec3(2, 0.5f, 0.25f));
  EXPECT_EQ(half.at(1, 0), glm::vec3(1024, 0, -4));
  writeExrChannels(folder / "y.exr", 1, 2, {"Y"}, {{0.125f, 3}}, TINYEXR_PIXELTYPE_FLOAT);
  const ImageRgbF grey = readImage(folder / "y.exr");
  ASSERT_EQ(grey.height, 2);
  EXPECT_EQ(grey.at(0, 0), glm::vec3(0.125f));
  EXPECT_EQ(grey.at(0, 1), glm::vec3(3));
}

TEST(ImageIoExr, NonFinitePixelsAreRefusedOnReadAndWrite) {
  const auto folder = temporaryFolder("image_exr_nan");
  const float nan = std::numeric_limits<float>::quiet_NaN();
  writeExrChannels(folder / "nan.exr", 2, 1, {"B", "G", "R"}, {{0, 0}, {0, nan}, {0, 0}}, TINYEXR_PIXELTYPE_FLOAT);
  expectError([&] { readImage(folder / "nan.exr"); }, {"nan.exr", "pixel (1, 0) is not finite"});
  const ImageRgbF infinite = image2x1(glm::vec3(0), glm::vec3(std::numeric_limits<float>::infinity()));
  expectError([&] { writeExr(folder / "inf.exr", infinite); }, {"inf.exr", "pixel (1, 0) is not finite"});
  EXPECT_FALSE(std::filesystem::exists(folder / "inf.exr"));
}

// --- Display encoding: what `glint render` writes as PNG ----------------------------------------

// A smooth gradient, like a sky, about four codes across 512 columns: rounding alone turns it into
// flat bands, each 8 x 8 tile off the exact values' mean by up to half a code; dithered, every
// tile's mean code follows the exact mean to within 0.1 of a code. Black and white stay flat.
TEST(ImageIoDisplay, SmoothGradientsAreDitheredNotBanded) {
  constexpr int kWidth = 512;
  constexpr int kTile = 8;
  ImageRgbF radiance = ImageRgbF::filled(kWidth, kTile);
  std::vector<double> exactCodes(kWidth);
  for (int x = 0; x < kWidth; ++x) {
    const float value = 0.05f + 0.005f * static_cast<float>(x) / static_cast<float>(kWidth - 1);
    for (int y = 0; y < kTile; ++y) radiance.at(x, y) = glm::vec3(value);
    exactCodes[static_cast<std::size_t>(x)] = 255.0 * kernel::glintDisplayEncode(glm::vec3(value), 1.0f).x;
  }
  ASSERT_GT(exactCodes.back() - exactCodes.front(), 3.0);  // the gradient crosses several codes
  const ImageRgb8 encoded = displayEncode(radiance, 1.0f);
  double worstDithered = 0.0;
  double worstRounded = 0.0;
  for (int tile = 0; tile < kWidth / kTile; ++tile) {
    double exact = 0.0;
    double dithered = 0.0;
    double rounded = 0.0;
    for (int x = tile * kTile; x < (tile + 1) * kTile; ++x) {
      const double code = exactCodes[static_cast<std::size_t>(x)];
      for (int y = 0; y < kTile; ++y) {
        exact += code;
        dithered += encoded.at(x, y).r;
        rounded += std::round(code);
        EXPECT_EQ(encoded.at(x, y).g, encoded.at(x, y).r);  // grey stays grey
      }
    }
    const double pixels = kTile * kTile;
    worstDithered = std::max(worstDithered, std::abs(dithered - exact) / pixels);
    worstRounded = std::max(worstRounded, std::abs(rounded - exact) / pixels);
  }
  EXPECT_LE(worstDithered, 0.1);
  EXPECT_GT(worstRounded, 0.3);  // the gradient is one that bands when rounded
  const ImageRgb8 black = displayEncode(ImageRgbF::filled(16, 16), 1.0f);
  const ImageRgb8 white = displayEncode(ImageRgbF::filled(16, 16, glm::vec3(1e6f)), 1.0f);
  for (int y = 0; y < 16; ++y) {
    for (int x = 0; x < 16; ++x) {
      EXPECT_EQ(black.at(x, y).r, 0);
      EXPECT_EQ(white.at(x, y).r, 255);
    }
  }
}

// --- Reading: content decides, and every failure is one line naming the file --------------------

TEST(ImageIoRead, FormatIsDecidedByContentNotName) {
  const auto folder = temporaryFolder("image_magic");
  const ImageRgbF image = image2x1(glm::vec3(0.5f, 2, 3), glm::vec3(-1, 0, 1));
  writeExr(folder / "looks_like.png", image);
  expectBitIdentical(readImage(folder / "looks_like.png"), image);
  writeBytes(folder / "looks_like.exr", encodePng(1, 1, 1, 8, {255}));
  EXPECT_EQ(readImage(folder / "looks_like.exr").at(0, 0), glm::vec3(1.0f));
}

TEST(ImageIoRead, BadFilesGiveOneLineErrorsNamingTheFile) {
  const auto folder = temporaryFolder("image_bad");
  const std::string png = encodePng(8, 8, 3, 8, std::vector<std::uint16_t>(8 * 8 * 3, 100));
  writeBytes(folder / "truncated.png", png.substr(0, png.size() / 2));
  writeBytes(folder / "signature_only.png", png.substr(0, 6));
  std::string corrupt = png;
  corrupt[40] = static_cast<char>(corrupt[40] ^ 0x55);  // inside IDAT's stored-block header
  writeBytes(folder / "corrupt.png", corrupt);
  writeBytes(folder / "zero.png", encodePng(0, 4, 3, 8, {}));
  ImageRgbF image = ImageRgbF::filled(20, 20, glm::vec3(0.25f));
  writeExr(folder / "whole.exr", image);
  const std::string exr = slurp(folder / "whole.exr");
  writeBytes(folder / "truncated.exr", exr.substr(0, exr.size() / 2));
  writeBytes(folder / "header_only.exr", exr.substr(0, 20));
  writeExrChannels(folder / "uv.exr", 1, 1, {"U", "V"}, {{1}, {2}}, TINYEXR_PIXELTYPE_FLOAT);
  writeBytes(folder / "text.png", "hello, not an image\n");
  writeBytes(folder / "empty.exr", "");

  expectError([&] { readImage(folder / "truncated.png"); }, {"truncated.png: truncated or corrupt PNG"});
  expectError([&] { readImage(folder / "signature_only.png"); }, {"signature_only.png: truncated or corrupt PNG"});
  expectError([&] { readImage(folder / "corrupt.png"); }, {"corrupt.png: truncated or corrupt PNG"});
  expectError([&] { readImage(folder / "zero.png"); }, {"zero.png: zero-size image (0x4)"});
  expectError([&] { readImage(folder / "truncated.exr"); }, {"truncated.exr: truncated or corrupt EXR"});
  expectError([&] { readImage(folder / "header_only.exr"); }, {"header_only.exr: truncated or corrupt EXR"});
  expectError([&] { readImage(folder / "uv.exr"); }, {"uv.exr: unsupported EXR", "R channel not found"});
  expectError([&] { readImage(folder / "text.png"); }, {"text.png: not a PNG or EXR image"});
  expectError([&] { readImage(folder / "empty.exr"); }, {"empty.exr: empty file"});
  expectError([&] { readImage(folder / "missing.png"); }, {"missing.png: cannot open"});
  expectError([&] { readImage(folder); }, {"is a directory"});
  // A damaged chunk's name reaches the message as printable text, not raw bytes.
  std::string renamed = png;
  const std::size_t idat = renamed.find("IDAT");
  ASSERT_NE(idat, std::string::npos);
  renamed[idat + 3] = static_cast<char>(0xbd);
  writeBytes(folder / "renamed.png", renamed);
  const std::string message = errorOf([&] { readImage(folder / "renamed.png"); });
  EXPECT_NE(message.find("renamed.png: truncated or corrupt PNG (IDA? PNG chunk not known)"), std::string::npos) << message;
  EXPECT_TRUE(std::all_of(message.begin(), message.end(), [](char c) { return c >= 0x20 && c <= 0x7e; })) << message;
}

// --- Writing by extension ----------------------------------------------------------------------

TEST(ImageIoWrite, ChoosesTheFormatByExtension) {
  const auto folder = temporaryFolder("image_write");
  const ImageRgbF image = image2x1(glm::vec3(0.25f), glm::vec3(1.0f));
  writeImage(folder / "a.EXR", image);
  writeImage(folder / "b.Png", image);
  EXPECT_EQ(slurp(folder / "a.EXR").substr(0, 4), std::string("\x76\x2f\x31\x01", 4));
  EXPECT_EQ(slurp(folder / "b.Png").substr(0, 4), "\x89PNG");
  expectError([&] { writeImage(folder / "c.jpg", image); }, {"c.jpg", "'.jpg'", "(supported: .png, .exr)"});
  expectError([&] { writeImage(folder / "d", image); }, {"(supported: .png, .exr)"});
  expectError([&] { writeImage(folder / "no" / "such" / "e.exr", image); }, {"e.exr: cannot create"});
  EXPECT_FALSE(std::filesystem::exists(folder / "c.jpg"));
  EXPECT_FALSE(std::filesystem::exists(folder / "d"));
}

// A full disk, as /dev/full stands for it (every write fails with ENOSPC), reached through a link
// with the image's extension: the error names the file and the system's reason, and nothing is
// left behind (the link stays a link to the device).
TEST(ImageIoWrite, AFullDiskGivesTheSystemsReasonAndTheFileName) {
  if (!std::filesystem::is_character_file("/dev/full")) GTEST_SKIP() << "needs /dev/full (Linux)";
  const auto folder = temporaryFolder("image_full_disk");
  for (const char* name : {"full.png", "full.exr"}) std::filesystem::create_symlink("/dev/full", folder / name);
  const ImageRgbF image = image2x1(glm::vec3(0.25f), glm::vec3(1.0f));
  expectError([&] { writeImage(folder / "full.png", image); }, {"full.png: cannot write (No space left on device)"});
  expectError([&] { writeExr(folder / "full.exr", image); }, {"full.exr: cannot write (No space left on device)"});
  std::size_t entries = 0;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    EXPECT_TRUE(entry.is_symlink()) << "left behind: " << entry.path();
    ++entries;
  }
  EXPECT_EQ(entries, 2u);
  EXPECT_TRUE(std::filesystem::is_character_file("/dev/full"));
}

// Files that come one at a time and make one output (an orbit's frames): none is in place before
// commit(); a failure at the third leaves the first two's old contents and no temporary; after
// commit() all are in place.
TEST(ImageIoWrite, StagedFilesAppearTogetherOrNotAtAll) {
  const auto folder = temporaryFolder("staged_files");
  const auto bytes = [](const std::string& text) {
    return std::vector<std::byte>(reinterpret_cast<const std::byte*>(text.data()),
                                  reinterpret_cast<const std::byte*>(text.data()) + text.size());
  };
  writeFileAtomically(folder / "a", bytes("old a"));
  std::filesystem::create_directory(folder / "c");  // a folder where the third file would go
  {
    StagedFiles staged;
    staged.add(folder / "a", bytes("new a"));
    staged.add(folder / "b", bytes("new b"));
    EXPECT_EQ(slurp(folder / "a"), "old a");
    EXPECT_FALSE(std::filesystem::exists(folder / "b"));
    expectError([&] { staged.add(folder / "c", bytes("new c")); }, {"c: cannot write (is a directory)"});
  }  // not committed: the staged files' temporaries go
  EXPECT_EQ(slurp(folder / "a"), "old a");
  EXPECT_FALSE(std::filesystem::exists(folder / "b"));
  std::filesystem::remove(folder / "c");
  {
    StagedFiles staged;
    for (const char* name : {"a", "b", "c"}) staged.add(folder / name, bytes(std::string("new ") + name));
    staged.commit();
  }
  for (const char* name : {"a", "b", "c"}) EXPECT_EQ(slurp(folder / name), std::string("new ") + name);
  {
    // One name given twice, the second time spelt another way: both would share a temporary.
    StagedFiles staged;
    staged.add(folder / "a", bytes("newer a"));
    expectError([&] { staged.add(folder / "." / "a", bytes("other a")); }, {"a: given twice as an output"});
  }
  EXPECT_EQ(slurp(folder / "a"), "new a");
  std::size_t entries = 0;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    EXPECT_EQ(entry.path().string().find(".tmp"), std::string::npos) << "left behind: " << entry.path();
    ++entries;
  }
  EXPECT_EQ(entries, 3u);
}

// --- Metrics -----------------------------------------------------------------------------------

TEST(ImageIoMetrics, MatchHandComputedValues) {
  // Values exact in float. Differences over the six samples: 0.25, 0, 0, 0, 0, -0.5.
  const ImageRgbF reference = image2x1(glm::vec3(0.25f, 0.5f, 0.75f), glm::vec3(1, 1, 1));
  const ImageRgbF test = image2x1(glm::vec3(0.5f, 0.5f, 0.75f), glm::vec3(1, 1, 0.5f));
  const ImageError error = compareImages(test, reference);
  EXPECT_NEAR(error.rmse, std::sqrt((0.0625 + 0.25) / 6.0), 1e-12);                   // 0.2282177
  EXPECT_NEAR(error.relmse, (0.0625 / (0.0625 + 0.01) + 0.25 / (1.0 + 0.01)) / 6.0, 1e-12);  // 0.1849323
  EXPECT_NEAR(error.meanReference, (0.25 + 0.5 + 0.75 + 3.0) / 6.0, 1e-12);          // 0.75
  const ImageError same = compareImages(reference, reference);
  EXPECT_EQ(same.rmse, 0.0);
  EXPECT_EQ(same.relmse, 0.0);
  // relmse is not symmetric: the reference's values divide.
  EXPECT_NEAR(compareImages(reference, test).relmse, (0.0625 / (0.25 + 0.01) + 0.25 / (0.25 + 0.01)) / 6.0, 1e-12);
}

TEST(ImageIoMetrics, SizesMustMatch) {
  const ImageRgbF wide = ImageRgbF::filled(2, 1);
  const ImageRgbF tall = ImageRgbF::filled(1, 2);
  expectError([&] { compareImages(wide, tall); }, {"test 2x1", "reference 1x2"});
  expectError([&] { falseColourDifference(wide, tall, 1.0f); }, {"2x1", "1x2"});
  expectError([&] { compareImages(ImageRgbF{}, ImageRgbF{}); }, {"empty"});
}

// --- The false-colour picture ------------------------------------------------------------------

TEST(ImageIoDiffPicture, AutomaticScaleIgnoresOneOutlier) {
  // 100 pixels differing by 0.5 and one by 1000: the nearest-rank 99th percentile of 101 values is
  // the 100th smallest, 0.5.
  ImageRgbF a = ImageRgbF::filled(101, 1, glm::vec3(0.5f));
  const ImageRgbF b = ImageRgbF::filled(101, 1);
  a.at(50, 0) = glm::vec3(1000.0f);
  EXPECT_EQ(automaticDifferenceScale(a, b), 0.5f);
  // Under 1% differ: the largest difference; none differ: 1.
  ImageRgbF c = ImageRgbF::filled(200, 1);
  c.at(3, 0) = glm::vec3(0.0f, 0.0f, 6.0f);  // mean over channels: 2
  EXPECT_EQ(automaticDifferenceScale(c, ImageRgbF::filled(200, 1)), 2.0f);
  EXPECT_EQ(automaticDifferenceScale(b, b), 1.0f);
}

TEST(ImageIoDiffPicture, MapsDifferencesThroughTheColourMapWithALegend) {
  ImageRgbF a = ImageRgbF::filled(4, 3);
  const ImageRgbF b = ImageRgbF::filled(4, 3);
  a.at(1, 0) = glm::vec3(0.3f);   // exactly the scale: top of the map
  a.at(2, 0) = glm::vec3(30.0f);  // beyond it: saturates
  const ImageRgb8 picture = falseColourDifference(a, b, 0.3f);
  EXPECT_EQ(picture.width(), kMinDiffWidth);  // widened so that the legend fits
  EXPECT_GT(picture.height(), 3);
  auto same = [](Rgb8 p, Rgb8 q) { return p.r == q.r && p.g == q.g && p.b == q.b; };
  const Rgb8 bottom{0, 0, 4};  // inferno(0), matplotlib's #000004
  const Rgb8 top{252, 255, 164};  // inferno(1), #FCFFA4
  EXPECT_TRUE(same(infernoColour(0.0f), bottom));
  EXPECT_TRUE(same(infernoColour(1.0f), top));
  EXPECT_TRUE(same(picture.at(0, 0), bottom));
  EXPECT_TRUE(same(picture.at(1, 0), top));
  EXPECT_TRUE(same(picture.at(2, 0), top));
  EXPECT_TRUE(same(picture.at(3, 2), bottom));
  // The colour bar runs from the bottom to the top of the map across the legend.
  bool sawBottom = false, sawTop = false;
  for (int y = 3; y < picture.height(); ++y) {
    for (int x = 0; x < picture.width(); ++x) {
      sawBottom = sawBottom || same(picture.at(x, y), bottom);
      sawTop = sawTop || same(picture.at(x, y), top);
    }
  }
  EXPECT_TRUE(sawBottom && sawTop);
  expectError([&] { falseColourDifference(a, b, -1.0f); }, {"scale must be a finite number >= 0, got -1"});
  expectError([&] { falseColourDifference(a, b, std::numeric_limits<float>::quiet_NaN()); }, {"scale"});
  // Wide images keep their width.
  EXPECT_EQ(falseColourDifference(ImageRgbF::filled(300, 2), ImageRgbF::filled(300, 2), 0.0f).width(), 300);
}

// --- `glint diff` ------------------------------------------------------------------------------

TEST(DiffCli, IdenticalImagesHaveZeroError) {
  const auto folder = temporaryFolder("diff_identical");
  writeExr(folder / "a.exr", image2x1(glm::vec3(0.1f, 0.2f, 0.3f), glm::vec3(4, 5, 6)));
  const RunResult result = runGlint(folder, "diff a.exr a.exr");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_EQ(result.out, "rmse 0\nrelmse 0\n");
  EXPECT_EQ(result.err, "");
}

TEST(DiffCli, PrintsTheMetricsOfAKnownDifference) {
  // The images of ImageIoMetrics.MatchHandComputedValues: rmse sqrt(0.3125 / 6) = 0.22821773,
  // relmse (0.0625 / 0.0725 + 0.25 / 1.01) / 6 = 0.18493229, printed with %.6g.
  const auto folder = temporaryFolder("diff_known");
  writeExr(folder / "reference.exr", image2x1(glm::vec3(0.25f, 0.5f, 0.75f), glm::vec3(1, 1, 1)));
  writeExr(folder / "test.exr", image2x1(glm::vec3(0.5f, 0.5f, 0.75f), glm::vec3(1, 1, 0.5f)));
  const RunResult result = runGlint(folder, "diff test.exr reference.exr");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_EQ(result.out, "rmse 0.228218\nrelmse 0.184932\n");
}

TEST(DiffCli, ComparesPngInLinearValues) {
  // sRGB code 128 is linear 0.2158605: against an EXR holding that value the error is only the
  // float rounding of the decode, not 128/255 - 0.2158605 = 0.29.
  const auto folder = temporaryFolder("diff_linear");
  writeBytes(folder / "grey.png", encodePng(2, 1, 1, 8, {128, 128}));
  writeExr(folder / "grey.exr", ImageRgbF::filled(2, 1, glm::vec3(kLinear128)));
  const RunResult result = runGlint(folder, "diff grey.png grey.exr");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  ASSERT_EQ(result.out.rfind("rmse ", 0), 0u) << result.out;
  EXPECT_LT(std::stod(result.out.substr(5)), 1e-7) << result.out;
}

TEST(DiffCli, WritesAFalseColourPicture) {
  const auto folder = temporaryFolder("diff_picture");
  ImageRgbF reference = ImageRgbF::filled(200, 50, glm::vec3(0.5f));
  ImageRgbF test = reference;
  for (int x = 0; x < 200; ++x) test.at(x, 10) = glm::vec3(0.5f + x / 400.0f);
  writeExr(folder / "reference.exr", reference);
  writeExr(folder / "test.exr", test);
  const RunResult result = runGlint(folder, "diff test.exr reference.exr -o diff.png --scale 0.25");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_EQ(std::count(result.out.begin(), result.out.end(), '\n'), 2) << result.out;
  const ImageRgbF picture = readImage(folder / "diff.png");
  EXPECT_EQ(picture.width, 200);
  EXPECT_GT(picture.height, 50);
  EXPECT_EQ(picture.at(0, 0), glm::vec3(srgbToLinear(0.0f), srgbToLinear(0.0f), srgbToLinear(4.0f / 255.0f)));
  EXPECT_NE(picture.at(199, 10), picture.at(0, 0));
  ASSERT_EQ(runGlint(folder, "diff test.exr reference.exr -o auto.png").exitCode, 0);
  EXPECT_TRUE(std::filesystem::exists(folder / "auto.png"));
}

TEST(DiffCli, BadInputsGiveOneLineErrorsAndNoPicture) {
  const auto folder = temporaryFolder("diff_errors");
  writeExr(folder / "a.exr", ImageRgbF::filled(2, 1));
  writeExr(folder / "tall.exr", ImageRgbF::filled(1, 2));
  const std::string png = encodePng(4, 4, 3, 8, std::vector<std::uint16_t>(48, 9));
  writeBytes(folder / "truncated.png", png.substr(0, png.size() / 2));
  const std::string exr = slurp(folder / "a.exr");
  writeBytes(folder / "truncated.exr", exr.substr(0, exr.size() / 2));
  writeBytes(folder / "notes.txt", "not an image\n");
  expectOneLineError(runGlint(folder, "diff missing.png a.exr -o diff.png"), "missing.png: cannot open");
  expectOneLineError(runGlint(folder, "diff a.exr missing.exr -o diff.png"), "missing.exr: cannot open");
  expectOneLineError(runGlint(folder, "diff truncated.png a.exr -o diff.png"), "truncated.png: truncated or corrupt PNG");
  expectOneLineError(runGlint(folder, "diff a.exr truncated.exr -o diff.png"), "truncated.exr: truncated or corrupt EXR");
  expectOneLineError(runGlint(folder, "diff notes.txt a.exr -o diff.png"), "notes.txt: not a PNG or EXR image");
  expectOneLineError(runGlint(folder, "diff a.exr tall.exr -o diff.png"),
                     "a.exr vs tall.exr: image sizes differ: test 2x1, reference 1x2");
  expectOneLineError(runGlint(folder, "diff a.exr a.exr -o diff.jpg"), "diff.jpg: the difference picture is a PNG");
  expectOneLineError(runGlint(folder, "diff a.exr a.exr -o diff.png --scale -1"), "scale must be a finite number >= 0");
  expectOneLineError(runGlint(folder, "diff a.exr a.exr -o no/such/diff.png"), "no/such/diff.png: cannot create");
  const RunResult noOutput = runGlint(folder, "diff a.exr a.exr --scale 2");
  expectOneLineError(noOutput, "--scale");
  EXPECT_EQ(noOutput.exitCode, 2);
  expectOneLineError(runGlint(folder, "diff a.exr"), "B");
  for (const char* name : {"diff.png", "diff.jpg"}) EXPECT_FALSE(std::filesystem::exists(folder / name)) << name;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    EXPECT_EQ(entry.path().string().find(".tmp"), std::string::npos) << entry.path();
  }
}

}  // namespace
}  // namespace glint
