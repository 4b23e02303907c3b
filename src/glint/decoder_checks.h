// What glint checks on image bytes before a third-party decoder sees them. The decoders are
// Debian's compiled copies (stb_image through libstb and libtinygltf, tinyexr), which glint cannot
// patch; their known defects on crafted files are listed in docs/reliability.md, and each check
// here refuses exactly the input that reaches one, as a corrupt file, before the decoder runs.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

namespace glint {

// The largest image side stb_image accepts (its STBI_MAX_DIMENSIONS default); glint's own readers
// use it too so that every decoder refuses the same sizes.
inline constexpr std::uint32_t kMaxImageSide = 1u << 24;
// The most pixels glint decodes from one image, whatever its format: 2^27, a 16384 x 8192
// environment map (1.5 GiB as float RGB). A crafted header can ask for far more than its bytes
// hold (a compressed EXR of 8 million by 10 pixels is a few hundred bytes), and the decoders
// allocate and fill what the header asks for; a larger image is refused, naming its size.
inline constexpr std::uint64_t kMaxImagePixels = std::uint64_t{1} << 27;

// Throws Error "image too large (WxH, more than N pixels)" when width x height exceeds maxPixels.
void checkImagePixels(std::uint64_t width, std::uint64_t height, std::uint64_t maxPixels);

// Whether the bytes start with the PNG signature, the JPEG start-of-image marker.
bool looksLikePng(std::span<const std::byte> bytes);
bool looksLikeJpeg(std::span<const std::byte> bytes);

// For bytes that start with the PNG signature: throws Error (a message without the file's name,
// for the caller to prefix) when IHDR is not the first chunk with 13 bytes, when the image has a
// zero side or one over kMaxImageSide, more pixels than maxPixels, when a chunk declares more than 2^31 - 1 bytes (PNG's own
// limit), or when an empty IDAT chunk comes before any image data: stb_image then copies zero
// bytes to a null pointer (undefined behaviour). What the walk cannot see (a chunk running past
// the end, a bad CRC or zlib stream) is left to the decoder, which reports it.
void checkPngForDecoder(std::span<const std::byte> bytes, std::uint64_t maxPixels = kMaxImagePixels);

// For bytes that start with the JPEG start-of-image marker: walks the marker segments as stb_image
// reads them (skipping the entropy-coded data of each scan) and throws Error for a Huffman table
// (DHT) of more than 256 codes, or whose segment length does not match its tables: stb_image
// builds the table before looking at either, and more than 256 codes write past its 257-entry
// arrays (a heap overflow in libstb), and for a frame of more pixels than maxPixels.
void checkJpegForDecoder(std::span<const std::byte> bytes, std::uint64_t maxPixels = kMaxImagePixels);

// A glTF file's image as the glTF loader hands it to stb_image: PNG or JPEG, the formats glTF 2.0
// allows (stb_image's others never see a file's bytes), checked as above; throws Error otherwise.
void checkGltfImageForDecoder(std::span<const std::byte> bytes, std::uint64_t maxPixels = kMaxImagePixels);

// For the bytes of a single-part EXR file: walks its header's attributes as tinyexr reads them
// (name, type name, 32-bit little-endian size, value) and throws Error where tinyexr would fail an
// assert, which aborts the program: a "tiles" attribute of a tiled file that does not hold 9 bytes,
// or a "type" attribute other than scanlineimage in a scanline file or tiledimage after a valid
// "tiles" attribute (tinyexr converts the header it has read even when reading it failed, and
// asserts that the type matches). What tinyexr stops at (a truncated attribute) ends the walk.
void checkExrForDecoder(std::span<const std::byte> bytes);

// stb_image's reason for a failed decode, fit for one line of text: its terse code ("outofdata"),
// with any byte that is not printable ASCII (a damaged chunk's name) as '?', or `otherwise` when
// stb_image gave none.
std::string decoderReason(const char* reason, const std::string& otherwise = "unreadable");

}  // namespace glint
