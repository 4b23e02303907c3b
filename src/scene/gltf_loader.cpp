#include "scene/gltf_loader.h"

#include "scene/area_lights.h"
#include "scene/gltf_compression.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstring>
#include <cstdint>
#include <span>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <tuple>
#include <utility>

#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
// Debian's libtinygltf-dev ships the implementation compiled (libtinygltf.so): no
// TINYGLTF_IMPLEMENTATION or STB_* macros here.
#include <tiny_gltf.h>
#include <stb_image.h>  // stbi_failure_reason: tinygltf decodes images with the system's stb_image

#include "glint/decoder_checks.h"
#include "glint/error.h"
#include "glint/file_io.h"
#include "scene/geometry.h"
#include "scene/gltf_field_types.h"
#include "scene/gltf_glint.h"
#include "scene/gltf_precheck.h"

namespace glint::scene {

namespace {

namespace fs = std::filesystem;

// tinygltf's messages span lines; ours are one line (docs/conventions.md, "Errors").
std::string oneLine(const std::string& text) {
  std::string line;
  for (char c : text) {
    if (c == '\n' || c == '\r') {
      if (!line.empty() && line.back() != ' ') line += "; ";
    } else {
      line += c;
    }
  }
  while (!line.empty() && (line.back() == ' ' || line.back() == ';')) line.pop_back();
  return line;
}

// A number read from the file in its shortest form that reads back as the same double, so that a
// value just outside a range does not print as its bound (1.0000000001, not 1).
std::string exactly(double value) {
  std::array<char, 32> text{};
  const auto written = std::to_chars(text.data(), text.data() + text.size(), value);
  return std::string(text.data(), written.ptr);
}

template <typename... Parts>
Error error(const Parts&... parts) {
  std::ostringstream message;
  (message << ... << parts);
  return Error(message.str());
}

// Prefixes an Error thrown by `body` with `context` (e.g. "material 2 'paint': ").
template <typename Body>
auto withContext(const std::string& context, Body&& body) {
  try {
    return body();
  } catch (const Error& e) {
    throw Error(context + e.what());
  }
}

// ---- Accessors --------------------------------------------------------------------------------

const char* typeName(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR: return "SCALAR";
    case TINYGLTF_TYPE_VEC2: return "VEC2";
    case TINYGLTF_TYPE_VEC3: return "VEC3";
    case TINYGLTF_TYPE_VEC4: return "VEC4";
    default: return "a matrix or unknown type";
  }
}

// Bytes [offset, offset + stride * (count - 1) + elementSize) of buffer view `viewIndex`, checked
// against the view and the view against its buffer. All sizes in 64 bits: no overflow from huge
// counts in a hostile file (count is checked against the view's length before multiplying).
const unsigned char* viewBytes(const tinygltf::Model& model, int viewIndex, std::uint64_t offset,
                               std::uint64_t stride, std::uint64_t elementSize, std::uint64_t count) {
  if (viewIndex < 0 || static_cast<std::size_t>(viewIndex) >= model.bufferViews.size()) {
    throw error("buffer view ", viewIndex, " does not exist (the file has ", model.bufferViews.size(), ")");
  }
  const tinygltf::BufferView& view = model.bufferViews[static_cast<std::size_t>(viewIndex)];
  if (view.buffer < 0 || static_cast<std::size_t>(view.buffer) >= model.buffers.size()) {
    throw error("buffer view ", viewIndex, ": buffer ", view.buffer, " does not exist");
  }
  const tinygltf::Buffer& buffer = model.buffers[static_cast<std::size_t>(view.buffer)];
  if (view.byteOffset > buffer.data.size() || view.byteLength > buffer.data.size() - view.byteOffset) {
    throw error("buffer view ", viewIndex, ": bytes ", view.byteOffset, " + ", view.byteLength,
                " exceed buffer ", view.buffer, " (", buffer.data.size(), " bytes)");
  }
  if (count > 0) {
    const std::uint64_t length = view.byteLength;
    const bool fits = count <= length && offset <= length && stride <= length &&
                      offset + stride * (count - 1) + elementSize <= length;
    if (!fits) {
      throw error(count, " elements of ", elementSize, " bytes, ", stride, " apart from offset ", offset,
                  " exceed buffer view ", viewIndex, " (", length, " bytes)");
    }
  }
  return buffer.data.data() + view.byteOffset + offset;
}

// One component as glTF defines it: floats as they are, normalised integers mapped to [0, 1] or
// [-1, 1], other integers as their value (KHR_mesh_quantization).
double readComponent(const unsigned char* p, int componentType, bool normalized) {
  auto load = [p]<typename T>(T) {
    T value;
    std::memcpy(&value, p, sizeof value);  // data need not be aligned
    return value;
  };
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return load(float{});
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      const double v = load(std::int8_t{});
      return normalized ? std::max(v / 127.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
      const double v = load(std::uint8_t{});
      return normalized ? v / 255.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      const double v = load(std::int16_t{});
      return normalized ? std::max(v / 32767.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      const double v = load(std::uint16_t{});
      return normalized ? v / 65535.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
      const double v = load(std::uint32_t{});
      return normalized ? v / 4294967295.0 : v;
    }
    default: return 0.0;  // rejected before reading
  }
}

int componentSize(int componentType) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return 4;
    default: return 0;
  }
}

struct AccessorValues {
  std::size_t count = 0;
  int components = 0;
  std::vector<double> values;  // count * components
};

// Reads accessor `index`, which must be of type `expectedType`, with its sparse substitution.
AccessorValues readAccessor(const tinygltf::Model& model, int index, int expectedType) {
  if (index < 0 || static_cast<std::size_t>(index) >= model.accessors.size()) {
    throw error("accessor ", index, " does not exist (the file has ", model.accessors.size(), ")");
  }
  return withContext("accessor " + std::to_string(index) + ": ", [&] {
    const tinygltf::Accessor& accessor = model.accessors[static_cast<std::size_t>(index)];
    if (accessor.type != expectedType) {
      throw error("type ", typeName(accessor.type), ", expected ", typeName(expectedType));
    }
    const int size = componentSize(accessor.componentType);
    if (size == 0) throw error("unsupported component type ", accessor.componentType);
    AccessorValues result;
    result.count = accessor.count;
    result.components = tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(accessor.type));
    const std::uint64_t elementSize = static_cast<std::uint64_t>(size) * static_cast<std::uint64_t>(result.components);
    const auto components = static_cast<std::size_t>(result.components);
    if (accessor.bufferView >= 0) {
      if (static_cast<std::size_t>(accessor.bufferView) >= model.bufferViews.size()) {
        throw error("buffer view ", accessor.bufferView, " does not exist (the file has ", model.bufferViews.size(), ")");
      }
      const tinygltf::BufferView& view = model.bufferViews[static_cast<std::size_t>(accessor.bufferView)];
      const std::uint64_t stride = view.byteStride == 0 ? elementSize : view.byteStride;
      if (stride < elementSize || stride % static_cast<std::uint64_t>(size) != 0) {
        throw error("byte stride ", stride, " does not fit elements of ", elementSize, " bytes");
      }
      const unsigned char* bytes =
          viewBytes(model, accessor.bufferView, accessor.byteOffset, stride, elementSize, accessor.count);
      result.values.resize(result.count * components);
      for (std::size_t i = 0; i < result.count; ++i) {
        for (std::size_t c = 0; c < components; ++c) {
          result.values[i * components + c] =
              readComponent(bytes + i * stride + c * static_cast<std::size_t>(size), accessor.componentType,
                            accessor.normalized);
        }
      }
    } else {
      // glTF: an accessor without a buffer view is all zeros (unless sparse values replace some).
      // No bytes bound the count here: cap it so a hostile file cannot ask for gigabytes of zeros.
      if (accessor.count > (std::size_t{1} << 22)) throw error("count ", accessor.count, " without a buffer view");
      result.values.assign(result.count * components, 0.0);
    }
    if (accessor.sparse.isSparse) {
      const auto& sparse = accessor.sparse;
      if (sparse.count < 0 || static_cast<std::size_t>(sparse.count) > accessor.count) {
        throw error("sparse count ", sparse.count, " exceeds count ", accessor.count);
      }
      const int indexSize = componentSize(sparse.indices.componentType);
      if (indexSize == 0 || sparse.indices.componentType == TINYGLTF_COMPONENT_TYPE_BYTE ||
          sparse.indices.componentType == TINYGLTF_COMPONENT_TYPE_SHORT ||
          sparse.indices.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT) {
        throw error("sparse indices of unsupported component type ", sparse.indices.componentType);
      }
      const auto count = static_cast<std::uint64_t>(sparse.count);
      const unsigned char* indices =
          viewBytes(model, sparse.indices.bufferView, static_cast<std::uint64_t>(std::max(0, sparse.indices.byteOffset)),
                    static_cast<std::uint64_t>(indexSize), static_cast<std::uint64_t>(indexSize), count);
      const unsigned char* values =
          viewBytes(model, sparse.values.bufferView, static_cast<std::uint64_t>(std::max(0, sparse.values.byteOffset)),
                    elementSize, elementSize, count);
      for (std::size_t i = 0; i < count; ++i) {
        const double target = readComponent(indices + i * static_cast<std::size_t>(indexSize),
                                            sparse.indices.componentType, false);
        if (target >= static_cast<double>(accessor.count)) {
          throw error("sparse index ", static_cast<std::uint64_t>(target), " out of range (count ", accessor.count, ")");
        }
        for (std::size_t c = 0; c < components; ++c) {
          result.values[static_cast<std::size_t>(target) * components + c] =
              readComponent(values + i * elementSize + c * static_cast<std::size_t>(size), accessor.componentType,
                            accessor.normalized);
        }
      }
    }
    return result;
  });
}

// ---- Textures ---------------------------------------------------------------------------------

// An image's file, or for an embedded one (buffer view, data URI) its name, "" when it has none: a
// data URI is the image itself.
std::string imageLabel(const tinygltf::Image& image) {
  const bool external = !image.uri.empty() && image.uri.rfind("data:", 0) != 0;
  return external ? image.uri : image.name;
}

// How messages name an image: "image 2 'wood.png'", or "image 2" when it has no label.
std::string describeImage(const tinygltf::Image& image, int imageIndex) {
  const std::string label = imageLabel(image);
  return "image " + std::to_string(imageIndex) + (label.empty() ? "" : " '" + label + "'");
}

// tinygltf's own image decoder (stb_image), whose message names an image by its index alone ("STB
// cannot decode image data for image[0]"): glint's names its file too and gives stb_image's reason.
// The decoder runs behind glint's checks of the image's header (glint/decoder_checks.h).
bool decodeImage(tinygltf::Image* image, int imageIndex, std::string* errors, std::string* warnings, int width,
                 int height, const unsigned char* bytes, int size, void*) {
  try {
    checkGltfImageForDecoder({reinterpret_cast<const std::byte*>(bytes), static_cast<std::size_t>(std::max(size, 0))});
  } catch (const Error& e) {
    if (errors) *errors += describeImage(*image, imageIndex) + ": " + e.what() + "\n";
    return false;
  }
  std::string tinygltfReason;
  if (tinygltf::LoadImageData(image, imageIndex, &tinygltfReason, warnings, width, height, bytes, size, nullptr)) {
    return true;
  }
  if (errors) {
    *errors += describeImage(*image, imageIndex) + ": not an image glint can decode (" +
               decoderReason(stbi_failure_reason(), oneLine(tinygltfReason)) + ")\n";
  }
  return false;
}

// An image decoded by tinygltf (1 to 4 channels, 8 or 16 bits) as RGBA8: grey spreads to RGB,
// missing alpha is opaque, 16-bit values are rounded to 8 bits.
Texture toTexture(const tinygltf::Image& image, int imageIndex, bool srgb) {
  const std::string label = imageLabel(image);
  return withContext(describeImage(image, imageIndex) + ": ", [&] {
    if (image.image.empty()) throw error("no image data (the file is missing or cannot be decoded)");
    const int channels = image.component;
    const int bytes = image.bits / 8;
    if (channels < 1 || channels > 4) throw error(channels, " channels, expected 1 to 4");
    if (image.bits != 8 && image.bits != 16) throw error(image.bits, " bits per channel, expected 8 or 16");
    if (image.width <= 0 || image.height <= 0) throw error("size ", image.width, " x ", image.height);
    const std::size_t pixels = static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height);
    if (image.image.size() != pixels * static_cast<std::size_t>(channels * bytes)) {
      throw error(image.image.size(), " bytes of data for ", image.width, " x ", image.height, " x ", channels,
                  " channels of ", image.bits, " bits");
    }
    Texture texture;
    texture.name = label.empty() ? "image " + std::to_string(imageIndex) : label;
    texture.width = image.width;
    texture.height = image.height;
    texture.srgb = srgb;
    texture.rgba.resize(pixels * 4);
    auto channel = [&](std::size_t pixel, int c) -> std::uint8_t {
      const unsigned char* p = image.image.data() + (pixel * static_cast<std::size_t>(channels) + static_cast<std::size_t>(c)) * static_cast<std::size_t>(bytes);
      if (bytes == 1) return p[0];
      std::uint16_t v;
      std::memcpy(&v, p, 2);  // tinygltf stores 16-bit samples in native byte order
      return static_cast<std::uint8_t>((v * 255u + 32767u) / 65535u);
    };
    for (std::size_t i = 0; i < pixels; ++i) {
      std::uint8_t* out = texture.rgba.data() + i * 4;
      if (channels <= 2) {
        out[0] = out[1] = out[2] = channel(i, 0);
        out[3] = channels == 2 ? channel(i, 1) : 255;
      } else {
        for (int c = 0; c < 3; ++c) out[c] = channel(i, c);
        out[3] = channels == 4 ? channel(i, 3) : 255;
      }
    }
    return texture;
  });
}

// Texture coordinates glint accepts, in magnitude.
constexpr float kLargestUv = 1e6f;

// A member of a JSON object that tinygltf keeps as text (a material's extras or extensions):
// nullopt when the text is empty, does not parse, is not an object or lacks the member.
std::optional<nlohmann::json> memberOf(const std::string& objectText, const char* member) {
  if (objectText.empty()) return std::nullopt;
  const nlohmann::json object = nlohmann::json::parse(objectText, nullptr, false);
  if (!object.is_object() || !object.contains(member)) return std::nullopt;
  return object[member];
}

// ---- The reader -------------------------------------------------------------------------------

class GltfReader {
 public:
  explicit GltfReader(const tinygltf::Model& model) : model_(model) {}

  Scene read(const std::string& name) {
    scene_.name = name;
    for (std::size_t i = 0; i < model_.materials.size(); ++i) {
      const tinygltf::Material& source = model_.materials[i];
      withContext("material " + std::to_string(i) + (source.name.empty() ? "" : " '" + source.name + "'") + ": ",
                  [&] { scene_.materials.push_back(material(source, static_cast<int>(i))); });
    }
    std::vector<bool> onPath(model_.nodes.size(), false);
    for (int root : rootNodes()) visitNode(root, glm::dmat4(1.0), onPath, 0);
    std::size_t triangles = 0;
    for (const Mesh& mesh : scene_.meshes) triangles += mesh.indices.size() / 3;
    if (triangles == 0) throw error("no triangles in the scene");
    addCameras();
    // The file's KHR_lights_punctual lights replace the default ones, and so do its area lights
    // (emissive quadrilaterals, findAreaLights) in a file without punctual lights; glTF has no
    // environment, so the default one stays either way.
    std::vector<Light> fileLights = std::move(scene_.lights);
    scene_.lights.clear();
    addDefaultLighting(scene_);
    if (!fileLights.empty() || !findAreaLights(scene_).lights.empty()) {
      scene_.lights = std::move(fileLights);
      scene_.defaultLights = false;
    }
    scene_.exposure = 1.0f;
    noteUnreadFeatures();
    return std::move(scene_);
  }

 private:
  // What the file uses and glint does not render (found here and while the materials were read), so
  // that the commands warn instead of showing a different picture silently (docs/scenes.md, "Not
  // read"): one line per kind, naming the first place and counting the others. Then the one line
  // on glint layers read from extras.glint.
  void noteUnreadFeatures() {
    for (const std::string& extension : model_.extensionsUsed) {
      if (!glintReadsExtension(extension)) note("extension " + extension + " is not read", "");
    }
    for (std::size_t i = 0; i < model_.meshes.size(); ++i) {
      const tinygltf::Mesh& mesh = model_.meshes[i];
      const std::string where = "mesh " + std::to_string(i) + (mesh.name.empty() ? "" : " '" + mesh.name + "'");
      for (const tinygltf::Primitive& primitive : mesh.primitives) {
        if (!primitive.targets.empty()) note("morph targets are not applied, the base shape is drawn", where);
      }
      // Once a mesh, however many of its primitives are points or lines.
      if (std::any_of(mesh.primitives.begin(), mesh.primitives.end(), [](const tinygltf::Primitive& primitive) {
            return primitive.mode >= TINYGLTF_MODE_POINTS && primitive.mode <= TINYGLTF_MODE_LINE_STRIP;
          })) {
        note("points and lines are not drawn (glint shades surfaces)", where);
      }
    }
    for (std::size_t i = 0; i < model_.materials.size(); ++i) {
      const tinygltf::Material& material = model_.materials[i];
      const std::string where = "material " + std::to_string(i) + (material.name.empty() ? "" : " '" + material.name + "'");
      // KHR_texture_transform's texCoord, where given, overrides the texture's own.
      auto texCoordOf = [](int texCoord, const tinygltf::ExtensionMap& extensions) {
        const auto transform = extensions.find("KHR_texture_transform");
        if (transform == extensions.end() || !transform->second.Has("texCoord")) return texCoord;
        return transform->second.Get("texCoord").GetNumberAsInt();
      };
      const tinygltf::PbrMetallicRoughness& pbr = material.pbrMetallicRoughness;
      const std::pair<const char*, int> texCoords[] = {
          {"baseColorTexture", texCoordOf(pbr.baseColorTexture.texCoord, pbr.baseColorTexture.extensions)},
          {"metallicRoughnessTexture",
           texCoordOf(pbr.metallicRoughnessTexture.texCoord, pbr.metallicRoughnessTexture.extensions)},
          {"normalTexture", texCoordOf(material.normalTexture.texCoord, material.normalTexture.extensions)},
          {"occlusionTexture", texCoordOf(material.occlusionTexture.texCoord, material.occlusionTexture.extensions)},
          {"emissiveTexture", texCoordOf(material.emissiveTexture.texCoord, material.emissiveTexture.extensions)}};
      for (const auto& [texture, texCoord] : texCoords) {
        if (texCoord != 0) note("textures on a texCoord other than 0 are mapped with TEXCOORD_0", where + " " + texture);
      }
    }
    for (std::size_t i = 0; i < model_.textures.size(); ++i) {
      if (model_.textures[i].source < 0) {
        note("textures without a source image are left out, their materials drawn without them",
             "texture " + std::to_string(i));
      }
    }
    if (!model_.skins.empty()) note("skins are not applied, the meshes are drawn unskinned", std::to_string(model_.skins.size()) + " skins");
    if (!model_.animations.empty()) {
      note("animations are not played, the nodes' own transforms are drawn", std::to_string(model_.animations.size()) + " animations");
    }
    for (const auto& [what, places] : unread_) scene_.unreadFeatures.push_back(oneLine(what + placesText(places)));
    // One line for the whole file, however many materials use the older form.
    if (!extrasGlintMaterials_.empty()) {
      scene_.notes.push_back(oneLine("glint layers read from extras.glint, the older form" + placesText(extrasGlintMaterials_) +
                                     "; glint export writes them as EXT_materials_glint"));
    }
  }

  // Something the file uses that glint does not render, at `where` ("" for the whole file).
  void note(const std::string& what, const std::string& where) {
    auto it = std::find_if(unread_.begin(), unread_.end(), [&](const auto& kind) { return kind.first == what; });
    if (it == unread_.end()) it = unread_.insert(unread_.end(), {what, {}});
    it->second.push_back(where);
  }

  // " (the first place and N more)", or "" when the places are the whole file.
  static std::string placesText(const std::vector<std::string>& places) {
    if (places.empty() || places.front().empty()) return "";
    std::string text = " (" + places.front();
    if (places.size() > 1) text += " and " + std::to_string(places.size() - 1) + " more";
    return text + ")";
  }

  std::vector<int> rootNodes() const {
    if (model_.defaultScene >= 0) {
      if (static_cast<std::size_t>(model_.defaultScene) >= model_.scenes.size()) {
        throw error("default scene ", model_.defaultScene, " does not exist (the file has ", model_.scenes.size(), ")");
      }
      return model_.scenes[static_cast<std::size_t>(model_.defaultScene)].nodes;
    }
    if (!model_.scenes.empty()) return model_.scenes[0].nodes;
    // No scene at all: every node that is nobody's child is a root.
    std::vector<bool> isChild(model_.nodes.size(), false);
    for (const tinygltf::Node& node : model_.nodes) {
      for (int child : node.children) {
        if (child >= 0 && static_cast<std::size_t>(child) < isChild.size()) isChild[static_cast<std::size_t>(child)] = true;
      }
    }
    std::vector<int> roots;
    for (std::size_t i = 0; i < model_.nodes.size(); ++i) {
      if (!isChild[i]) roots.push_back(static_cast<int>(i));
    }
    return roots;
  }

  static glm::dmat4 localTransform(const tinygltf::Node& node) {
    if (!node.matrix.empty()) {
      if (node.matrix.size() != 16) throw error("matrix has ", node.matrix.size(), " numbers, expected 16");
      return glm::make_mat4(node.matrix.data());  // glTF matrices are column-major, like glm's
    }
    glm::dmat4 transform(1.0);
    if (!node.translation.empty()) {
      if (node.translation.size() != 3) throw error("translation has ", node.translation.size(), " numbers");
      transform = glm::translate(transform, glm::make_vec3(node.translation.data()));
    }
    if (!node.rotation.empty()) {
      if (node.rotation.size() != 4) throw error("rotation has ", node.rotation.size(), " numbers");
      const auto& r = node.rotation;
      // glTF quaternions are (x, y, z, w); glm's constructor takes w first.
      transform *= glm::mat4_cast(glm::normalize(glm::dquat(r[3], r[0], r[1], r[2])));
    }
    if (!node.scale.empty()) {
      if (node.scale.size() != 3) throw error("scale has ", node.scale.size(), " numbers");
      transform = glm::scale(transform, glm::make_vec3(node.scale.data()));
    }
    return transform;
  }

  void visitNode(int index, const glm::dmat4& parent, std::vector<bool>& onPath, int depth) {
    // Recursion depth is bounded so that a hostile chain of nodes cannot overflow the stack.
    constexpr int kMaxDepth = 1000;
    if (depth > kMaxDepth) throw error("node hierarchy deeper than ", kMaxDepth);
    if (index < 0 || static_cast<std::size_t>(index) >= model_.nodes.size()) {
      throw error("node ", index, " does not exist (the file has ", model_.nodes.size(), ")");
    }
    const auto slot = static_cast<std::size_t>(index);
    if (onPath[slot]) throw error("node ", index, " is its own ancestor");
    onPath[slot] = true;
    const tinygltf::Node& node = model_.nodes[slot];
    const glm::dmat4 world = withContext("node " + std::to_string(index) + ": ", [&] {
      const glm::dmat4 transform = parent * localTransform(node);
      for (int c = 0; c < 4; ++c) {
        for (int r = 0; r < 4; ++r) {
          if (!std::isfinite(transform[c][r])) throw error("transform is not finite");
        }
      }
      return transform;
    });
    if (node.mesh >= 0) {
      if (static_cast<std::size_t>(node.mesh) >= model_.meshes.size()) {
        throw error("node ", index, ": mesh ", node.mesh, " does not exist (the file has ", model_.meshes.size(), ")");
      }
      const tinygltf::Mesh& mesh = model_.meshes[static_cast<std::size_t>(node.mesh)];
      for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
        std::string context = "mesh " + std::to_string(node.mesh) + (mesh.name.empty() ? "" : " '" + mesh.name + "'") +
                              " primitive " + std::to_string(p) + ": ";
        withContext(context, [&] { addPrimitive(mesh, node.mesh, p, world); });
      }
    }
    if (node.camera >= 0) withContext("node " + std::to_string(index) + ": ", [&] { addCamera(node.camera, world); });
    const auto lightExtension = node.extensions.find("KHR_lights_punctual");
    if (lightExtension != node.extensions.end()) {
      withContext("node " + std::to_string(index) + ": ", [&] { addLight(lightExtension->second, world); });
    }
    for (int child : node.children) visitNode(child, world, onPath, depth + 1);
    onPath[slot] = false;
  }

  // A glTF camera looks down its node's -z with +y up (glTF 2.0, "Cameras"). The frame's size sets
  // the aspect ratio, as for a perspective camera's missing aspectRatio: an orthographic camera's
  // ymag is its view's half height and its xmag is not used; docs/scenes.md says so.
  void addCamera(int index, const glm::dmat4& world) {
    if (static_cast<std::size_t>(index) >= model_.cameras.size()) {
      throw error("camera ", index, " does not exist (the file has ", model_.cameras.size(), ")");
    }
    const tinygltf::Camera& source = model_.cameras[static_cast<std::size_t>(index)];
    const std::string label = "camera " + std::to_string(index) + (source.name.empty() ? "" : " '" + source.name + "'");
    Camera camera;
    if (source.type == "perspective") {
      const double yfov = source.perspective.yfov;
      if (!(yfov > 0.0 && yfov < 3.14159)) throw error(label, ": yfov ", yfov, " is not in (0, pi) radians");
      camera.verticalFovDegrees = static_cast<float>(glm::degrees(yfov));
    } else {  // "orthographic": tinygltf refuses any other type
      const double ymag = source.orthographic.ymag;
      if (!(ymag > 0.0 && ymag < 1e30)) throw error(label, ": ymag ", ymag, " is not in (0, 1e30)");
      camera.projection = Camera::Projection::Orthographic;
      camera.orthographicHalfHeight = static_cast<float>(ymag);
    }
    const glm::dvec3 position(world * glm::dvec4(0, 0, 0, 1));
    const glm::dvec3 forward(world * glm::dvec4(0, 0, -1, 0));
    const glm::dvec3 up(world * glm::dvec4(0, 1, 0, 0));
    if (!(glm::length(forward) > 0.0 && glm::length(up) > 0.0 && glm::length(glm::cross(forward, up)) > 0.0)) {
      throw error(label, ": its node's transform collapses the view direction");
    }
    camera.position = glm::vec3(position);
    camera.up = glm::vec3(glm::normalize(up));
    fileCameras_.push_back({source.name.empty() ? "camera" + std::to_string(index) : source.name, camera,
                            glm::normalize(forward)});
  }

  // The file's cameras after the bounding-box presets, under their own names (or
  // "cameraN"), a file camera winning over a preset of the same name; the first one in node order
  // is also "default" unless one is named so.
  void addCameras() {
    scene_.cameras = scene_.presetCameras = standardCameras(scene_.boundsMin(), scene_.boundsMax());
    // The viewer orbits around a camera's target: put it on the view ray, as far as the scene's centre.
    const glm::vec3 centre = 0.5f * (scene_.boundsMin() + scene_.boundsMax());
    for (FileCamera& file : fileCameras_) {
      const float distance = std::max(glm::length(centre - file.camera.position), 1e-3f);
      file.camera.target = file.camera.position + distance * glm::vec3(file.forward);
      scene_.cameras[file.name] = file.camera;
    }
    const bool namedDefault =
        std::any_of(fileCameras_.begin(), fileCameras_.end(), [](const FileCamera& c) { return c.name == "default"; });
    if (!fileCameras_.empty() && !namedDefault) scene_.cameras["default"] = fileCameras_.front().camera;
  }

  // KHR_lights_punctual: point, spot and directional lights. Its photometric units become
  // radiometric ones at 683 lm/W (the luminous efficacy at 555 nm, as glTF exporters convert
  // watts): a point or spot light's candela to W/sr, a directional light's lux to W/m^2. A point or
  // spot light's `range` ends its light smoothly at that distance (kernel/lights.h); tinygltf reads
  // an absent range as 0, so 0 means none, as absent.
  void addLight(const tinygltf::Value& extension, const glm::dmat4& world) {
    if (!extension.IsObject() || !extension.Has("light") || !extension.Get("light").IsNumber()) {
      throw error("KHR_lights_punctual has no light index");
    }
    const int index = extension.Get("light").GetNumberAsInt();
    if (index < 0 || static_cast<std::size_t>(index) >= model_.lights.size()) {
      throw error("light ", index, " does not exist (the file has ", model_.lights.size(), ")");
    }
    const tinygltf::Light& source = model_.lights[static_cast<std::size_t>(index)];
    const std::string label = "light " + std::to_string(index) + (source.name.empty() ? "" : " '" + source.name + "'");
    constexpr double kLumensPerWatt = 683.0;
    glm::dvec3 colour(1.0);
    if (!source.color.empty()) {
      if (source.color.size() != 3) throw error(label, ": color has ", source.color.size(), " numbers, expected 3");
      colour = glm::make_vec3(source.color.data());
    }
    for (int c = 0; c < 3; ++c) {
      if (!(std::isfinite(colour[c]) && colour[c] >= 0.0)) throw error(label, ": color ", colour[c], " is not a finite number >= 0");
    }
    if (!(std::isfinite(source.intensity) && source.intensity >= 0.0)) {
      throw error(label, ": intensity ", source.intensity, " is not a finite number >= 0");
    }
    Light light;
    light.intensity = glm::vec3(colour * (source.intensity / kLumensPerWatt));
    for (int c = 0; c < 3; ++c) {
      if (!std::isfinite(light.intensity[c])) {
        throw error(label, ": intensity ", source.intensity, " times color ", colour[c], " is beyond a float's range");
      }
    }
    if (source.type != "point" && source.type != "spot" && source.type != "directional") {
      throw error(label, ": unknown type '", source.type, "'");
    }
    light.type = source.type == "point" ? Light::Type::Point
                 : source.type == "spot" ? Light::Type::Spot
                                         : Light::Type::Directional;
    light.position = glm::vec3(world * glm::dvec4(0, 0, 0, 1));
    if (light.type != Light::Type::Point) {
      const glm::dvec3 direction(world * glm::dvec4(0, 0, -1, 0));  // spots and suns shine down their node's -z
      if (!(glm::length(direction) > 0.0)) throw error(label, ": its node's transform collapses its direction");
      light.direction = glm::vec3(glm::normalize(direction));
    }
    if (!(std::isfinite(source.range) && source.range >= 0.0)) {
      throw error(label, ": range ", source.range, " is not a finite number > 0");
    }
    // A positive range below float's smallest normal (it would round to 0, "no range") is taken as
    // that: the light then reaches nothing.
    if (light.type != Light::Type::Directional && source.range > 0.0) {
      light.range = std::max(static_cast<float>(source.range), std::numeric_limits<float>::min());
    }
    if (light.type == Light::Type::Spot) {
      const double inner = source.spot.innerConeAngle;
      const double outer = source.spot.outerConeAngle;
      // The extension's ranges: 0 <= inner < outer <= pi / 2.
      if (!(inner >= 0.0 && inner < outer && outer <= 1.5707964)) {
        throw error(label, ": spot cone angles (inner ", inner, ", outer ", outer, ") are not 0 <= inner < outer <= pi/2");
      }
      light.innerConeAngle = static_cast<float>(inner);
      light.outerConeAngle = static_cast<float>(outer);
    }
    scene_.lights.push_back(light);
  }

  std::vector<std::uint32_t> triangleIndices(const tinygltf::Primitive& primitive, int mode, std::size_t vertexCount) const {
    std::vector<std::uint32_t> source;
    if (primitive.indices >= 0) {
      const tinygltf::Accessor* accessor =
          static_cast<std::size_t>(primitive.indices) < model_.accessors.size()
              ? &model_.accessors[static_cast<std::size_t>(primitive.indices)]
              : nullptr;
      if (accessor && (accessor->componentType == TINYGLTF_COMPONENT_TYPE_FLOAT || accessor->normalized ||
                       accessor->componentType == TINYGLTF_COMPONENT_TYPE_BYTE ||
                       accessor->componentType == TINYGLTF_COMPONENT_TYPE_SHORT)) {
        throw error("indices (accessor ", primitive.indices, ") must be unsigned integers");
      }
      const AccessorValues values = readAccessor(model_, primitive.indices, TINYGLTF_TYPE_SCALAR);
      source.reserve(values.count);
      for (double value : values.values) {
        if (value >= static_cast<double>(vertexCount)) {
          throw error("index ", static_cast<std::uint64_t>(value), " out of range (", vertexCount, " vertices)");
        }
        source.push_back(static_cast<std::uint32_t>(value));
      }
    } else {
      if (vertexCount > 0xffffffffu) throw error("too many vertices");
      source.resize(vertexCount);
      for (std::size_t i = 0; i < vertexCount; ++i) source[i] = static_cast<std::uint32_t>(i);
    }
    std::vector<std::uint32_t> triangles;
    if (mode == TINYGLTF_MODE_TRIANGLES) {
      if (source.size() % 3 != 0) throw error(source.size(), " indices, not a multiple of 3");
      triangles = std::move(source);
    } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
      // glTF: triangle i is (i, i + 1 + i % 2, i + 2 - i % 2), keeping the winding.
      for (std::size_t i = 0; i + 2 < source.size(); ++i) {
        triangles.insert(triangles.end(), {source[i], source[i + 1 + i % 2], source[i + 2 - i % 2]});
      }
    } else {  // TINYGLTF_MODE_TRIANGLE_FAN
      for (std::size_t i = 1; i + 1 < source.size(); ++i) {
        triangles.insert(triangles.end(), {source[i], source[i + 1], source[0]});
      }
    }
    return triangles;
  }

  // Attribute `name` of `type` (with `count` elements when given), all finite; empty when the
  // primitive lacks it.
  AccessorValues attribute(const tinygltf::Primitive& primitive, const std::string& name, int type,
                           std::optional<std::size_t> count) const {
    const auto found = primitive.attributes.find(name);
    if (found == primitive.attributes.end()) return {};
    return withContext(name + ": ", [&] {
      AccessorValues values = readAccessor(model_, found->second, type);
      if (count && values.count != *count) throw error(values.count, " elements, POSITION has ", *count);
      for (std::size_t i = 0; i < values.values.size(); ++i) {
        if (!std::isfinite(values.values[i])) {
          throw error("element ", i / static_cast<std::size_t>(values.components), " is not finite");
        }
      }
      return values;
    });
  }

  // COLOR_0 as glTF allows it: RGB or RGBA, float or normalised unsigned bytes or shorts, in
  // [0, 1]; empty when the primitive has none.
  AccessorValues vertexColours(const tinygltf::Primitive& primitive, std::size_t count) const {
    const auto found = primitive.attributes.find("COLOR_0");
    if (found == primitive.attributes.end()) return {};
    const int index = found->second;
    bool rgb = false;  // a missing accessor: readAccessor below names it
    if (index >= 0 && static_cast<std::size_t>(index) < model_.accessors.size()) {
      const tinygltf::Accessor& accessor = model_.accessors[static_cast<std::size_t>(index)];
      if (accessor.type != TINYGLTF_TYPE_VEC3 && accessor.type != TINYGLTF_TYPE_VEC4) {
        throw error("COLOR_0: accessor ", index, ": type ", typeName(accessor.type), ", expected VEC3 or VEC4");
      }
      const bool normalisedInteger = accessor.normalized && (accessor.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                                                             accessor.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);
      if (!(accessor.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT && !accessor.normalized) && !normalisedInteger) {
        throw error("COLOR_0: accessor ", index, " must hold floats, or unsigned bytes or shorts with normalized true");
      }
      rgb = accessor.type == TINYGLTF_TYPE_VEC3;
    }
    AccessorValues colours = attribute(primitive, "COLOR_0", rgb ? TINYGLTF_TYPE_VEC3 : TINYGLTF_TYPE_VEC4, count);
    for (std::size_t i = 0; i < colours.values.size(); ++i) {
      if (!(colours.values[i] >= 0.0 && colours.values[i] <= 1.0)) {
        throw error("COLOR_0: element ", i / static_cast<std::size_t>(colours.components), " has ", exactly(colours.values[i]),
                    ", outside [0, 1]");
      }
    }
    return colours;
  }

  void addPrimitive(const tinygltf::Mesh& sourceMesh, int meshIndex, std::size_t primitiveIndex, const glm::dmat4& world) {
    const tinygltf::Primitive& primitive = sourceMesh.primitives[primitiveIndex];
    const int mode = primitive.mode < 0 ? TINYGLTF_MODE_TRIANGLES : primitive.mode;
    if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP && mode != TINYGLTF_MODE_TRIANGLE_FAN) {
      return;  // points and lines: nothing to shade
    }
    if (!primitive.attributes.contains("POSITION")) throw error("no POSITION attribute");
    const AccessorValues positions = attribute(primitive, "POSITION", TINYGLTF_TYPE_VEC3, std::nullopt);
    const std::size_t count = positions.count;
    const std::vector<double> normals = attribute(primitive, "NORMAL", TINYGLTF_TYPE_VEC3, count).values;
    const std::vector<double> uvs = attribute(primitive, "TEXCOORD_0", TINYGLTF_TYPE_VEC2, count).values;
    const std::vector<double> tangents = attribute(primitive, "TANGENT", TINYGLTF_TYPE_VEC4, count).values;
    const AccessorValues colours = vertexColours(primitive, count);

    const glm::dmat3 linear(world);
    const double determinant = glm::determinant(linear);
    // A node scaled to nothing (a common way to hide a part) has no area to draw.
    if (!(std::abs(determinant) > 0.0)) return;
    const glm::dmat3 normalMatrix = glm::transpose(glm::inverse(linear));
    const double handedness = determinant < 0.0 ? -1.0 : 1.0;

    Mesh mesh;
    mesh.name = sourceMesh.name.empty() ? "mesh " + std::to_string(meshIndex) : sourceMesh.name;
    if (sourceMesh.primitives.size() > 1) mesh.name += " #" + std::to_string(primitiveIndex);
    mesh.material = materialIndex(primitive.material);
    const Material& material = scene_.materials[static_cast<std::size_t>(mesh.material)];
    if (uvs.empty() && material.normalTexture >= 0) {
      throw error("material ", primitive.material, " '", material.name, "' has a normalTexture but no TEXCOORD_0 to map it");
    }
    mesh.indices = triangleIndices(primitive, mode, count);
    if (mesh.indices.empty()) return;
    // A mirroring transform turns counter-clockwise triangles clockwise: turn them back.
    if (determinant < 0.0) {
      for (std::size_t i = 0; i + 2 < mesh.indices.size(); i += 3) std::swap(mesh.indices[i + 1], mesh.indices[i + 2]);
    }

    mesh.vertices.resize(count);
    bool badNormals = false;
    bool badTangents = false;
    for (std::size_t i = 0; i < count; ++i) {
      Vertex& v = mesh.vertices[i];
      const glm::dvec3 position = glm::make_vec3(&positions.values[3 * i]);
      v.position = glm::vec3(world * glm::dvec4(position, 1.0));
      if (!std::isfinite(v.position.x) || !std::isfinite(v.position.y) || !std::isfinite(v.position.z)) {
        throw error("POSITION ", i, " is not finite after the node transforms");
      }
      v.uv = uvs.empty() ? glm::vec2(0.0f) : glm::vec2(glm::make_vec2(&uvs[2 * i]));
      // Beyond 1e6 a float uv has no texel left to resolve, and scaled it overflows.
      if (!(std::abs(v.uv.x) <= kLargestUv && std::abs(v.uv.y) <= kLargestUv)) {
        throw error("TEXCOORD_0 ", i, " (", uvs[2 * i], ", ", uvs[2 * i + 1], ") is beyond +-1e6");
      }
      if (!colours.values.empty()) {
        const double* rgba = &colours.values[static_cast<std::size_t>(colours.components) * i];
        v.colour = glm::vec4(glm::vec3(glm::make_vec3(rgba)), colours.components == 4 ? static_cast<float>(rgba[3]) : 1.0f);
      }
      if (!normals.empty()) {
        const glm::dvec3 n = normalMatrix * glm::make_vec3(&normals[3 * i]);
        const double length = glm::length(n);
        if (length > 1e-12 && std::isfinite(length)) {
          v.normal = glm::vec3(n / length);
        } else {
          v.normal = glm::vec3(0.0f);  // repaired below from the faces around it
          badNormals = true;
        }
      }
      if (!tangents.empty()) {
        const glm::dvec3 t = linear * glm::make_vec3(&tangents[4 * i]);
        const double w = tangents[4 * i + 3] < 0.0 ? -handedness : handedness;
        v.tangent = glm::vec4(glm::vec3(t), static_cast<float>(w));
      }
    }
    if (normals.empty()) {
      makeFlatShaded(mesh);  // glTF: no normals means flat shading
    } else if (badNormals) {
      const std::vector<glm::vec3> repaired = smoothNormals(mesh);
      for (std::size_t i = 0; i < count; ++i) {
        if (mesh.vertices[i].normal == glm::vec3(0.0f)) mesh.vertices[i].normal = repaired[i];
      }
    }
    if (!tangents.empty() && !normals.empty()) {
      // The transforms (and the file) may leave tangents off perpendicular: Gram-Schmidt again.
      for (Vertex& v : mesh.vertices) {
        const glm::vec3 t = glm::vec3(v.tangent) - v.normal * glm::dot(v.normal, glm::vec3(v.tangent));
        const float length = glm::length(t);
        if (length > 1e-6f && std::isfinite(length)) {
          v.tangent = glm::vec4(t / length, v.tangent.w);
        } else {
          badTangents = true;
          v.tangent = glm::vec4(0.0f);
        }
      }
      if (badTangents) {
        Mesh generated = mesh;
        generateTangents(generated);
        for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
          if (mesh.vertices[i].tangent == glm::vec4(0.0f)) mesh.vertices[i].tangent = generated.vertices[i].tangent;
        }
      }
    } else {
      generateTangents(mesh);
    }
    scene_.meshes.push_back(std::move(mesh));
  }

  int materialIndex(int index) {
    if (index >= 0) {
      if (static_cast<std::size_t>(index) >= model_.materials.size()) {
        throw error("material ", index, " does not exist (the file has ", model_.materials.size(), ")");
      }
      return index;
    }
    if (defaultMaterial_ < 0) {
      // The glTF default material: every property at its default (white, metallic 1, roughness 1).
      Material fallback;
      fallback.name = "default";
      fallback.baseColour = glm::vec4(1.0f);
      fallback.metallic = 1.0f;
      fallback.roughness = 1.0f;
      fallback.specular = kGltfSpecular;
      defaultMaterial_ = static_cast<int>(scene_.materials.size());
      scene_.materials.push_back(fallback);
    }
    return defaultMaterial_;
  }

  // Scene texture for glTF texture `index` in the given colour space, decoded once per image and
  // colour space.
  int texture(int index, bool srgb) {
    if (index < 0 || static_cast<std::size_t>(index) >= model_.textures.size()) {
      throw error("texture ", index, " does not exist (the file has ", model_.textures.size(), ")");
    }
    const int source = model_.textures[static_cast<std::size_t>(index)].source;
    // A texture may leave its image to an extension (KHR_texture_basisu, EXT_texture_webp): glint
    // reads none of those, so the material is drawn without it (noteUnreadFeatures says so). When
    // such an extension is required the file is refused before this (gltf_precheck.h).
    if (source < 0) return -1;
    if (static_cast<std::size_t>(source) >= model_.images.size()) {
      throw error("texture ", index, " has no image it can read (source ", source, ")");
    }
    const int sampler = model_.textures[static_cast<std::size_t>(index)].sampler;
    const auto key = std::make_tuple(source, srgb, sampler);
    if (const auto found = textureOf_.find(key); found != textureOf_.end()) return found->second;
    const TextureSampler settings = withContext("texture " + std::to_string(index) + ": ", [&] { return textureSampler(sampler); });
    Texture made = toTexture(model_.images[static_cast<std::size_t>(source)], source, srgb);
    made.sampler = settings;
    scene_.textures.push_back(std::move(made));
    const int result = static_cast<int>(scene_.textures.size()) - 1;
    textureOf_[key] = result;
    return result;
  }

  // glTF sampler `index` (-1: none, glTF's repeat and the viewer's filters): OpenGL's enums, which
  // glTF uses, each checked.
  TextureSampler textureSampler(int index) const {
    TextureSampler sampler;
    if (index < 0) return sampler;
    if (static_cast<std::size_t>(index) >= model_.samplers.size()) {
      throw error("sampler ", index, " does not exist (the file has ", model_.samplers.size(), ")");
    }
    const tinygltf::Sampler& source = model_.samplers[static_cast<std::size_t>(index)];
    auto wrap = [&](int mode, const char* field) {
      switch (mode) {
        case 10497: return TextureSampler::Wrap::Repeat;
        case 33071: return TextureSampler::Wrap::ClampToEdge;
        case 33648: return TextureSampler::Wrap::MirroredRepeat;
        default: throw error("sampler ", index, " ", field, " ", mode, " is not a wrap mode (10497, 33071 or 33648)");
      }
    };
    sampler.wrapS = wrap(source.wrapS, "wrapS");
    sampler.wrapT = wrap(source.wrapT, "wrapT");
    if (source.magFilter == 9728) {
      sampler.magnifyNearest = true;
    } else if (source.magFilter != -1 && source.magFilter != 9729) {
      throw error("sampler ", index, " magFilter ", source.magFilter, " is not 9728 (NEAREST) or 9729 (LINEAR)");
    }
    switch (source.minFilter) {
      case -1: break;  // none given: trilinear
      case 9728: sampler.minifyNearest = true; sampler.mipmap = TextureSampler::Mipmap::None; break;
      case 9729: sampler.mipmap = TextureSampler::Mipmap::None; break;
      case 9984: sampler.minifyNearest = true; sampler.mipmap = TextureSampler::Mipmap::Nearest; break;
      case 9985: sampler.mipmap = TextureSampler::Mipmap::Nearest; break;
      case 9986: sampler.minifyNearest = true; break;
      case 9987: break;
      default: throw error("sampler ", index, " minFilter ", source.minFilter, " is not one of OpenGL's (9728, 9729, 9984 to 9987)");
    }
    return sampler;
  }

  int optionalTexture(int index, bool srgb, const char* what) {
    if (index < 0) return -1;
    return withContext(std::string(what) + ": ", [&] { return texture(index, srgb); });
  }

  // A texture's KHR_texture_transform (its members' types are checked with the file's JSON,
  // gltf_field_types.cpp); the identity without one.
  static UvTransform uvTransform(const tinygltf::ExtensionMap& extensions, const char* texture) {
    UvTransform transform;
    const auto found = extensions.find("KHR_texture_transform");
    if (found == extensions.end() || !found->second.IsObject()) return transform;
    const tinygltf::Value& value = found->second;
    auto pair = [&](const char* member, glm::vec2& out) {
      if (!value.Has(member)) return;
      const tinygltf::Value& array = value.Get(member);
      if (array.ArrayLen() != 2) {
        throw error(texture, ".KHR_texture_transform.", member, " has ", array.ArrayLen(), " numbers, expected 2");
      }
      for (int k = 0; k < 2; ++k) out[k] = static_cast<float>(array.Get(k).GetNumberAsDouble());
    };
    pair("offset", transform.offset);
    pair("scale", transform.scale);
    if (value.Has("rotation")) transform.rotation = static_cast<float>(value.Get("rotation").GetNumberAsDouble());
    // Bounded, so that the transformed uv of any sane uv stays finite in float (scale 1e38 would
    // take uv 1 to infinity, which the renderers would sample differently).
    constexpr float kLargest = 1e6f;
    const glm::mat3x2 matrix = transform.matrix();
    for (int column = 0; column < 3; ++column) {
      for (int row = 0; row < 2; ++row) {
        if (!(std::abs(matrix[column][row]) <= kLargest)) {
          throw error(texture, ".KHR_texture_transform must be finite, with offset and scale within 1e6");
        }
      }
    }
    return transform;
  }

  static float unitFactor(double value, const char* field) {
    if (!(value >= 0.0 && value <= 1.0)) throw error(field, " must be in [0, 1], got ", exactly(value));
    return static_cast<float>(value);
  }

  Material material(const tinygltf::Material& source, int index) {
    Material m;
    m.specular = kGltfSpecular;
    m.name = source.name.empty() ? "material " + std::to_string(index) : source.name;
    const tinygltf::PbrMetallicRoughness& pbr = source.pbrMetallicRoughness;
    if (pbr.baseColorFactor.size() == 4) {
      for (int c = 0; c < 4; ++c) m.baseColour[c] = unitFactor(pbr.baseColorFactor[static_cast<std::size_t>(c)], "baseColorFactor");
    } else if (!pbr.baseColorFactor.empty()) {
      throw error("baseColorFactor has ", pbr.baseColorFactor.size(), " numbers, expected 4");
    }
    m.metallic = unitFactor(pbr.metallicFactor, "metallicFactor");
    m.roughness = unitFactor(pbr.roughnessFactor, "roughnessFactor");
    m.baseColourTexture = optionalTexture(pbr.baseColorTexture.index, true, "baseColorTexture");
    m.metallicRoughnessTexture = optionalTexture(pbr.metallicRoughnessTexture.index, false, "metallicRoughnessTexture");
    m.normalTexture = optionalTexture(source.normalTexture.index, false, "normalTexture");
    m.baseColourUv = uvTransform(pbr.baseColorTexture.extensions, "baseColorTexture");
    m.metallicRoughnessUv = uvTransform(pbr.metallicRoughnessTexture.extensions, "metallicRoughnessTexture");
    m.normalUv = uvTransform(source.normalTexture.extensions, "normalTexture");
    m.occlusionUv = uvTransform(source.occlusionTexture.extensions, "occlusionTexture");
    m.emissiveUv = uvTransform(source.emissiveTexture.extensions, "emissiveTexture");
    m.normalScale = static_cast<float>(source.normalTexture.scale);
    // Beyond 1e4 the perturbed normals' slopes, and their squares in the normal-map moments,
    // overflow a float.
    if (!(std::abs(m.normalScale) <= 1e4f)) {
      throw error("normalTexture.scale ", source.normalTexture.scale, " is not within +-1e4");
    }
    m.occlusionStrength = unitFactor(source.occlusionTexture.strength, "occlusionTexture.strength");
    m.occlusionTexture = optionalTexture(source.occlusionTexture.index, false, "occlusionTexture");
    if (source.emissiveFactor.size() == 3) {
      for (int c = 0; c < 3; ++c) m.emissive[c] = unitFactor(source.emissiveFactor[static_cast<std::size_t>(c)], "emissiveFactor");
    } else if (!source.emissiveFactor.empty()) {
      throw error("emissiveFactor has ", source.emissiveFactor.size(), " numbers, expected 3");
    }
    // KHR_materials_emissive_strength: glTF keeps emissiveFactor in [0, 1]; this scales it past 1.
    const auto emissiveStrength = source.extensions.find("KHR_materials_emissive_strength");
    if (emissiveStrength != source.extensions.end() && emissiveStrength->second.IsObject() &&
        emissiveStrength->second.Has("emissiveStrength")) {
      const double strength = emissiveStrength->second.Get("emissiveStrength").GetNumberAsDouble();
      // Finite as a float too: the renderers multiply in float, and 0 * inf would be NaN.
      if (!(std::isfinite(static_cast<float>(strength)) && strength >= 0.0)) {
        throw error("KHR_materials_emissive_strength.emissiveStrength must be a finite number >= 0 (at most 3.4e38), got ",
                    strength);
      }
      m.emissive *= static_cast<float>(strength);  // finite: the factor is at most 1
    }
    m.emissiveTexture = optionalTexture(source.emissiveTexture.index, true, "emissiveTexture");
    m.doubleSided = source.doubleSided;
    if (source.alphaMode == "MASK") {
      m.alphaMode = Material::AlphaMode::Mask;
    } else if (source.alphaMode == "BLEND") {
      m.alphaMode = Material::AlphaMode::Blend;
    } else if (source.alphaMode != "OPAQUE") {
      throw error("alphaMode must be OPAQUE, MASK or BLEND, got '", source.alphaMode, "'");
    }
    if (!(std::isfinite(source.alphaCutoff) && source.alphaCutoff >= 0.0)) {
      throw error("alphaCutoff must be a finite number >= 0, got ", source.alphaCutoff);
    }
    m.alphaCutoff = static_cast<float>(source.alphaCutoff);
    const auto clearcoat = source.extensions.find("KHR_materials_clearcoat");
    if (clearcoat != source.extensions.end() && clearcoat->second.IsObject()) {
      m.clearcoat = withContext("KHR_materials_clearcoat.", [&] { return readClearcoat(clearcoat->second); });
    }
    readGlint(source, m, index);
    return m;
  }

  // KHR_materials_clearcoat (its members' types are checked with the file's JSON,
  // gltf_field_types.cpp): factors in [0, 1], textures as the core's, a normal map's scale as
  // normalTexture's.
  Material::Clearcoat readClearcoat(const tinygltf::Value& extension) {
    Material::Clearcoat coat;
    auto factor = [&](const char* member, float fallback) {
      return extension.Has(member) ? unitFactor(extension.Get(member).GetNumberAsDouble(), member) : fallback;
    };
    coat.factor = factor("clearcoatFactor", 0.0f);
    coat.roughness = factor("clearcoatRoughnessFactor", 0.0f);
    auto textureOf = [&](const char* member, bool srgb, UvTransform& transform) {
      if (!extension.Has(member)) return -1;
      const tinygltf::Value& info = extension.Get(member);
      if (!info.Has("index")) throw error(member, ".index is missing");
      if (info.Has("extensions") && info.Get("extensions").IsObject()) {
        const tinygltf::Value::Object& object = info.Get("extensions").Get<tinygltf::Value::Object>();
        transform = uvTransform(tinygltf::ExtensionMap(object.begin(), object.end()), member);
      }
      return optionalTexture(info.Get("index").GetNumberAsInt(), srgb, member);
    };
    coat.texture = textureOf("clearcoatTexture", false, coat.uv);
    coat.roughnessTexture = textureOf("clearcoatRoughnessTexture", false, coat.roughnessUv);
    coat.normalTexture = textureOf("clearcoatNormalTexture", false, coat.normalUv);
    if (extension.Has("clearcoatNormalTexture") && extension.Get("clearcoatNormalTexture").Has("scale")) {
      const double scale = extension.Get("clearcoatNormalTexture").Get("scale").GetNumberAsDouble();
      if (!(std::abs(scale) <= 1e4)) throw error("clearcoatNormalTexture.scale ", scale, " is not within +-1e4");
      coat.normalScale = static_cast<float>(scale);
    }
    return coat;
  }

  // The material's glint layer and specular target: from EXT_materials_glint, else from
  // extras.glint, the older form, or extras.glint_specular (docs/scenes.md, "Glint parameters in
  // glTF"). Both are read from the file's original JSON: tinygltf's own Value drops empty objects
  // ("glint": {} still enables a layer) and keeps only 32-bit integers. Extras are free-form: only
  // their "glint" and "glint_specular" members concern glint.
  void readGlint(const tinygltf::Material& source, Material& m, int index) {
    const std::string label = "material " + std::to_string(index) + (source.name.empty() ? "" : " '" + source.name + "'");
    const GlintTextureSource textures{
        model_.textures.size(), [&](int gltfIndex) { return texture(gltfIndex, false); },
        [&](const std::string& what, const std::string& field) {
          note(what, label + " " + kGlintExtensionName + "." + field);
        }};
    const std::optional<nlohmann::json> extension = memberOf(source.extensions_json_string, kGlintExtensionName);
    const std::optional<nlohmann::json> glint = memberOf(source.extras_json_string, "glint");
    const std::optional<nlohmann::json> specular = memberOf(source.extras_json_string, "glint_specular");
    GltfGlint read{m.glint, m.specular};
    if (extension) {
      read = withContext(std::string(kGlintExtensionName) + ": ", [&] {
        return readGlintLayer(*extension, GlintSpelling::Extension, m.roughness, m.specular, textures);
      });
      if (glint || specular) {
        note(std::string(glint ? "extras.glint" : "extras.glint_specular") +
                 " is not read where a material has EXT_materials_glint, whose values win",
             label);
      }
    } else if (glint) {
      read = withContext("extras.glint: ", [&] {
        return readGlintLayer(*glint, GlintSpelling::Extras, m.roughness, m.specular, textures);
      });
      extrasGlintMaterials_.push_back(label);
    } else if (specular) {
      read.specular = withContext("extras.glint_specular: ", [&] { return readGlintSpecularTarget(*specular, m.specular); });
    }
    if (read.layer.enabled) validateGlintLayer(read.layer, scene_.textures.size());
    m.glint = read.layer;
    m.specular = read.specular;
  }

  struct FileCamera {
    std::string name;
    Camera camera;  // its target is set once the scene's bounds are known (addCameras)
    glm::dvec3 forward;
  };

  const tinygltf::Model& model_;
  Scene scene_;
  std::vector<FileCamera> fileCameras_;
  std::map<std::tuple<int, bool, int>, int> textureOf_;  // (image, sRGB, sampler) -> scene texture
  // What the file uses and glint does not render: each kind in the order first met, with its places.
  std::vector<std::pair<std::string, std::vector<std::string>>> unread_;
  std::vector<std::string> extrasGlintMaterials_;  // the materials whose layer came from extras.glint
  int defaultMaterial_ = -1;
};

// tinygltf's file reader for a buffer's or an image's uri, through glint's (file_io.h): a uri that
// names a folder is refused as one ("is a directory, expected a file"), where tinygltf's own reader
// takes the folder's stream size for the file's and fails to allocate it.
bool readReferencedFile(std::vector<unsigned char>* out, std::string* err, const std::string& path, void*) {
  try {
    const std::vector<std::byte> bytes = readFile(path);
    const auto* first = reinterpret_cast<const unsigned char*>(bytes.data());
    out->assign(first, first + bytes.size());
    return true;
  } catch (const std::exception& e) {
    // tinygltf's message names the file already ("File read error : PATH : "): the reason alone.
    std::string reason = e.what();
    if (reason.rfind(path + ": ", 0) == 0) reason.erase(0, path.size() + 2);
    if (err) *err += reason + "\n";
    return false;
  }
}

// Little-endian 32-bit word at `at` (the caller checks the range).
std::uint32_t word32(std::span<const std::byte> bytes, std::size_t at) {
  return static_cast<std::uint32_t>(bytes[at]) | static_cast<std::uint32_t>(bytes[at + 1]) << 8 |
         static_cast<std::uint32_t>(bytes[at + 2]) << 16 | static_cast<std::uint32_t>(bytes[at + 3]) << 24;
}

// The file's bytes with its JSON replaced by `document`: the JSON itself for a .gltf; for a .glb
// the JSON chunk, padded with spaces to 4 bytes as the container requires, and the header's
// lengths rewritten, the chunks after it kept (readGltfJson has checked the header).
std::string withJson(std::span<const std::byte> bytes, bool binary, const nlohmann::json& document) {
  std::string json = document.dump();
  if (!binary) return json;
  const std::size_t rest = 20 + word32(bytes, 12);
  json.append((4 - json.size() % 4) % 4, ' ');
  const auto put = [](std::string& out, std::uint32_t value) {
    for (int b = 0; b < 4; ++b) out += static_cast<char>((value >> (8 * b)) & 0xFF);
  };
  std::string out = "glTF";
  put(out, 2);
  put(out, static_cast<std::uint32_t>(20 + json.size() + (bytes.size() - rest)));
  put(out, static_cast<std::uint32_t>(json.size()));
  out += "JSON";
  out += json;
  out.append(reinterpret_cast<const char*>(bytes.data()) + rest, bytes.size() - rest);
  return out;
}

}  // namespace

Scene loadGltf(const fs::path& path) {
  try {
    std::error_code ignored;
    if (!fs::exists(path, ignored)) throw error("no such file");
    if (!fs::is_regular_file(path, ignored)) throw error("not a regular file");
    return loadGltf(readFile(path), path.stem().string(), path.parent_path());
  } catch (const std::exception& e) {  // Error, and an allocation failure reading the file
    throw Error(path.string() + ": " + e.what());
  }
}

Scene loadGltf(std::span<const std::byte> bytes, const std::string& name, const fs::path& baseDirectory) {
  try {
    // On the file's own JSON, before tinygltf reads it (gltf_field_types.h, gltf_precheck.h); a file
    // whose JSON does not parse is left to tinygltf's message.
    const bool binary = bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;
    // The container's version (the header's second word): 2 for glTF 2.0, 1 for glTF 1.0's.
    if (binary && bytes.size() >= 8 && word32(bytes, 4) != 2) {
      const std::uint32_t version = word32(bytes, 4);
      if (version == 1) throw error("binary glTF 1.0 is not supported (glint reads glTF 2.0)");
      throw error("binary glTF container version ", version, " is not supported (glint reads glTF 2.0)");
    }
    // The file with its whole-number indices made integers, its Draco primitives' indices and its
    // meshopt-compressed views' placements set aside (gltf_compression.h).
    std::optional<std::string> rewritten;
    if (std::optional<nlohmann::json> document = readGltfJson(bytes)) {
      checkGltfVersion(*document);
      const bool wholeNumbers = wholeNumberIndicesToIntegers(*document);
      checkGltfFieldTypes(*document);
      checkRequiredExtensions(*document);
      checkBufferViewRanges(*document);
      const bool dracoIndices = setAsideDracoIndices(*document);
      const bool meshoptViews = setAsideMeshoptViews(*document, binary);
      if (wholeNumbers || dracoIndices || meshoptViews) rewritten = withJson(bytes, binary, *document);
    }
    if (rewritten) bytes = {reinterpret_cast<const std::byte*>(rewritten->data()), rewritten->size()};
    // tinygltf takes a 32-bit length.
    if (bytes.size() > std::numeric_limits<unsigned int>::max()) throw error(bytes.size(), " bytes, more than 4 GiB");
    tinygltf::TinyGLTF loader;
    loader.SetStoreOriginalJSONForExtrasAndExtensions(true);  // for extras.glint, read with nlohmann::json
    loader.SetImageLoader(decodeImage, nullptr);
    tinygltf::FsCallbacks files{};
    files.FileExists = &tinygltf::FileExists;
    files.ExpandFilePath = &tinygltf::ExpandFilePath;
    files.ReadWholeFile = &readReferencedFile;
    files.WriteWholeFile = &tinygltf::WriteWholeFile;
    loader.SetFsCallbacks(files);
    tinygltf::Model model;
    std::string errors;
    std::string warnings;
    const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
    const auto length = static_cast<unsigned int>(bytes.size());
    // The content decides, not the extension (binary, above): a .gltf that is really binary still loads.
    const bool loaded =
        binary ? loader.LoadBinaryFromMemory(&model, &errors, &warnings, data, length, baseDirectory.string())
               : loader.LoadASCIIFromString(&model, &errors, &warnings, reinterpret_cast<const char*>(data), length,
                                            baseDirectory.string());
    if (!loaded) {
      const std::string reason = oneLine(errors.empty() ? warnings : errors);
      throw Error(reason.empty() ? "cannot parse the file" : reason);
    }
    decodeCompressedMeshes(model);
    return GltfReader(model).read(name);
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {  // allocation failures and the like from a hostile file
    throw Error(e.what());
  }
}

}  // namespace glint::scene
