// The image readers: glint's PNG and EXR reader (glint/image_io.h, decodeImage), and the way the
// glTF loader decodes a file's embedded images (PNG or JPEG): glint's checks, then tinygltf's
// stb_image decoder (scene/gltf_loader.cpp, loadCheckedImage, which calls these two).
#include <string>

#include <tiny_gltf.h>

#include "decoder_checks.h"
#include "error.h"
#include "fuzz_support.h"
#include "image_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto bytes = glint::fuzz::bytesOf(data, size);
  try {
    glint::decodeImage(bytes, "fuzz");
  } catch (const glint::Error&) {
  }
  try {
    glint::checkGltfImageForDecoder(bytes);
  } catch (const glint::Error&) {
    return 0;
  }
  tinygltf::Image image;
  std::string errors;
  std::string warnings;
  tinygltf::LoadImageData(&image, 0, &errors, &warnings, 0, 0, data, static_cast<int>(size), nullptr);
  return 0;
}
