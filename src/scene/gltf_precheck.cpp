#include "scene/gltf_precheck.h"

#include <array>
#include <string>
#include <string_view>

#include "glint/error.h"
#include "scene/gltf_compression.h"
#include "scene/gltf_glint.h"

namespace glint::scene {

namespace {

// The extensions glint honours: its lights are read, quantised attributes are plain normalised or
// integer accessors, which the loader reads, emissive strengths, clear coats and texture transforms
// are read, and so are glint layers (docs/scenes.md); Draco- and meshopt-compressed data are decoded
// where this build has their decoders (gltf_compression.h).
constexpr std::array<std::string_view, 6> kReadExtensions = {"KHR_lights_punctual", "KHR_mesh_quantization",
                                                             "KHR_materials_emissive_strength", "KHR_materials_clearcoat",
                                                             "KHR_texture_transform", kGlintExtensionName};

// A non-negative integer member, or `fallback` when absent; the field-type check has already
// refused members of the wrong type.
double integerMember(const nlohmann::json& object, const char* name, double fallback) {
  const auto it = object.find(name);
  return it != object.end() && it->is_number() ? it->get<double>() : fallback;
}

}  // namespace

void checkGltfVersion(const nlohmann::json& document) {
  if (!document.is_object()) return;
  const auto asset = document.find("asset");
  if (asset == document.end() || !asset->is_object()) return;
  const auto version = asset->find("version");
  if (version == asset->end() || !version->is_string()) return;  // tinygltf names what is missing
  const std::string text = version->get<std::string>();
  if (text.rfind("2.", 0) != 0) {
    // The version as shown: printable and short, so that the message stays one harmless line.
    std::string shown = text.substr(0, 16);
    for (char& c : shown) {
      if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
    }
    throw Error("glTF " + shown + " is not supported (glint reads glTF 2.0)");
  }
}

bool glintReadsExtension(const std::string& name) {
  for (std::string_view known : kReadExtensions) {
    if (name == known) return true;
  }
  return (name == "KHR_draco_mesh_compression" && decodesDraco()) || (name == "EXT_meshopt_compression" && decodesMeshopt());
}

void checkRequiredExtensions(const nlohmann::json& document) {
  const auto required = document.find("extensionsRequired");
  if (required == document.end() || !required->is_array()) return;
  for (const nlohmann::json& extension : *required) {
    if (!extension.is_string()) continue;
    const std::string name = extension.get<std::string>();
    if (!glintReadsExtension(name)) throw Error("requires extension " + name + ", which glint does not support");
  }
}

void checkBufferViewRanges(const nlohmann::json& document) {
  const auto views = document.find("bufferViews");
  const auto buffers = document.find("buffers");
  if (views == document.end() || !views->is_array()) return;
  for (std::size_t i = 0; i < views->size(); ++i) {
    const nlohmann::json& view = (*views)[i];
    if (!view.is_object()) continue;
    const std::string where = "bufferViews[" + std::to_string(i) + "]";
    const double buffer = integerMember(view, "buffer", -1.0);
    if (buffers == document.end() || !buffers->is_array() || !(buffer >= 0.0) ||
        buffer >= static_cast<double>(buffers->size())) {
      throw Error(where + ": buffer " + std::to_string(static_cast<long long>(buffer)) + " does not exist");
    }
    const nlohmann::json& target = (*buffers)[static_cast<std::size_t>(buffer)];
    const double bufferLength = target.is_object() ? integerMember(target, "byteLength", 0.0) : 0.0;
    const double offset = integerMember(view, "byteOffset", 0.0);
    const double length = integerMember(view, "byteLength", 0.0);
    // In double: offsets and lengths up to 2^53 add exactly, far beyond any file.
    if (offset + length > bufferLength) {
      throw Error(where + ": bytes " + std::to_string(static_cast<long long>(offset)) + " to " +
                  std::to_string(static_cast<long long>(offset + length)) + " run past the end of buffer " +
                  std::to_string(static_cast<long long>(buffer)) + " (" +
                  std::to_string(static_cast<long long>(bufferLength)) + " bytes)");
    }
  }
}

}  // namespace glint::scene
