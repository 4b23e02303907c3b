#include "scene/gltf_compression.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

// The desktop build defines GLINT_DRACO 1 (CMakeLists.txt); the page's has no Draco.
#ifndef GLINT_DRACO
#define GLINT_DRACO 0
#endif
#if GLINT_DRACO
#include <draco/compression/decode.h>
#endif

#include "glint/error.h"

namespace glint::scene {

bool decodesDraco() { return GLINT_DRACO != 0; }

namespace {

constexpr const char* kDraco = "KHR_draco_mesh_compression";
constexpr const char* kSetAsideIndices = "glintIndices";

}  // namespace

bool setAsideDracoIndices(nlohmann::json& document) {
  bool moved = false;
  const auto meshes = document.find("meshes");
  if (!decodesDraco() || meshes == document.end() || !meshes->is_array()) return false;
  for (nlohmann::json& mesh : *meshes) {
    if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array()) continue;
    for (nlohmann::json& primitive : mesh["primitives"]) {
      if (!primitive.is_object() || !primitive.contains("indices") || !primitive.contains("extensions")) continue;
      nlohmann::json& extensions = primitive["extensions"];
      if (!extensions.is_object() || !extensions.contains(kDraco) || !extensions[kDraco].is_object()) continue;
      extensions[kDraco][kSetAsideIndices] = primitive["indices"];
      primitive.erase("indices");
      moved = true;
    }
  }
  return moved;
}

#if GLINT_DRACO

namespace {

// A buffer of its own for `bytes`, and a buffer view over all of it; the view's index.
int addDecodedView(tinygltf::Model& model, const void* bytes, std::size_t size) {
  tinygltf::Buffer buffer;
  buffer.name = "decoded";
  buffer.data.resize(size);
  if (size > 0) std::memcpy(buffer.data.data(), bytes, size);
  model.buffers.push_back(std::move(buffer));
  tinygltf::BufferView view;
  view.buffer = static_cast<int>(model.buffers.size()) - 1;
  view.byteOffset = 0;
  view.byteLength = size;
  model.bufferViews.push_back(std::move(view));
  return static_cast<int>(model.bufferViews.size()) - 1;
}

// The largest value of a glTF integer component type, which a normalised one maps to 1; 0 for
// the others.
double normalisedMaximum(int componentType) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: return 127.0;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 255.0;
    case TINYGLTF_COMPONENT_TYPE_SHORT: return 32767.0;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 65535.0;
    default: return 0.0;
  }
}

// Accessor `index` pointed at decoded values (count elements of its type), after checking that
// the stream decoded as many as the accessor declares (the extension requires it).
tinygltf::Accessor& decodedAccessor(tinygltf::Model& model, int index, std::size_t count, const std::string& what) {
  if (index < 0 || static_cast<std::size_t>(index) >= model.accessors.size()) {
    throw Error(what + ": accessor " + std::to_string(index) + " does not exist");
  }
  tinygltf::Accessor& accessor = model.accessors[static_cast<std::size_t>(index)];
  if (accessor.count != count) {
    throw Error(what + ": the stream decodes " + std::to_string(count) + " values, accessor " + std::to_string(index) +
                " declares " + std::to_string(accessor.count));
  }
  return accessor;
}

void decodeDracoPrimitive(tinygltf::Model& model, tinygltf::Primitive& primitive, const tinygltf::Value& extension) {
  if (!extension.IsObject() || !extension.Has("bufferView") || !extension.Get("bufferView").IsNumber()) {
    throw Error(std::string(kDraco) + ": bufferView is missing");
  }
  const int viewIndex = extension.Get("bufferView").GetNumberAsInt();
  if (viewIndex < 0 || static_cast<std::size_t>(viewIndex) >= model.bufferViews.size()) {
    throw Error(std::string(kDraco) + ": buffer view " + std::to_string(viewIndex) + " does not exist");
  }
  const tinygltf::BufferView& view = model.bufferViews[static_cast<std::size_t>(viewIndex)];
  if (view.buffer < 0 || static_cast<std::size_t>(view.buffer) >= model.buffers.size()) {
    throw Error(std::string(kDraco) + ": buffer view " + std::to_string(viewIndex) + " has no buffer");
  }
  const tinygltf::Buffer& buffer = model.buffers[static_cast<std::size_t>(view.buffer)];
  if (view.byteOffset > buffer.data.size() || view.byteLength > buffer.data.size() - view.byteOffset) {
    throw Error(std::string(kDraco) + ": buffer view " + std::to_string(viewIndex) + " runs past its buffer");
  }
  draco::DecoderBuffer stream;
  stream.Init(reinterpret_cast<const char*>(buffer.data.data() + view.byteOffset), view.byteLength);
  draco::Decoder decoder;
  auto decoded = decoder.DecodeMeshFromBuffer(&stream);
  if (!decoded.ok()) {
    throw Error(std::string(kDraco) + ": the stream does not decode (" + decoded.status().error_msg_string() + ")");
  }
  const std::unique_ptr<draco::Mesh> mesh = std::move(decoded).value();
  if (!mesh) throw Error(std::string(kDraco) + ": the stream decodes to no mesh");
  const std::size_t points = mesh->num_points();

  // The triangles, as 32-bit indices: Draco's faces are a triangle list, and the primitive's only
  // connectivity (the points may be reordered).
  if (primitive.mode != TINYGLTF_MODE_TRIANGLES && primitive.mode != -1) {
    throw Error(std::string(kDraco) + ": mode " + std::to_string(primitive.mode) + ", but Draco's faces are triangles (mode 4)");
  }
  std::vector<std::uint32_t> indices;
  indices.reserve(static_cast<std::size_t>(mesh->num_faces()) * 3);
  for (draco::FaceIndex f(0); f < mesh->num_faces(); ++f) {
    for (int corner = 0; corner < 3; ++corner) indices.push_back(mesh->face(f)[corner].value());
  }
  if (extension.Has(kSetAsideIndices) && extension.Get(kSetAsideIndices).IsNumber()) {
    primitive.indices = extension.Get(kSetAsideIndices).GetNumberAsInt();
  }
  if (primitive.indices < 0) throw Error(std::string(kDraco) + ": the primitive has no indices accessor for its triangles");
  {
    tinygltf::Accessor& accessor = decodedAccessor(model, primitive.indices, indices.size(), std::string(kDraco) + " indices");
    accessor.bufferView = addDecodedView(model, indices.data(), indices.size() * sizeof(std::uint32_t));
    accessor.byteOffset = 0;
    accessor.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
    accessor.normalized = false;
    accessor.sparse = {};
  }

  // Each attribute the extension names, as floats: a normalised integer accessor's values mapped to
  // [0, 1] or [-1, 1] as glTF reads them, whether or not the stream's attribute says it is
  // normalised (encoders such as draco3d's leave that flag unset).
  if (!extension.Has("attributes") || !extension.Get("attributes").IsObject()) {
    throw Error(std::string(kDraco) + ": attributes are missing");
  }
  const tinygltf::Value& attributes = extension.Get("attributes");
  for (const std::string& name : attributes.Keys()) {
    const std::string what = std::string(kDraco) + " " + name;
    const auto target = primitive.attributes.find(name);
    if (target == primitive.attributes.end()) throw Error(what + ": the primitive has no such attribute");
    const tinygltf::Value& id = attributes.Get(name);
    if (!id.IsNumber() || id.GetNumberAsInt() < 0) throw Error(what + ": its id is not a non-negative integer");
    const draco::PointAttribute* attribute = mesh->GetAttributeByUniqueId(static_cast<std::uint32_t>(id.GetNumberAsInt()));
    if (!attribute) throw Error(what + ": the stream has no attribute " + std::to_string(id.GetNumberAsInt()));
    tinygltf::Accessor& accessor = decodedAccessor(model, target->second, points, what);
    const int components = tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(accessor.type));
    if (components < 1 || components > 4 || attribute->num_components() != components) {
      throw Error(what + ": the stream's attribute has " + std::to_string(attribute->num_components()) +
                  " components, its accessor " + std::to_string(components));
    }
    std::vector<float> values(points * static_cast<std::size_t>(components));
    for (draco::PointIndex p(0); p < static_cast<std::uint32_t>(points); ++p) {
      if (!attribute->ConvertValue<float>(attribute->mapped_index(p), static_cast<std::int8_t>(components),
                                          &values[p.value() * static_cast<std::size_t>(components)])) {
        throw Error(what + ": its values do not convert to floats");
      }
    }
    const bool integers = attribute->data_type() != draco::DT_FLOAT32 && attribute->data_type() != draco::DT_FLOAT64;
    if (accessor.normalized && integers && !attribute->normalized()) {
      const double largest = normalisedMaximum(accessor.componentType);
      if (largest <= 0.0) throw Error(what + ": normalized, but its accessor's component type is not an integer");
      for (float& v : values) v = static_cast<float>(std::max(v / largest, -1.0));
    }
    accessor.bufferView = addDecodedView(model, values.data(), values.size() * sizeof(float));
    accessor.byteOffset = 0;
    accessor.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
    accessor.normalized = false;
    accessor.sparse = {};
  }
}

}  // namespace

void decodeCompressedMeshes(tinygltf::Model& model) {
  for (std::size_t m = 0; m < model.meshes.size(); ++m) {
    tinygltf::Mesh& mesh = model.meshes[m];
    for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
      tinygltf::Primitive& primitive = mesh.primitives[p];
      const auto draco = primitive.extensions.find(kDraco);
      if (draco == primitive.extensions.end()) continue;
      try {
        decodeDracoPrimitive(model, primitive, draco->second);
      } catch (const Error& e) {
        throw Error("mesh " + std::to_string(m) + (mesh.name.empty() ? "" : " '" + mesh.name + "'") + " primitive " +
                    std::to_string(p) + ": " + e.what());
      }
    }
  }
}

#else

void decodeCompressedMeshes(tinygltf::Model&) {}

#endif

}  // namespace glint::scene
