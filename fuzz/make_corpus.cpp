// Writes the fuzz targets' seed corpus (fuzz/corpus/<target>/) and regression inputs
// (fuzz/regressions/<target>/) with glint's own writers where it has one: `make_fuzz_corpus FOLDER`
// (FOLDER is fuzz/). Not run by the build: the files are committed, and this says how each was made.
// Each regression input is named for the defect it pins; the test suite reads some of them too
// (tests/test_decoder_checks.cpp).
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <draco/compression/encode.h>
#include <draco/mesh/mesh.h>
#include <meshoptimizer.h>
#include <stb_image_write.h>
#include <tinyexr.h>

#include "glint/dictionary.h"
#include "glint/image_io.h"
#include "glint/radiance_hdr.h"
#include "scene/gltf_writer.h"
#include "scene/scene.h"

namespace {

namespace fs = std::filesystem;
using namespace glint;

fs::path root;

void write(const std::string& relative, const std::string& bytes) {
  const fs::path path = root / relative;
  fs::create_directories(path.parent_path());
  std::ofstream(path, std::ios::binary) << bytes;
  std::printf("%s: %zu bytes\n", relative.c_str(), bytes.size());
}

std::string text(const std::vector<std::byte>& bytes) {
  return {reinterpret_cast<const char*>(bytes.data()), bytes.size()};
}

std::string slurp(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Through a temporary file: glint's image writers take paths.
std::string exrOf(const ImageRgbF& image) {
  const fs::path path = fs::temp_directory_path() / "glint-corpus.exr";
  writeExr(path, image);
  const std::string bytes = slurp(path);
  fs::remove(path);
  return bytes;
}
std::string pngOf(const ImageRgbF& image) {
  const fs::path path = fs::temp_directory_path() / "glint-corpus.png";
  writePngSrgb(path, image);
  const std::string bytes = slurp(path);
  fs::remove(path);
  return bytes;
}

ImageRgbF gradient(int width, int height) {
  ImageRgbF image = ImageRgbF::filled(width, height);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) image.at(x, y) = glm::vec3(0.1f * x, 0.2f * y, 0.5f);
  }
  return image;
}

// EXR kinds glint's writer does not make (it writes float RGB with ZIP): half, one channel, other
// compressions, tiles; through tinyexr's own writer.
std::string exrVariant(int pixelType, int compression, bool single, bool tiled) {
  const int width = 4;
  const int height = 2;
  const int channels = single ? 1 : 3;
  std::vector<std::vector<float>> planes(static_cast<std::size_t>(channels), std::vector<float>(width * height));
  for (int c = 0; c < channels; ++c) {
    for (int i = 0; i < width * height; ++i) planes[c][i] = 0.125f * static_cast<float>(i + c);
  }
  std::vector<float*> pointers;
  for (auto& plane : planes) pointers.push_back(plane.data());
  std::vector<EXRChannelInfo> info(static_cast<std::size_t>(channels));
  const char* names[3] = {"B", "G", "R"};
  for (int c = 0; c < channels; ++c) std::strcpy(info[c].name, single ? "Y" : names[c]);
  std::vector<int> input(static_cast<std::size_t>(channels), TINYEXR_PIXELTYPE_FLOAT);
  std::vector<int> stored(static_cast<std::size_t>(channels), pixelType);
  EXRHeader header;
  InitEXRHeader(&header);
  header.num_channels = channels;
  header.channels = info.data();
  header.pixel_types = input.data();
  header.requested_pixel_types = stored.data();
  header.compression_type = compression;
  if (tiled) {
    header.tiled = 1;
    header.tile_size_x = 2;
    header.tile_size_y = 2;
    header.tile_level_mode = TINYEXR_TILE_ONE_LEVEL;
  }
  EXRImage image;
  InitEXRImage(&image);
  image.num_channels = channels;
  image.width = width;
  image.height = height;
  image.images = reinterpret_cast<unsigned char**>(pointers.data());
  unsigned char* memory = nullptr;
  const char* error = nullptr;
  const std::size_t size = SaveEXRImageToMemory(&image, &header, &memory, &error);
  if (size == 0) {
    std::fprintf(stderr, "tinyexr: %s\n", error ? error : "?");
    std::exit(1);
  }
  std::string bytes(reinterpret_cast<const char*>(memory), size);
  std::free(memory);
  return bytes;
}

std::string jpegOf(int width, int height, int components) {
  std::vector<unsigned char> pixels(static_cast<std::size_t>(width * height * components));
  for (std::size_t i = 0; i < pixels.size(); ++i) pixels[i] = static_cast<unsigned char>(i * 37);
  std::string bytes;
  stbi_write_jpg_to_func([](void* out, void* data, int size) { static_cast<std::string*>(out)->append(static_cast<char*>(data), size); },
                         &bytes, width, height, components, pixels.data(), 90);
  return bytes;
}

std::string bigEndian32(std::uint32_t value) {
  return {static_cast<char>(value >> 24), static_cast<char>(value >> 16), static_cast<char>(value >> 8), static_cast<char>(value)};
}
std::string littleEndian32(std::uint32_t value) {
  return {static_cast<char>(value), static_cast<char>(value >> 8), static_cast<char>(value >> 16), static_cast<char>(value >> 24)};
}

// A .glb of `json` and a BIN chunk `bin` (each padded to 4 bytes as the format asks).
std::string glb(std::string json, std::string bin) {
  while (json.size() % 4) json += ' ';
  while (bin.size() % 4) bin += '\0';
  const std::string chunks = littleEndian32(static_cast<std::uint32_t>(json.size())) + "JSON" + json +
                             (bin.empty() ? "" : littleEndian32(static_cast<std::uint32_t>(bin.size())) + "BIN" + '\0' + bin);
  return "glTF" + littleEndian32(2) + littleEndian32(static_cast<std::uint32_t>(12 + chunks.size())) + chunks;
}

std::string base64(const std::string& bytes) {
  static const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    std::uint32_t v = static_cast<unsigned char>(bytes[i]) << 16;
    if (i + 1 < bytes.size()) v |= static_cast<unsigned char>(bytes[i + 1]) << 8;
    if (i + 2 < bytes.size()) v |= static_cast<unsigned char>(bytes[i + 2]);
    out += digits[v >> 18 & 63];
    out += digits[v >> 12 & 63];
    out += i + 1 < bytes.size() ? digits[v >> 6 & 63] : '=';
    out += i + 2 < bytes.size() ? digits[v & 63] : '=';
  }
  return out;
}

// A quad of two materials (a textured glint layer, a plain one with vertex colours), three lights
// and a camera: small, and most of what the loader reads.
scene::Scene quadScene() {
  using namespace glint::scene;
  Scene s;
  s.name = "quad";
  Mesh quad;
  quad.name = "quad";
  const glm::vec2 corners[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (const glm::vec2 c : corners) {
    quad.vertices.push_back({glm::vec3(c.x - 0.5f, 0.0f, 0.5f - c.y), glm::vec3(0, 1, 0), glm::vec4(1, 0, 0, 1), c});
  }
  quad.indices = {0, 1, 2, 0, 2, 3};
  quad.material = 0;
  Mesh triangle = quad;
  triangle.name = "triangle";
  triangle.vertices.resize(3);
  triangle.vertices[1].colour = glm::vec4(0.5f, 0.25f, 1.0f, 1.0f);
  triangle.indices = {0, 1, 2};
  triangle.material = 1;
  s.meshes = {quad, triangle};
  Texture texture;
  texture.name = "checker";
  texture.width = 2;
  texture.height = 2;
  texture.rgba = {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 128};
  s.textures = {texture};
  Material glint;
  glint.name = "glitter";
  glint.baseColourTexture = 0;
  glint.normalTexture = 0;
  glint.baseColourUv.scale = glm::vec2(2.0f);
  glint.glint.enabled = true;
  glint.glint.logDensity = 20.0f;
  glint.glint.roughnessTexture = 0;
  glint.glint.patternSeed = 7;
  Material plain;
  plain.name = "plain";
  plain.emissive = glm::vec3(0.5f);
  plain.alphaMode = Material::AlphaMode::Mask;
  s.materials = {glint, plain};
  Light point;
  point.type = Light::Type::Point;
  point.position = glm::vec3(0, 2, 0);
  point.range = 10.0f;
  Light spot = point;
  spot.type = Light::Type::Spot;
  spot.direction = glm::vec3(0, -1, 0);
  Light sun;
  sun.type = Light::Type::Directional;
  s.lights = {point, spot, sun};
  s.cameras["default"] = Camera{};
  return s;
}

std::string trianglePositions() {
  const float p[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  return {reinterpret_cast<const char*>(p), sizeof p};
}

// A triangle (36 bytes of positions in the BIN chunk) textured with a JPEG of `jpegBytes` after them.
std::string jpegTextureJson(std::size_t jpegBytes) {
  return R"({"asset":{"version":"2.0"},"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)"
         R"("meshes":[{"primitives":[{"attributes":{"POSITION":0}, "material":0}]}],)"
         R"("materials":[{"pbrMetallicRoughness":{"baseColorTexture":{"index":0}}}],"textures":[{"source":0}],)"
         R"("images":[{"bufferView":1,"mimeType":"image/jpeg"}],)"
         R"("accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"}],)"
         R"("bufferViews":[{"buffer":0,"byteLength":36},{"buffer":0,"byteOffset":36,"byteLength":)" +
         std::to_string(jpegBytes) + R"(}],"buffers":[{"byteLength":)" + std::to_string(36 + jpegBytes) + "}]}";
}

// A triangle whose positions and indices are a KHR_draco_mesh_compression stream (sequential, no
// quantisation) in a GLB's BIN chunk: the fuzzed bytes reach Draco's decoder.
std::string dracoTriangleGlb() {
  draco::Mesh mesh;
  mesh.set_num_points(3);
  draco::GeometryAttribute position;
  position.Init(draco::GeometryAttribute::POSITION, nullptr, 3, draco::DT_FLOAT32, false, 12, 0);
  const int id = mesh.AddAttribute(position, true, 3);
  const float p[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  for (std::uint32_t i = 0; i < 3; ++i) mesh.attribute(id)->SetAttributeValue(draco::AttributeValueIndex(i), p + 3 * i);
  draco::Mesh::Face face;
  for (std::uint32_t k = 0; k < 3; ++k) face[k] = draco::PointIndex(k);
  mesh.AddFace(face);
  draco::Encoder encoder;
  encoder.SetEncodingMethod(draco::MESH_SEQUENTIAL_ENCODING);
  draco::EncoderBuffer out;
  if (!encoder.EncodeMeshToBuffer(mesh, &out).ok()) throw std::runtime_error("draco: the triangle does not encode");
  const std::string stream(out.data(), out.size());
  const std::string size = std::to_string(stream.size());
  return glb(R"({"asset":{"version":"2.0"},"extensionsUsed":["KHR_draco_mesh_compression"],)"
             R"("extensionsRequired":["KHR_draco_mesh_compression"],"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)"
             R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1,"extensions":{"KHR_draco_mesh_compression":)"
             R"({"bufferView":0,"attributes":{"POSITION":)" +
                 std::to_string(mesh.attribute(id)->unique_id()) +
                 R"(}}}}]}],"accessors":[{"componentType":5126,"count":3,"type":"VEC3"},)"
                 R"({"componentType":5125,"count":3,"type":"SCALAR"}],"bufferViews":[{"buffer":0,"byteLength":)" +
                 size + R"(}],"buffers":[{"byteLength":)" + size + "}]}",
             stream);
}

// A triangle whose positions and indices are EXT_meshopt_compression streams (the vertex codec and
// the triangle index codec) in a GLB's BIN chunk, their uncompressed placements in a fallback
// buffer without data: the fuzzed bytes reach both of meshoptimizer's decoders.
std::string meshoptTriangleGlb() {
  const float p[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const std::uint16_t triangle[3] = {0, 1, 2};
  std::vector<unsigned char> vertices(meshopt_encodeVertexBufferBound(3, 12));
  vertices.resize(meshopt_encodeVertexBuffer(vertices.data(), vertices.size(), p, 3, 12));
  std::vector<unsigned char> indices(meshopt_encodeIndexBufferBound(3, 3));
  indices.resize(meshopt_encodeIndexBuffer(indices.data(), indices.size(), triangle, 3));
  if (vertices.empty() || indices.empty()) throw std::runtime_error("meshopt: the triangle does not encode");
  std::string bin(vertices.begin(), vertices.end());
  while (bin.size() % 4) bin += '\0';
  const std::size_t indexOffset = bin.size();
  bin.append(indices.begin(), indices.end());
  return glb(R"({"asset":{"version":"2.0"},"extensionsUsed":["EXT_meshopt_compression"],)"
             R"("extensionsRequired":["EXT_meshopt_compression"],"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)"
             R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}],)"
             R"("accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"},)"
             R"({"bufferView":1,"componentType":5123,"count":3,"type":"SCALAR"}],)"
             R"("bufferViews":[{"buffer":1,"byteLength":36,"byteStride":12,"extensions":{"EXT_meshopt_compression":)"
             R"({"buffer":0,"byteLength":)" + std::to_string(vertices.size()) +
                 R"(,"byteStride":12,"count":3,"mode":"ATTRIBUTES"}}},)"
                 R"({"buffer":1,"byteOffset":36,"byteLength":6,"extensions":{"EXT_meshopt_compression":)"
                 R"({"buffer":0,"byteOffset":)" + std::to_string(indexOffset) + R"(,"byteLength":)" +
                 std::to_string(indices.size()) + R"(,"byteStride":2,"count":3,"mode":"TRIANGLES"}}}],)"
                 R"("buffers":[{"byteLength":)" + std::to_string(bin.size()) +
                 R"(},{"byteLength":44,"extensions":{"EXT_meshopt_compression":{"fallback":true}}}]})",
             bin);
}

// A textured triangle in JSON with what the export does not write: a fan, a sparse accessor, a
// node hierarchy with a matrix, TRS and a camera on a child.
std::string handWrittenGltf() {
  std::string positions;
  const float p[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  positions.append(reinterpret_cast<const char*>(p), sizeof p);
  std::string sparseIndex(2, '\0');
  sparseIndex[0] = 1;
  std::string sparseValue;
  const float q[3] = {2, 0, 0};
  sparseValue.append(reinterpret_cast<const char*>(q), sizeof q);
  const std::string buffer = positions + sparseIndex + std::string(2, '\0') + sparseValue;
  return R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],
"nodes":[{"matrix":[1,0,0,0,0,1,0,0,0,0,1,0,0,0,0,1],"children":[1,2]},{"mesh":0,"translation":[0,1,0],"rotation":[0,0,0,1],"scale":[1,2,1]},
{"camera":0,"translation":[0,0,3]}],
"cameras":[{"type":"orthographic","orthographic":{"xmag":1,"ymag":1,"znear":0.1,"zfar":10}}],
"meshes":[{"primitives":[{"attributes":{"POSITION":0},"mode":6,"material":0}]}],
"materials":[{"pbrMetallicRoughness":{"baseColorFactor":[1,0.5,0.25,1],"metallicFactor":0.5},"doubleSided":true,
"extras":{"glint":{"alpha":[0.2,0.4],"rho":0.3,"log_density":18,"pattern_seed":4294967295,"random_colours":true}}}],
"accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0],
"sparse":{"count":1,"indices":{"bufferView":1,"componentType":5123},"values":{"bufferView":2}}}],
"bufferViews":[{"buffer":0,"byteLength":36},{"buffer":0,"byteOffset":36,"byteLength":2},{"buffer":0,"byteOffset":40,"byteLength":12}],
"buffers":[{"byteLength":52,"uri":"data:application/octet-stream;base64,)" +
         base64(buffer) + R"("}]})";
}

// A triangle whose material or node carries `material` / `node` members, for the huge-number
// regressions: each loads up to the property it pins.
std::string triangleWith(const std::string& material, const std::string& node, const std::string& extensions = "") {
  std::string positions;
  const float p[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  positions.append(reinterpret_cast<const char*>(p), sizeof p);
  return R"({"asset":{"version":"2.0"},)" + extensions + R"("scenes":[{"nodes":[0]}],"nodes":[{"mesh":0)" + node +
         R"(}],"meshes":[{"primitives":[{"attributes":{"POSITION":0},"material":0}]}],"materials":[{)" + material +
         R"(}],"accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"}],)"
         R"("bufferViews":[{"buffer":0,"byteLength":36}],"buffers":[{"byteLength":36,"uri":"data:application/octet-stream;base64,)" +
         base64(positions) + R"("}]})";
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: make_fuzz_corpus FOLDER (the repository's fuzz/)\n");
    return 2;
  }
  root = argv[1];

  // --- dictionary: glint's format, and one file of the authors' folder (4 texels, RGB) ---------
  DictionaryParameters tiny;
  tiny.numLevels = 2;
  tiny.numDistributions = 3;
  tiny.texelsPerDistribution = 4;
  const Dictionary tinyDictionary = generateDictionary(tiny);
  write("corpus/dictionary/tiny.gdict", text(tinyDictionary.serialise()));
  write("corpus/dictionary/tiny-tree-levels.gdict", text(tinyDictionary.serialise(DictionaryFileTables::LevelsAndTreeLevels)));
  tiny.numLevels = 1;
  tiny.numDistributions = 1;
  tiny.texelsPerDistribution = 2;
  tiny.placement = LobePlacement::Independent;
  write("corpus/dictionary/smallest.gdict", text(generateDictionary(tiny).serialise()));
  write("corpus/dictionary/authors-file.exr", exrOf(gradient(4, 1)));

  // --- image: PNG and EXR as glint reads them, JPEG as glTF images -----------------------------
  write("corpus/image/rgb.png", pngOf(gradient(3, 2)));
  write("corpus/image/float-zip.exr", exrOf(gradient(3, 2)));
  write("corpus/image/half-none.exr", exrVariant(TINYEXR_PIXELTYPE_HALF, TINYEXR_COMPRESSIONTYPE_NONE, false, false));
  write("corpus/image/y-piz.exr", exrVariant(TINYEXR_PIXELTYPE_FLOAT, TINYEXR_COMPRESSIONTYPE_PIZ, true, false));
  write("corpus/image/half-rle-tiled.exr", exrVariant(TINYEXR_PIXELTYPE_HALF, TINYEXR_COMPRESSIONTYPE_RLE, false, true));
  write("corpus/image/grey.jpg", jpegOf(8, 8, 1));
  write("corpus/image/rgb.jpg", jpegOf(16, 8, 3));
  write("corpus/image/flat.hdr", text(encodeRadianceHdr("flat.hdr", gradient(3, 2))));
  {
    std::string grey16;  // a 16-bit grey-alpha PNG through stb_image_write's encoder is 8-bit only
    unsigned char pixels[8] = {0, 255, 64, 128, 128, 64, 255, 0};
    stbi_write_png_to_func([](void* out, void* data, int size) { static_cast<std::string*>(out)->append(static_cast<char*>(data), size); },
                           &grey16, 2, 2, 2, pixels, 4);
    write("corpus/image/grey-alpha.png", grey16);
  }

  // --- gltf: exported by glint, and hand-written ------------------------------------------------
  const scene::Scene quad = quadScene();
  write("corpus/gltf/quad.glb", text(scene::encodeGltf(quad, scene::GltfEncoding::Binary)));
  write("corpus/gltf/quad.gltf", text(scene::encodeGltf(quad, scene::GltfEncoding::Json)));
  write("corpus/gltf/fan-sparse-hierarchy.gltf", handWrittenGltf());
  {
    const std::string jpeg = jpegOf(8, 8, 3);
    write("corpus/gltf/jpeg-texture.glb", glb(jpegTextureJson(jpeg.size()), trianglePositions() + jpeg));
  }
  write("corpus/gltf/draco-triangle.glb", dracoTriangleGlb());
  write("corpus/gltf/meshopt-triangle.glb", meshoptTriangleGlb());

  // --- eval: lines of `glint eval` --------------------------------------------------------------
  write("corpus/eval_line/default.json", "{}");
  write("corpus/eval_line/glint.json",
        R"({"uv":[0.3,0.7],"duvdx":[0.001,0],"duvdy":[0,0.002],"wo":[0.3,0,1],"wi":[-0.2,0.1,1],"alpha":[0.3,0.5],)"
        R"("rho":0.2,"log_density":18,"relative_area":0.5,"density_randomisation":1,"max_anisotropy":4,"pattern_seed":3})");
  write("corpus/eval_line/cook-torrance.json", R"({"brdf":"cook-torrance","wo":[0,0,1],"wi":[0.5,0,1],"alpha":[0.1,0.1]})");
  write("corpus/eval_line/grazing.json", R"({"wo":[1,0,0.01],"wi":[-1,0,0.01],"duvdx":[0.5,0],"duvdy":[0,1e-6]})");

  // --- regressions: inputs that crashed or misbehaved once, and what pins third-party defects ---
  // Footprints beyond float's squared range once gave NaN axes (now scaled down first): the first,
  // a seed, gave P22 0; the second, swapped back unscaled, also converted a NaN to an int.
  write("corpus/eval_line/footprint-1e20.json", R"({"duvdx":[1e20,0],"duvdy":[0,1e20]})");
  write("regressions/eval_line/huge-duvdy-swapped.json", R"({"duvdx":[1e-20,0],"duvdy":[1e20,1e20]})");
  // The largest 32-bit seed: a float rounds it to 2^32, whose conversion back overflows.
  write("regressions/eval_line/pattern-seed-max.json", R"({"pattern_seed":4294967295})");
  write("regressions/eval_line/beyond-double.json", R"({"rho":1e400})");

  // An image's buffer view running past its buffer: tinygltf handed it to stb_image unchecked,
  // which copied the IDAT chunk from beyond the buffer.
  {
    const std::string png = pngOf(gradient(4, 4));
    const std::string head = png.substr(0, 33 + 8);  // signature, IHDR, the IDAT chunk's length and type
    const std::string json =
        R"({"asset":{"version":"2.0"},"images":[{"bufferView":0,"mimeType":"image/png"}],"textures":[{"source":0}],)"
        R"("materials":[{"pbrMetallicRoughness":{"baseColorTexture":{"index":0}}}],)"
        R"("bufferViews":[{"buffer":0,"byteLength":)" + std::to_string(png.size() + 65536) +
        R"(}],"buffers":[{"byteLength":)" + std::to_string(head.size()) + "}]}";
    write("regressions/gltf/image-view-past-buffer.glb", glb(json, head));
  }
  // Seeds that reach the loader's number checks: values finite in double but not in a float, each
  // where the loader reads it (they once gave black renders, not crashes, so they are seeds, not
  // regression inputs), an index beyond a 32-bit int (tinygltf misread it), the largest seed.
  write("corpus/gltf/light-intensity-1e300.gltf",
        triangleWith("", R"(,"extensions":{"KHR_lights_punctual":{"light":0}})",
                     R"("extensionsUsed":["KHR_lights_punctual"],"extensions":{"KHR_lights_punctual":{"lights":[{"type":"point","intensity":1e300}]}},)"));
  write("corpus/gltf/glint-log-density-1e39.gltf", triangleWith(R"("extras":{"glint":{"log_density":1e39}})", ""));
  write("corpus/gltf/emissive-strength-1e39.gltf",
        triangleWith(R"("emissiveFactor":[1,1,1],"extensions":{"KHR_materials_emissive_strength":{"emissiveStrength":1e39}})", ""));
  write("corpus/gltf/translation-1e308.gltf", triangleWith("", R"(,"translation":[1e308,0,0],"scale":[1e308,1,1])"));
  write("corpus/gltf/pattern-seed-max.gltf", triangleWith(R"("extras":{"glint":{"pattern_seed":4294967295}})", ""));
  {
    std::string json = triangleWith("", "");
    const std::string node = R"("nodes":[{"mesh":0}])";
    json.replace(json.find(node), node.size(), R"("nodes":[{"mesh":4294967296}])");
    write("corpus/gltf/index-beyond-int.gltf", json);
  }
  // Extras nested deeper than tinygltf's recursive parser survives.
  write("regressions/gltf/deep-extras.gltf", triangleWith(R"("extras":)" + std::string(20000, '[') + std::string(20000, ']'), ""));

  // stb_image copies an empty first IDAT chunk to a null pointer.
  {
    const std::string png = pngOf(gradient(2, 2));
    const std::size_t idat = png.find("IDAT") - 4;
    // An empty IDAT (length 0, type, the CRC of "IDAT") before the real one.
    const std::string empty = bigEndian32(0) + "IDAT" + bigEndian32(0x35AF061E);
    write("regressions/image/png-empty-idat-first.png", png.substr(0, idat) + empty + png.substr(idat));
  }
  // stb_image's Huffman builder writes past its 257-entry table for a table of more than 256 codes
  // (16 counts of 255: 4080 codes).
  {
    const std::string jpeg = jpegOf(8, 8, 1);
    const std::size_t dht = jpeg.find("\xFF\xC4");
    const std::string table = std::string(1, '\0') + std::string(16, '\xFF') + std::string(4080, '\x01');
    const std::size_t length = table.size() + 2;
    const std::string segment = std::string("\xFF\xC4") + static_cast<char>(length >> 8) + static_cast<char>(length & 0xFF) + table;
    const std::string bad = jpeg.substr(0, dht) + segment + jpeg.substr(dht);
    write("regressions/image/jpeg-huffman-4080-codes.jpg", bad);
    // The same JPEG as a glTF file's texture, where stb_image meets it through tinygltf.
    write("regressions/gltf/jpeg-huffman-4080-codes.glb", glb(jpegTextureJson(bad.size()), trianglePositions() + bad));
  }
  // tinyexr computes max_x - min_x + 1 of the data window in int: (-1, 0) to (2^31 - 1, 1) overflows.
  {
    std::string exr = exrOf(gradient(2, 2));
    const std::size_t at = exr.find(std::string("dataWindow\0box2i\0", 17)) + 17 + 4;
    const int window[4] = {-1, 0, 2147483647, 1};
    std::memcpy(&exr[at], window, sizeof window);
    write("regressions/image/exr-data-window-overflow.exr", exr);
  }
  // A header that asks for 2^23 x 10 pixels in a file of a few hundred bytes: tinyexr allocates and
  // fills them all (16 s under ASan); refused by the pixel budget before decoding.
  {
    std::string exr = exrOf(gradient(2, 2));
    const std::size_t at = exr.find(std::string("dataWindow\0box2i\0", 17)) + 17 + 4;
    const int window[4] = {0, 0, (1 << 23) - 1, 9};
    std::memcpy(&exr[at], window, sizeof window);
    write("regressions/image/exr-80-million-pixels.exr", exr);
  }
  return 0;
}
