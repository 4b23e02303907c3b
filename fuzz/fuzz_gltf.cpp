// The glTF loader (scene/gltf_loader.cpp with its checks in gltf_field_types.cpp and
// gltf_precheck.cpp): .gltf JSON and .glb, through tinygltf, as `glint render FILE` reads them.
#include "glint/error.h"
#include "fuzz_support.h"
#include "scene/gltf_loader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  // Relative URIs point into an empty folder: the file's own bytes are what is fuzzed.
  static const std::filesystem::path empty = glint::fuzz::scratchFolder();
  try {
    glint::scene::loadGltf(glint::fuzz::bytesOf(data, size), "fuzz", empty);
  } catch (const glint::Error&) {
  }
  return 0;
}
