// What glint checks before the third-party decoders (stb_image, tinyexr) see a file's bytes
// (glint/decoder_checks.h, image_io.cpp's EXR reader): each crafted input that reaches a known
// defect of theirs is refused as corrupt, and the valid files of the fuzz corpus still load. The
// crafted inputs are the fuzz targets' regression inputs (fuzz/regressions, written by
// fuzz/make_corpus.cpp).
#include <cstring>
#include <filesystem>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "glint/decoder_checks.h"
#include "glint/error.h"
#include "glint/file_io.h"
#include "glint/image_io.h"
#include "glint/radiance_hdr.h"
#include "scene/gltf_loader.h"
#include "test_support.h"

namespace glint {
namespace {

namespace fs = std::filesystem;

const fs::path kFuzz = fs::path(GLINT_SOURCE_DIR) / "fuzz";

using test::errorOf;
// One line that contains each of `parts`.
void expectError(const std::function<void()>& load, const std::vector<std::string>& parts) {
  const std::string message = errorOf(load);
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  for (const std::string& part : parts) EXPECT_NE(message.find(part), std::string::npos) << message;
}

TEST(DecoderChecks, PngWithAnEmptyIdatBeforeItsDataIsRefused) {
  const fs::path bad = kFuzz / "regressions/image/png-empty-idat-first.png";
  expectError([&] { readImage(bad); }, {"png-empty-idat-first.png", "empty IDAT chunk before the image data"});
  expectError([&] { checkGltfImageForDecoder(readFile(bad)); }, {"empty IDAT"});
  // The valid PNGs of the corpus pass, and an empty IDAT after the data is PNG's own business.
  for (const char* good : {"rgb.png", "grey-alpha.png"}) {
    const std::vector<std::byte> bytes = readFile(kFuzz / "corpus/image" / good);
    EXPECT_NO_THROW(checkPngForDecoder(bytes)) << good;
    EXPECT_NO_THROW(readImage(kFuzz / "corpus/image" / good)) << good;
  }
}

TEST(DecoderChecks, PngChunkLongerThanTheFileIsRefused) {
  // 72 bytes whose third chunk declares 1.2 GB (found by fuzz_image): refused before the decoder
  // allocates for it.
  const fs::path bad = kFuzz / "regressions/image/png-chunk-longer-than-file.png";
  expectError([&] { readImage(bad); }, {"png-chunk-longer-than-file.png", "a chunk declares 1207959570 bytes of data, which with its CRC need 1207959574, and 1 follow"});
  expectError([&] { checkGltfImageForDecoder(readFile(bad)); }, {"chunk declares"});
  // A file cut inside its last chunk is refused too; the whole file passes.
  std::vector<std::byte> bytes = readFile(kFuzz / "corpus/image/rgb.png");
  EXPECT_NO_THROW(checkPngForDecoder(bytes));
  bytes.resize(bytes.size() - 13);  // into the IDAT before IEND's 12 bytes
  expectError([&] { checkPngForDecoder(bytes); }, {"truncated or corrupt PNG", "chunk declares"});
}

TEST(DecoderChecks, PngOfAZeroOrHugeSideIsRefused) {
  std::vector<std::byte> bytes = readFile(kFuzz / "corpus/image/rgb.png");
  auto setWidth = [&](std::uint32_t width) {
    for (int i = 0; i < 4; ++i) bytes[16 + static_cast<std::size_t>(i)] = static_cast<std::byte>(width >> (24 - 8 * i));
  };
  setWidth(0);
  expectError([&] { checkPngForDecoder(bytes); }, {"zero-size image (0x2)"});
  setWidth(kMaxImageSide + 1);
  expectError([&] { checkPngForDecoder(bytes); }, {"image too large (16777217x2"});
}

// A header may ask for more pixels than its bytes hold; the decoders would allocate and fill them
// all. Each format refuses more than the pixel budget before decoding, naming the size.
TEST(DecoderChecks, ImagesOfMorePixelsThanTheBudgetAreRefused) {
  // The fuzzer's find: 2^23 x 10 pixels (84 million, under the default 2^27) in a few hundred
  // bytes; a budget of 2^26 refuses it before tinyexr allocates anything.
  const std::vector<std::byte> exr = readFile(kFuzz / "regressions/image/exr-80-million-pixels.exr");
  expectError([&] { decodeImage(exr, "big.exr", std::uint64_t{1} << 26); },
              {"big.exr: image too large (8388608x10, more than 67108864 pixels)"});
  // The default budget (2^27) is checked the same way: a PNG header of 16384 x 8193.
  std::vector<std::byte> png = readFile(kFuzz / "corpus/image/rgb.png");
  auto setSize = [&](std::uint32_t width, std::uint32_t height) {
    for (int i = 0; i < 4; ++i) {
      png[16 + static_cast<std::size_t>(i)] = static_cast<std::byte>(width >> (24 - 8 * i));
      png[20 + static_cast<std::size_t>(i)] = static_cast<std::byte>(height >> (24 - 8 * i));
    }
  };
  setSize(16384, 8193);
  expectError([&] { decodeImage(png, "big.png"); }, {"big.png: image too large (16384x8193, more than 134217728 pixels)"});
  setSize(3, 2);
  EXPECT_NO_THROW(decodeImage(png, "rgb.png", 6));
  expectError([&] { decodeImage(png, "rgb.png", 5); }, {"rgb.png: image too large (3x2, more than 5 pixels)"});
  // JPEG frame header and Radiance resolution line.
  expectError([&] { checkGltfImageForDecoder(readFile(kFuzz / "corpus/image/rgb.jpg"), 127); },
              {"image too large (16x8, more than 127 pixels)"});
  EXPECT_NO_THROW(checkGltfImageForDecoder(readFile(kFuzz / "corpus/image/rgb.jpg"), 128));
  const std::vector<std::byte> hdr = readFile(kFuzz / "corpus/image/flat.hdr");
  expectError([&] { decodeRadianceHdr(hdr, "flat.hdr", 5); }, {"flat.hdr: image too large (3x2, more than 5 pixels)"});
  EXPECT_EQ(decodeRadianceHdr(hdr, "flat.hdr", 6).width, 3);
}

TEST(DecoderChecks, JpegHuffmanTableOfMoreThan256CodesIsRefused) {
  expectError([&] { checkGltfImageForDecoder(readFile(kFuzz / "regressions/image/jpeg-huffman-4080-codes.jpg")); },
              {"corrupt JPEG (a Huffman table with 4080 codes, more than 256)"});
  for (const char* good : {"grey.jpg", "rgb.jpg"}) {
    EXPECT_NO_THROW(checkJpegForDecoder(readFile(kFuzz / "corpus/image" / good))) << good;
  }
  // Where stb_image meets it: a glTF file's texture. The file is refused naming the image.
  expectError([&] { scene::loadGltf(kFuzz / "regressions/gltf/jpeg-huffman-4080-codes.glb"); },
              {"jpeg-huffman-4080-codes.glb", "image 0", "4080 codes"});
  EXPECT_NO_THROW(scene::loadGltf(kFuzz / "corpus/gltf/jpeg-texture.glb"));
}

TEST(DecoderChecks, GltfImagesThatAreNeitherPngNorJpegAreRefused) {
  // "BM" and zeros, base64: stb_image would try its BMP reader on it.
  const std::string gltf =
      R"({"asset":{"version":"2.0"},"images":[{"uri":"data:image/png;base64,Qk0AAAAAAAAAAAAAAAA="}]})";
  const std::span<const std::byte> bytes(reinterpret_cast<const std::byte*>(gltf.data()), gltf.size());
  expectError([&] { scene::loadGltf(bytes, "bmp", ""); }, {"image 0", "not a PNG or JPEG image"});
}

TEST(DecoderChecks, ExrDataWindowThatOverflowsAnIntIsRefused) {
  expectError([&] { readImage(kFuzz / "regressions/image/exr-data-window-overflow.exr"); },
              {"exr-data-window-overflow.exr: truncated or corrupt EXR (data window (-1, 0) to (2147483647, 1)"});
}

// A header whose "type" attribute names an unknown kind, or a tiled kind without tiles: tinyexr
// fails an assert converting it (found by fuzz_image), even when a later attribute is cut short,
// and aborts; the walk refuses it first and passes every consistent header, tiled or not.
std::vector<std::byte> exrHeader(const std::vector<std::pair<std::string, std::string>>& attributes, bool tiled = false) {
  std::string text = std::string("\x76\x2f\x31\x01\x02\x00\x00\x00", 8);
  if (tiled) text[5] = '\x02';
  for (const auto& [name, value] : attributes) {
    const auto size = static_cast<std::uint32_t>(value.size());
    text += name + '\0' + (name == "tiles" ? "tiledesc" : "string") + '\0';
    for (int k = 0; k < 4; ++k) text += static_cast<char>(size >> (8 * k) & 0xff);
    text += value;
  }
  text += '\0';
  std::vector<std::byte> bytes(text.size());
  std::memcpy(bytes.data(), text.data(), text.size());
  return bytes;
}

TEST(DecoderChecks, ExrTypeAttributeThatTinyexrAssertsOnIsRefused) {
  expectError([&] { readImage(kFuzz / "regressions/image/exr-type-attribute-asserts.exr"); },
              {"exr-type-attribute-asserts.exr: unsupported EXR (its type attribute is"});
  const std::string tileDescription(9, '\x01');
  expectError([&] { readImage(kFuzz / "regressions/image/exr-type-attribute-then-cut-short.exr"); },
              {"exr-type-attribute-then-cut-short.exr: unsupported EXR (its type attribute is"});
  expectError([&] { checkExrForDecoder(exrHeader({{"type", std::string("tiledimage\0", 11)}})); },
              {"unsupported EXR (its type attribute is \"tiledimage\" in a scanline file"});
  expectError([&] { checkExrForDecoder(exrHeader({{"type", "tiledimage"}, {"tiles", tileDescription}}, true)); },
              {"unsupported EXR (its type attribute is \"tiledimage\" in a tiled file"});
  expectError([&] { checkExrForDecoder(exrHeader({{"tiles", tileDescription}, {"type", "scanlineimage"}}, true)); },
              {"unsupported EXR (its type attribute is \"scanlineimage\" in a tiled file"});
  expectError([&] { checkExrForDecoder(exrHeader({{"type", "deepscanline"}})); },
              {"unsupported EXR (its type attribute is \"deepscanline\""});
  expectError([&] { checkExrForDecoder(exrHeader({{"tiles", "12345678"}}, true)); },
              {"corrupt EXR (its tiles attribute holds 8 bytes, not 9)"});
  EXPECT_NO_THROW(checkExrForDecoder(exrHeader({{"type", "scanlineimage"}})));
  EXPECT_NO_THROW(checkExrForDecoder(exrHeader({{"tiles", tileDescription}, {"type", "tiledimage"}}, true)));
  EXPECT_NO_THROW(checkExrForDecoder(exrHeader({{"name", "left"}, {"tiles", "12345678"}})));  // not read in a scanline file
  // What follows an attribute tinyexr cannot read is not read.
  std::vector<std::byte> cut = exrHeader({{"name", "left"}, {"type", "bogus"}});
  cut.resize(cut.size() - 4);
  EXPECT_NO_THROW(checkExrForDecoder(cut));
}

// A chunk that does not decompress: tinyexr fails after allocating the planes, and freed only their
// list (a leak that the sanitizer build's LeakSanitizer reports at exit); now it frees them too.
TEST(DecoderChecks, ExrWhosePixelsDoNotDecodeIsRefusedWithoutALeak) {
  expectError([&] { readImage(kFuzz / "regressions/image/exr-corrupt-chunk-leaks-planes.exr"); },
              {"exr-corrupt-chunk-leaks-planes.exr: truncated or corrupt EXR ("});
}

// The EXR reader copies channels itself (tinyexr's own copy leaks on its error paths): scanlines
// and tiles, half and float, one channel and three, as tinyexr's writer stored them.
TEST(DecoderChecks, ExrKindsDecodeToTheirValues) {
  // make_corpus.cpp: 4 x 2 pixels, channel c (B, G, R in file order) of pixel i holds (i + c) / 8.
  for (const char* name : {"half-none.exr", "half-rle-tiled.exr", "y-piz.exr"}) {
    SCOPED_TRACE(name);
    const ImageRgbF image = readImage(kFuzz / "corpus/image" / name);
    ASSERT_EQ(image.width, 4);
    ASSERT_EQ(image.height, 2);
    const bool grey = std::string(name) == "y-piz.exr";
    for (int i = 0; i < 8; ++i) {
      const glm::vec3 expected =
          grey ? glm::vec3(0.125f * static_cast<float>(i)) : 0.125f * glm::vec3(i + 2, i + 1, i);
      EXPECT_EQ(image.at(i % 4, i / 4), expected) << "pixel " << i;
    }
  }
}

}  // namespace
}  // namespace glint
