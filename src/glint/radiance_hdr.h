// Radiance RGBE images (.hdr, Greg Ward's format as Radiance's `ra_rgbe` and most HDRI sites write
// it): the environment maps' other format beside EXR. glint reads and writes them itself, so that
// each problem of a file gets its own one-line message.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "glint/image_io.h"

namespace glint {

// Whether the bytes start as a Radiance file does ("#?", then the program's name).
bool looksLikeRadianceHdr(std::span<const std::byte> bytes);

// Decodes a Radiance RGBE file: a header of text lines ("FORMAT=32-bit_rle_rgbe" if any format is
// named; other variables are skipped) ended by an empty line, the resolution line "-Y H +X W" (rows
// from the top, the orientation every writer uses), then H scanlines, each flat (4 bytes a pixel)
// or run-length encoded per channel (the "new" encoding, widths 8 to 32767). A pixel (R, G, B, E)
// is (R, G, B) * 2^(E - 136), 0 when E is 0. Throws Error with one line naming `name` and the
// problem (not a Radiance file, unsupported format or orientation, zero or oversized size, more
// than maxPixels pixels, truncated data, a bad run).
ImageRgbF decodeRadianceHdr(std::span<const std::byte> bytes, const std::string& name,
                            std::uint64_t maxPixels = kMaxImagePixels);
// Flat RGBE scanlines (no run-length encoding; readers take both). Throws Error naming the file
// for a zero size or a negative or non-finite pixel; never leaves a partial file.
std::vector<std::byte> encodeRadianceHdr(const std::filesystem::path& path, const ImageRgbF& image);
void writeRadianceHdr(const std::filesystem::path& path, const ImageRgbF& image);

// An environment map file: a Radiance .hdr or an EXR, told apart by their first bytes. Throws
// Error with one line naming the file and the problem (missing, truncated or corrupt, another
// format, a non-finite or negative pixel).
ImageRgbF readRadianceImage(const std::filesystem::path& path);

}  // namespace glint
