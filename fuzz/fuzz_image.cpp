// The image readers: glint's PNG and EXR reader (glint/image_io.h, decodeImage), and the way the
// glTF loader decodes a file's embedded images (PNG or JPEG): glint's checks, then tinygltf's
// stb_image decoder (scene/gltf_loader.cpp, loadCheckedImage, which calls these two), and the
// Radiance .hdr reader of environment maps (glint/radiance_hdr.h).
//
// Every reader takes a pixel budget, 2^27 by default; here it is 2^22 so that an input whose
// header asks for the most a budget allows decodes in about a second under ASan (2^27 would take
// about 30 s, over libFuzzer's 10 s timeout): the refusal path is the same, only its threshold.
#include <string>

#include <tiny_gltf.h>

#include "glint/decoder_checks.h"
#include "glint/error.h"
#include "fuzz_support.h"
#include "glint/image_io.h"
#include "glint/radiance_hdr.h"

namespace {
constexpr std::uint64_t kFuzzMaxPixels = std::uint64_t{1} << 22;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto bytes = glint::fuzz::bytesOf(data, size);
  try {
    glint::decodeImage(bytes, "fuzz", kFuzzMaxPixels);
  } catch (const glint::Error&) {
  }
  try {
    glint::decodeRadianceHdr(bytes, "fuzz", kFuzzMaxPixels);
  } catch (const glint::Error&) {
  }
  try {
    glint::checkGltfImageForDecoder(bytes, kFuzzMaxPixels);
  } catch (const glint::Error&) {
    return 0;
  }
  tinygltf::Image image;
  std::string errors;
  std::string warnings;
  tinygltf::LoadImageData(&image, 0, &errors, &warnings, 0, 0, data, static_cast<int>(size), nullptr);
  return 0;
}
