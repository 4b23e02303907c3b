// The header-only libraries that Debian ships compiled for the host only, compiled here for
// WebAssembly: tinygltf (glTF), with stb_image (its image decoder, also glint's) and
// stb_image_write (glint's PNG writer).
#define TINYGLTF_IMPLEMENTATION
#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <tiny_gltf.h>
