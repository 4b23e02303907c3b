#include "scene/gltf_compression.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <limits>
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
// Likewise GLINT_MESHOPT.
#ifndef GLINT_MESHOPT
#define GLINT_MESHOPT 0
#endif
#if GLINT_MESHOPT
#include <meshoptimizer.h>
#endif

#include "glint/error.h"

namespace glint::scene {

bool decodesDraco() { return GLINT_DRACO != 0; }
bool decodesMeshopt() { return GLINT_MESHOPT != 0; }

namespace {

constexpr const char* kDraco = "KHR_draco_mesh_compression";
constexpr const char* kSetAsideIndices = "glintIndices";
constexpr const char* kMeshopt = "EXT_meshopt_compression";
constexpr const char* kSetAsideFallback = "glintFallback";

// A whole-number field of a JSON object within [least, int32's largest] (`fallback` when absent and
// `fallback` >= 0): what tinygltf stores as an int, so that the decoding pass reads it unchanged.
std::int64_t integerField(const nlohmann::json& object, const char* name, std::int64_t fallback, std::int64_t least,
                          const std::string& what) {
  const auto found = object.find(name);
  if (found == object.end() && fallback >= 0) return fallback;
  const std::int64_t largest = std::numeric_limits<std::int32_t>::max();
  if (found == object.end() || !found->is_number_integer() || found->get<std::int64_t>() < least ||
      found->get<std::int64_t>() > largest) {
    throw Error(what + ": " + name + " must be a whole number in [" + std::to_string(least) + ", " + std::to_string(largest) + "]");
  }
  return found->get<std::int64_t>();
}

bool isMeshoptFallback(const nlohmann::json& buffer) {
  if (!buffer.is_object() || !buffer.contains("extensions") || !buffer["extensions"].is_object()) return false;
  const auto found = buffer["extensions"].find(kMeshopt);
  return found != buffer["extensions"].end() && found->is_object() && found->contains("fallback") && (*found)["fallback"] == true;
}

// An EXT_meshopt_compression object checked as the extension and its codecs require: the mode and
// filter by name, the stride each takes, count x byteStride filling the view (of `viewLength`
// bytes, element stride `viewStride`, 0 where it has none).
void checkMeshoptExtension(const nlohmann::json& extension, std::int64_t viewLength, std::int64_t viewStride,
                           const std::string& what) {
  const std::string mode = extension.contains("mode") && extension["mode"].is_string() ? extension["mode"].get<std::string>() : "";
  const std::string filter =
      !extension.contains("filter") ? "NONE" : extension["filter"].is_string() ? extension["filter"].get<std::string>() : "";
  if (mode != "ATTRIBUTES" && mode != "TRIANGLES" && mode != "INDICES") {
    throw Error(what + ": mode must be \"ATTRIBUTES\", \"TRIANGLES\" or \"INDICES\", got " + extension.value("mode", nlohmann::json()).dump());
  }
  if (filter != "NONE" && filter != "OCTAHEDRAL" && filter != "QUATERNION" && filter != "EXPONENTIAL") {
    throw Error(what + ": filter must be \"NONE\", \"OCTAHEDRAL\", \"QUATERNION\" or \"EXPONENTIAL\", got " + extension["filter"].dump());
  }
  const std::int64_t count = integerField(extension, "count", -1, 0, what);
  const std::int64_t stride = integerField(extension, "byteStride", -1, 1, what);
  // The codecs' own limits: vertex elements are a multiple of 4 bytes up to 256, indices 2 or 4 bytes.
  const bool attributes = mode == "ATTRIBUTES";
  if (attributes ? (stride % 4 != 0 || stride > 256) : (stride != 2 && stride != 4)) {
    throw Error(what + ": byteStride " + std::to_string(stride) + (attributes ? " is not a multiple of 4 up to 256" : " is not 2 or 4") +
                " for mode " + mode);
  }
  if (attributes && viewStride != 0 && viewStride != stride) {
    throw Error(what + ": byteStride " + std::to_string(stride) + " is not the buffer view's, " + std::to_string(viewStride));
  }
  if (mode == "TRIANGLES" && count % 3 != 0) throw Error(what + ": count " + std::to_string(count) + " is not a whole number of triangles");
  if (filter != "NONE" && !attributes) throw Error(what + ": filter " + filter + " applies to mode ATTRIBUTES only");
  if ((filter == "OCTAHEDRAL" && stride != 4 && stride != 8) || (filter == "QUATERNION" && stride != 8)) {
    throw Error(what + ": filter " + filter + " cannot have byteStride " + std::to_string(stride));
  }
  if (count * stride != viewLength) {
    throw Error(what + ": count " + std::to_string(count) + " x byteStride " + std::to_string(stride) + " is not the buffer view's byteLength, " +
                std::to_string(viewLength));
  }
}

}  // namespace

bool setAsideMeshoptViews(nlohmann::json& document, bool binary) {
  if (!decodesMeshopt()) return false;
  const auto buffers = document.find("buffers");
  const auto views = document.find("bufferViews");
  if (buffers == document.end() || !buffers->is_array() || views == document.end() || !views->is_array()) return false;
  const std::size_t bufferCount = buffers->size();
  auto compressed = [](const nlohmann::json& view) -> const nlohmann::json* {
    if (!view.is_object() || !view.contains("extensions") || !view["extensions"].is_object()) return nullptr;
    const auto found = view["extensions"].find(kMeshopt);
    return found == view["extensions"].end() ? nullptr : &*found;
  };
  // The buffers without data that only compressed views lie in, and those flagged as fallbacks (a
  // GLB's first buffer without a uri is its BIN chunk, which holds data, unless it is flagged).
  std::vector<int> uses(bufferCount, 0);  // 1: compressed views only, 2: some other view too
  for (const nlohmann::json& view : *views) {
    if (!view.is_object() || !view.contains("buffer") || !view["buffer"].is_number_integer()) continue;
    const std::int64_t b = view["buffer"].get<std::int64_t>();
    if (b < 0 || static_cast<std::uint64_t>(b) >= bufferCount) continue;
    uses[static_cast<std::size_t>(b)] = std::max(uses[static_cast<std::size_t>(b)], compressed(view) != nullptr ? 1 : 2);
  }
  std::vector<bool> placeholder(bufferCount, false);
  for (std::size_t b = 0; b < bufferCount; ++b) {
    const nlohmann::json& buffer = (*buffers)[b];
    if (!buffer.is_object() || buffer.contains("uri")) continue;
    placeholder[b] = isMeshoptFallback(buffer) || (uses[b] == 1 && !(binary && b == 0));
  }
  bool changed = false;
  for (std::size_t v = 0; v < views->size(); ++v) {
    nlohmann::json& view = (*views)[v];
    const std::string what = "buffer view " + std::to_string(v) + ": " + kMeshopt;
    const nlohmann::json* found = compressed(view);
    const std::int64_t viewBuffer = view.is_object() && view.contains("buffer") && view["buffer"].is_number_integer()
                                        ? view["buffer"].get<std::int64_t>() : -1;
    const bool inPlaceholder = viewBuffer >= 0 && static_cast<std::uint64_t>(viewBuffer) < bufferCount &&
                               placeholder[static_cast<std::size_t>(viewBuffer)];
    if (found == nullptr) {
      if (inPlaceholder) {
        throw Error("buffer view " + std::to_string(v) + ": its buffer " + std::to_string(viewBuffer) + " is a " + kMeshopt +
                    " fallback, which holds no data, and the view is not compressed");
      }
      continue;
    }
    nlohmann::json& extension = view["extensions"][kMeshopt];
    if (!extension.is_object()) throw Error(what + " must be an object");
    checkMeshoptExtension(extension, integerField(view, "byteLength", -1, 1, "buffer view " + std::to_string(v)),
                          integerField(view, "byteStride", 0, 0, "buffer view " + std::to_string(v)), what);
    const std::int64_t buffer = integerField(extension, "buffer", -1, 0, what);
    if (static_cast<std::uint64_t>(buffer) >= bufferCount) throw Error(what + ": buffer " + std::to_string(buffer) + " does not exist");
    if (placeholder[static_cast<std::size_t>(buffer)]) {
      throw Error(what + ": its stream's buffer " + std::to_string(buffer) + " is a fallback, which holds no data");
    }
    const std::int64_t length = integerField(extension, "byteLength", -1, 1, what);
    const std::int64_t offset = integerField(extension, "byteOffset", 0, 0, what);
    const std::int64_t available = integerField((*buffers)[static_cast<std::size_t>(buffer)], "byteLength", -1, 1,
                                                "buffer " + std::to_string(buffer));
    if (offset > available || length > available - offset) {
      throw Error(what + ": bytes " + std::to_string(offset) + " to " + std::to_string(offset + length) + " run past buffer " +
                  std::to_string(buffer) + " (" + std::to_string(available) + " bytes)");
    }
    extension[kSetAsideFallback] = {{"byteLength", view["byteLength"]}};
    view["buffer"] = buffer;
    view["byteOffset"] = offset;
    view["byteLength"] = length;
    changed = true;
  }
  // A placeholder buffer: one byte of its own, which no view reads any more.
  for (std::size_t b = 0; b < bufferCount; ++b) {
    if (!placeholder[b]) continue;
    (*buffers)[b]["uri"] = "data:application/octet-stream;base64,AA==";
    (*buffers)[b]["byteLength"] = 1;
    changed = true;
  }
  return changed;
}

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

#if GLINT_DRACO || GLINT_MESHOPT

namespace {

// A buffer of its own holding `bytes`; its index.
int addDecodedBuffer(tinygltf::Model& model, std::vector<unsigned char> bytes) {
  tinygltf::Buffer buffer;
  buffer.name = "decoded";
  buffer.data = std::move(bytes);
  model.buffers.push_back(std::move(buffer));
  return static_cast<int>(model.buffers.size()) - 1;
}

}  // namespace

#endif

#if GLINT_MESHOPT

namespace {

std::string stringField(const tinygltf::Value& object, const char* name, const char* fallback) {
  return object.Has(name) && object.Get(name).IsString() ? object.Get(name).Get<std::string>() : fallback;
}

// The bytes that buffer view `view` (pointed by setAsideMeshoptViews at its compressed data, its
// extension checked there) would hold uncompressed: the extension's codec (mode) and then its
// filter, over count elements of byteStride bytes, which fill the view's own byteLength.
void decodeMeshoptView(tinygltf::Model& model, tinygltf::BufferView& view, const tinygltf::Value& extension) {
  const std::string mode = stringField(extension, "mode", "");
  const std::string filter = stringField(extension, "filter", "NONE");
  const auto count = static_cast<std::size_t>(extension.Get("count").GetNumberAsInt());
  const auto stride = static_cast<std::size_t>(extension.Get("byteStride").GetNumberAsInt());
  const std::size_t size = count * stride;  // both below 2^31: checked on the JSON
  if (view.buffer < 0 || static_cast<std::size_t>(view.buffer) >= model.buffers.size()) throw Error("its buffer does not exist");
  const std::vector<unsigned char>& source = model.buffers[static_cast<std::size_t>(view.buffer)].data;
  if (view.byteOffset > source.size() || view.byteLength > source.size() - view.byteOffset) {
    throw Error("its compressed bytes run past their buffer");
  }
  // A stream expands by less than this (the vertex codec: 2 bits at least for a group of 16 bytes;
  // the triangle codec: a byte at least a triangle; an index sequence: a byte at least an index):
  // a count beyond it is not the stream's, and is not allocated.
  const std::size_t expansion = mode == "ATTRIBUTES" ? 64 : mode == "TRIANGLES" ? 12 : 4;
  if (size > expansion * view.byteLength + 256) throw Error("count " + std::to_string(count) + " is more than its stream can hold");
  const unsigned char* compressed = model.buffers[static_cast<std::size_t>(view.buffer)].data.data() + view.byteOffset;
  std::vector<unsigned char> decoded(size);
  const int status = mode == "ATTRIBUTES" ? meshopt_decodeVertexBuffer(decoded.data(), count, stride, compressed, view.byteLength)
                     : mode == "TRIANGLES" ? meshopt_decodeIndexBuffer(decoded.data(), count, stride, compressed, view.byteLength)
                                           : meshopt_decodeIndexSequence(decoded.data(), count, stride, compressed, view.byteLength);
  if (status != 0) throw Error("the stream does not decode (meshoptimizer's code " + std::to_string(status) + ")");
  if (filter == "OCTAHEDRAL") meshopt_decodeFilterOct(decoded.data(), count, stride);
  if (filter == "QUATERNION") meshopt_decodeFilterQuat(decoded.data(), count, stride);
  if (filter == "EXPONENTIAL") meshopt_decodeFilterExp(decoded.data(), count, stride);
  view.buffer = addDecodedBuffer(model, std::move(decoded));
  view.byteOffset = 0;
  view.byteLength = size;
}

void decodeMeshoptViews(tinygltf::Model& model) {
  for (std::size_t v = 0; v < model.bufferViews.size(); ++v) {
    tinygltf::BufferView& view = model.bufferViews[v];
    const auto meshopt = view.extensions.find(kMeshopt);
    if (meshopt == view.extensions.end() || !meshopt->second.Has(kSetAsideFallback)) continue;
    try {
      decodeMeshoptView(model, view, meshopt->second);
    } catch (const Error& e) {
      throw Error("buffer view " + std::to_string(v) + ": " + kMeshopt + ": " + e.what());
    }
  }
}

}  // namespace

#else

namespace {
void decodeMeshoptViews(tinygltf::Model&) {}
}  // namespace

#endif

#if GLINT_DRACO

namespace {

// A buffer of its own for `bytes`, and a buffer view over all of it; the view's index.
int addDecodedView(tinygltf::Model& model, const void* bytes, std::size_t size) {
  std::vector<unsigned char> data(size);
  if (size > 0) std::memcpy(data.data(), bytes, size);
  tinygltf::BufferView view;
  view.buffer = addDecodedBuffer(model, std::move(data));
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
  decodeMeshoptViews(model);
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

void decodeCompressedMeshes(tinygltf::Model& model) { decodeMeshoptViews(model); }

#endif

}  // namespace glint::scene
