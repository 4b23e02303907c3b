#include "scene/gltf_field_types.h"

#include <array>
#include <cmath>
#include <algorithm>
#include <limits>
#include <utility>
#include <vector>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "glint/error.h"

namespace glint::scene {

namespace {

enum class JsonType { Boolean, Number, Index, String };

// A property glint reads, as a path of member names from the document's root: "name[]" is an
// array of which every element goes on along the path, "*" every member of an object.
struct FieldType {
  std::string_view path;
  JsonType type;
};

// glTF 2.0 schema types; indices, counts, offsets and enumerations are integers >= 0. The first
// mistyped property in this table's order is the one reported.
constexpr std::array kFieldTypes = {
    FieldType{"extensionsRequired[]", JsonType::String},
    FieldType{"extensions.KHR_lights_punctual.lights[].name", JsonType::String},
    FieldType{"extensions.KHR_lights_punctual.lights[].type", JsonType::String},
    FieldType{"extensions.KHR_lights_punctual.lights[].color[]", JsonType::Number},
    FieldType{"extensions.KHR_lights_punctual.lights[].intensity", JsonType::Number},
    FieldType{"extensions.KHR_lights_punctual.lights[].range", JsonType::Number},
    FieldType{"extensions.KHR_lights_punctual.lights[].spot.innerConeAngle", JsonType::Number},
    FieldType{"extensions.KHR_lights_punctual.lights[].spot.outerConeAngle", JsonType::Number},
    FieldType{"scene", JsonType::Index},
    FieldType{"scenes[].nodes[]", JsonType::Index},
    FieldType{"nodes[].name", JsonType::String},
    FieldType{"nodes[].children[]", JsonType::Index},
    FieldType{"nodes[].mesh", JsonType::Index},
    FieldType{"nodes[].camera", JsonType::Index},
    FieldType{"nodes[].matrix[]", JsonType::Number},
    FieldType{"nodes[].translation[]", JsonType::Number},
    FieldType{"nodes[].rotation[]", JsonType::Number},
    FieldType{"nodes[].scale[]", JsonType::Number},
    FieldType{"nodes[].extensions.KHR_lights_punctual.light", JsonType::Index},
    FieldType{"cameras[].name", JsonType::String},
    FieldType{"cameras[].type", JsonType::String},
    FieldType{"cameras[].perspective.yfov", JsonType::Number},
    FieldType{"cameras[].orthographic.ymag", JsonType::Number},
    FieldType{"meshes[].name", JsonType::String},
    FieldType{"meshes[].primitives[].attributes.*", JsonType::Index},
    FieldType{"meshes[].primitives[].indices", JsonType::Index},
    FieldType{"meshes[].primitives[].material", JsonType::Index},
    FieldType{"meshes[].primitives[].mode", JsonType::Index},
    FieldType{"materials[].name", JsonType::String},
    FieldType{"materials[].pbrMetallicRoughness.baseColorFactor[]", JsonType::Number},
    FieldType{"materials[].pbrMetallicRoughness.metallicFactor", JsonType::Number},
    FieldType{"materials[].pbrMetallicRoughness.roughnessFactor", JsonType::Number},
    FieldType{"materials[].pbrMetallicRoughness.baseColorTexture.index", JsonType::Index},
    FieldType{"materials[].pbrMetallicRoughness.metallicRoughnessTexture.index", JsonType::Index},
    FieldType{"materials[].normalTexture.index", JsonType::Index},
    FieldType{"materials[].normalTexture.scale", JsonType::Number},
    FieldType{"materials[].occlusionTexture.index", JsonType::Index},
    FieldType{"materials[].occlusionTexture.strength", JsonType::Number},
    FieldType{"materials[].extensions.KHR_materials_emissive_strength.emissiveStrength", JsonType::Number},
    FieldType{"materials[].emissiveTexture.index", JsonType::Index},
    FieldType{"materials[].extensions.KHR_materials_clearcoat.clearcoatFactor", JsonType::Number},
    FieldType{"materials[].extensions.KHR_materials_clearcoat.clearcoatRoughnessFactor", JsonType::Number},
    FieldType{"materials[].extensions.KHR_materials_clearcoat.clearcoatTexture.index", JsonType::Index},
    FieldType{"materials[].extensions.KHR_materials_clearcoat.clearcoatTexture.extensions.KHR_texture_transform.offset[]", JsonType::Number},
    FieldType{"materials[].extensions.KHR_materials_clearcoat.clearcoatTexture.extensions.KHR_texture_transform.rotation", JsonType::Number},
    FieldType{"materials[].extensions.KHR_materials_clearcoat.clearcoatTexture.extensions.KHR_texture_transform.scale[]", JsonType::Number},
    FieldType{"materials[].extensions.KHR_materials_clearcoat.clearcoatTexture.extensions.KHR_texture_transform.texCoord", JsonType::Index},
    FieldType{"materials[].extensions.KHR_materials_clearcoat.clearcoatRoughnessTexture.index", JsonType::Index},
    FieldType{"materials[].extensions.KHR_materials_clearcoat.clearcoatRoughnessTexture.extensions.KHR_texture_transform.offset[]", JsonType::Number},
    FieldType{"materials[].extensions.KHR_materials_clearcoat.clearcoatRoughnessTexture.extensions.KHR_texture_transform.rotation", JsonType::Number},
    FieldType{"materials[].extensions.KHR_materials_clearcoat.clearcoatRoughnessTexture.extensions.KHR_texture_transform.scale[]", JsonType::Number},
    FieldType{"materials[].extensions.KHR_materials_clearcoat.clearcoatRoughnessTexture.extensions.KHR_texture_transform.texCoord", JsonType::Index},
    FieldType{"materials[].extensions.KHR_materials_clearcoat.clearcoatNormalTexture.index", JsonType::Index},
    FieldType{"materials[].extensions.KHR_materials_clearcoat.clearcoatNormalTexture.extensions.KHR_texture_transform.offset[]", JsonType::Number},
    FieldType{"materials[].extensions.KHR_materials_clearcoat.clearcoatNormalTexture.extensions.KHR_texture_transform.rotation", JsonType::Number},
    FieldType{"materials[].extensions.KHR_materials_clearcoat.clearcoatNormalTexture.extensions.KHR_texture_transform.scale[]", JsonType::Number},
    FieldType{"materials[].extensions.KHR_materials_clearcoat.clearcoatNormalTexture.extensions.KHR_texture_transform.texCoord", JsonType::Index},
    FieldType{"materials[].extensions.KHR_materials_clearcoat.clearcoatNormalTexture.scale", JsonType::Number},
    FieldType{"materials[].pbrMetallicRoughness.baseColorTexture.extensions.KHR_texture_transform.offset[]", JsonType::Number},
    FieldType{"materials[].pbrMetallicRoughness.baseColorTexture.extensions.KHR_texture_transform.rotation", JsonType::Number},
    FieldType{"materials[].pbrMetallicRoughness.baseColorTexture.extensions.KHR_texture_transform.scale[]", JsonType::Number},
    FieldType{"materials[].pbrMetallicRoughness.baseColorTexture.extensions.KHR_texture_transform.texCoord", JsonType::Index},
    FieldType{"materials[].pbrMetallicRoughness.metallicRoughnessTexture.extensions.KHR_texture_transform.offset[]", JsonType::Number},
    FieldType{"materials[].pbrMetallicRoughness.metallicRoughnessTexture.extensions.KHR_texture_transform.rotation", JsonType::Number},
    FieldType{"materials[].pbrMetallicRoughness.metallicRoughnessTexture.extensions.KHR_texture_transform.scale[]", JsonType::Number},
    FieldType{"materials[].pbrMetallicRoughness.metallicRoughnessTexture.extensions.KHR_texture_transform.texCoord", JsonType::Index},
    FieldType{"materials[].normalTexture.extensions.KHR_texture_transform.offset[]", JsonType::Number},
    FieldType{"materials[].normalTexture.extensions.KHR_texture_transform.rotation", JsonType::Number},
    FieldType{"materials[].normalTexture.extensions.KHR_texture_transform.scale[]", JsonType::Number},
    FieldType{"materials[].normalTexture.extensions.KHR_texture_transform.texCoord", JsonType::Index},
    FieldType{"materials[].occlusionTexture.extensions.KHR_texture_transform.offset[]", JsonType::Number},
    FieldType{"materials[].occlusionTexture.extensions.KHR_texture_transform.rotation", JsonType::Number},
    FieldType{"materials[].occlusionTexture.extensions.KHR_texture_transform.scale[]", JsonType::Number},
    FieldType{"materials[].occlusionTexture.extensions.KHR_texture_transform.texCoord", JsonType::Index},
    FieldType{"materials[].emissiveTexture.extensions.KHR_texture_transform.offset[]", JsonType::Number},
    FieldType{"materials[].emissiveTexture.extensions.KHR_texture_transform.rotation", JsonType::Number},
    FieldType{"materials[].emissiveTexture.extensions.KHR_texture_transform.scale[]", JsonType::Number},
    FieldType{"materials[].emissiveTexture.extensions.KHR_texture_transform.texCoord", JsonType::Index},
    FieldType{"materials[].emissiveFactor[]", JsonType::Number},
    FieldType{"materials[].doubleSided", JsonType::Boolean},
    FieldType{"materials[].alphaMode", JsonType::String},
    FieldType{"materials[].alphaCutoff", JsonType::Number},
    FieldType{"textures[].source", JsonType::Index},
    FieldType{"images[].uri", JsonType::String},
    FieldType{"images[].mimeType", JsonType::String},
    FieldType{"images[].bufferView", JsonType::Index},
    FieldType{"accessors[].bufferView", JsonType::Index},
    FieldType{"accessors[].byteOffset", JsonType::Index},
    FieldType{"accessors[].componentType", JsonType::Index},
    FieldType{"accessors[].normalized", JsonType::Boolean},
    FieldType{"accessors[].count", JsonType::Index},
    FieldType{"accessors[].type", JsonType::String},
    FieldType{"accessors[].sparse.count", JsonType::Index},
    FieldType{"accessors[].sparse.indices.bufferView", JsonType::Index},
    FieldType{"accessors[].sparse.indices.byteOffset", JsonType::Index},
    FieldType{"accessors[].sparse.indices.componentType", JsonType::Index},
    FieldType{"accessors[].sparse.values.bufferView", JsonType::Index},
    FieldType{"accessors[].sparse.values.byteOffset", JsonType::Index},
    FieldType{"bufferViews[].buffer", JsonType::Index},
    FieldType{"bufferViews[].byteOffset", JsonType::Index},
    FieldType{"bufferViews[].byteLength", JsonType::Index},
    FieldType{"bufferViews[].byteStride", JsonType::Index},
    FieldType{"buffers[].uri", JsonType::String},
    FieldType{"buffers[].byteLength", JsonType::Index},
};

// tinygltf 2.7 reads an integer property only when the JSON number is written as an integer (3.0
// counts as absent), and into an int (4294967297 becomes 1): both are refused here.
constexpr std::int64_t kLargestIndex = std::numeric_limits<std::int32_t>::max();

bool isIndex(const nlohmann::json& value) {
  if (value.is_number_unsigned()) return value.get<std::uint64_t>() <= static_cast<std::uint64_t>(kLargestIndex);
  if (value.is_number_integer()) return value.get<std::int64_t>() >= 0 && value.get<std::int64_t>() <= kLargestIndex;
  return false;
}

void expectType(const nlohmann::json& value, JsonType type, const std::string& location) {
  switch (type) {
    case JsonType::Boolean:
      if (!value.is_boolean()) throw Error(location + " must be true or false, got " + describeJsonValue(value));
      return;
    case JsonType::Number:
      if (!value.is_number()) throw Error(location + " must be a number, got " + describeJsonValue(value));
      return;
    case JsonType::Index:
      if (!isIndex(value)) {
        throw Error(location + " must be an integer in [0, " + std::to_string(kLargestIndex) + "], got " + describeJsonValue(value));
      }
      return;
    case JsonType::String:
      if (!value.is_string()) throw Error(location + " must be a string, got " + describeJsonValue(value));
      return;
  }
}

void expectObject(const nlohmann::json& value, const std::string& location) {
  if (!value.is_object()) throw Error(location + " must be an object, got " + describeJsonValue(value));
}

// A member name as the message shows it: control characters (a newline, a terminal escape) as '?',
// so that the message stays one harmless line.
std::string memberLocation(const std::string& parent, const std::string& name) {
  std::string shown = name;
  for (char& c : shown) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
  }
  return parent.empty() ? shown : parent + "." + shown;
}

// Checks `path` (the rest of a FieldType's path) inside `object`, at `location`.
void checkPath(const nlohmann::json& object, std::string_view path, JsonType type, const std::string& location) {
  const std::size_t dot = path.find('.');
  const std::string_view segment = path.substr(0, dot);
  const std::string_view rest = dot == std::string_view::npos ? std::string_view() : path.substr(dot + 1);
  // The next step: the value's type at the path's end, an object on the way.
  auto visit = [&](const nlohmann::json& value, const std::string& at) {
    if (rest.empty()) {
      expectType(value, type, at);
    } else {
      expectObject(value, at);
      checkPath(value, rest, type, at);
    }
  };
  if (segment == "*") {
    for (const auto& member : object.items()) visit(member.value(), memberLocation(location, member.key()));
    return;
  }
  const bool array = segment.ends_with("[]");
  const std::string name(array ? segment.substr(0, segment.size() - 2) : segment);
  const auto found = object.find(name);
  if (found == object.end()) return;
  const std::string at = memberLocation(location, name);
  if (!array) {
    visit(*found, at);
    return;
  }
  if (!found->is_array()) throw Error(at + " must be an array, got " + describeJsonValue(*found));
  for (std::size_t i = 0; i < found->size(); ++i) visit((*found)[i], at + "[" + std::to_string(i) + "]");
}

// The values at `path` (a FieldType's path, as checkPath walks it) inside `value` that are whole
// numbers written in floating point, within an index's range, made integers.
bool indicesToIntegers(nlohmann::json& value, std::string_view path) {
  if (path.empty()) {
    if (!value.is_number_float()) return false;
    const double number = value.get<double>();
    if (!(number >= 0.0 && number <= static_cast<double>(kLargestIndex) && number == std::floor(number))) return false;
    value = static_cast<std::int64_t>(number);
    return true;
  }
  if (!value.is_object()) return false;
  const std::size_t dot = path.find('.');
  const std::string_view segment = path.substr(0, dot);
  const std::string_view rest = dot == std::string_view::npos ? std::string_view() : path.substr(dot + 1);
  bool changed = false;
  if (segment == "*") {
    for (auto& member : value.items()) changed = indicesToIntegers(member.value(), rest) || changed;
    return changed;
  }
  const bool array = segment.ends_with("[]");
  const auto found = value.find(std::string(array ? segment.substr(0, segment.size() - 2) : segment));
  if (found == value.end()) return false;
  if (!array) return indicesToIntegers(*found, rest);
  if (!found->is_array()) return false;
  for (nlohmann::json& element : *found) changed = indicesToIntegers(element, rest) || changed;
  return changed;
}

std::uint32_t littleEndian32(const unsigned char* bytes) {
  return static_cast<std::uint32_t>(bytes[0]) | static_cast<std::uint32_t>(bytes[1]) << 8 |
         static_cast<std::uint32_t>(bytes[2]) << 16 | static_cast<std::uint32_t>(bytes[3]) << 24;
}

}  // namespace

std::string describeJsonValue(const nlohmann::json& value) {
  if (value.is_number() || value.is_boolean() || value.is_null()) return value.dump();
  if (value.is_string()) {
    constexpr std::size_t kLongest = 40;
    return value.get_ref<const std::string&>().size() <= kLongest ? "the string " + value.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace)
                                                               : "a string";
  }
  if (value.is_array()) return "an array";
  return "an object";
}

std::optional<nlohmann::json> readGltfJson(std::span<const std::byte> bytes) {
  const auto* data = reinterpret_cast<const char*>(bytes.data());
  std::string_view text(data, bytes.size());
  // A .glb: a 12-byte header ("glTF", version, length), then the JSON chunk's length and type
  // ("JSON") and the JSON itself (glTF 2.0, "GLB File Format Specification").
  if (text.substr(0, 4) == "glTF") {
    const auto* header = reinterpret_cast<const unsigned char*>(data);
    if (bytes.size() < 20 || littleEndian32(header + 16) != 0x4E4F534Au) return std::nullopt;
    const std::uint32_t length = littleEndian32(header + 12);
    if (length > bytes.size() - 20) return std::nullopt;  // a truncated file: tinygltf says so
    text = text.substr(20, length);
  }
  nlohmann::json document = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (document.is_discarded()) return std::nullopt;
  return document;
}

constexpr std::size_t kDeepest = 256;  // glTF itself nests about 8 levels; extras may add some

// The deepest nesting of arrays and objects, walked without recursion: tinygltf parses extras and
// extensions recursively, and a file nested a million levels deep overflows its stack.
std::size_t nestingDepth(const nlohmann::json& document) {
  std::size_t deepest = 0;
  std::vector<std::pair<const nlohmann::json*, std::size_t>> pending{{&document, 1}};
  while (!pending.empty()) {
    const auto [value, depth] = pending.back();
    pending.pop_back();
    if (!value->is_structured()) continue;
    deepest = std::max(deepest, depth);
    for (const nlohmann::json& child : *value) pending.emplace_back(&child, depth + 1);
  }
  return deepest;
}

bool wholeNumberIndicesToIntegers(nlohmann::json& document) {
  if (!document.is_object() || nestingDepth(document) > kDeepest) return false;  // checkGltfFieldTypes refuses it
  bool changed = false;
  for (const FieldType& field : kFieldTypes) {
    if (field.type == JsonType::Index) changed = indicesToIntegers(document, field.path) || changed;
  }
  return changed;
}

void checkGltfFieldTypes(const nlohmann::json& document) {
  if (!document.is_object()) throw Error("the JSON document must be an object, got " + describeJsonValue(document));
  if (nestingDepth(document) > kDeepest) {
    throw Error("the JSON nests arrays and objects more than " + std::to_string(kDeepest) + " levels deep");
  }
  for (const FieldType& field : kFieldTypes) checkPath(document, field.path, field.type, "");
}

}  // namespace glint::scene
