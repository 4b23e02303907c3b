// Compressed glTF meshes (scene/gltf_compression.h): a box written once with plain accessors and once
// as a KHR_draco_mesh_compression stream (encoded here by Debian's libdraco, lossless: no
// quantisation) loads as the same triangles, corner for corner, its unsigned-byte colours normalised
// as their accessor says; the same box as EXT_meshopt_compression streams (encoded here by Debian's
// libmeshoptimizer, its normals through the octahedral filter) loads as the file that holds the
// same views uncompressed; corrupt streams and mismatched accessors are one line each.
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <type_traits>
#include <vector>

#include <draco/compression/encode.h>
#include <draco/mesh/mesh.h>
#include <gtest/gtest.h>
#include <meshoptimizer.h>
#include <nlohmann/json.hpp>

#include "glint/error.h"
#include "scene/geometry.h"
#include "scene/gltf_loader.h"
#include "test_support.h"

namespace glint {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using scene::Mesh;
using scene::Scene;

struct BoxData {
  Mesh box = scene::makeBox("box", 0, glm::vec3(0.0f), glm::vec3(0.5f, 0.3f, 0.2f), 2.0f);
  std::vector<float> positions, normals, uvs;
  std::vector<std::uint8_t> colours;  // COLOR_0 as normalised unsigned bytes, a colour a face
  BoxData() {
    for (std::size_t i = 0; i < box.vertices.size(); ++i) {
      const scene::Vertex& v = box.vertices[i];
      positions.insert(positions.end(), {v.position.x, v.position.y, v.position.z});
      normals.insert(normals.end(), {v.normal.x, v.normal.y, v.normal.z});
      uvs.insert(uvs.end(), {v.uv.x, v.uv.y});
      const auto face = static_cast<std::uint8_t>(i / 4);
      colours.insert(colours.end(), {static_cast<std::uint8_t>(40 * face), static_cast<std::uint8_t>(255 - 30 * face), 128, 255});
    }
  }
  std::size_t count() const { return box.vertices.size(); }
};

json accessor(int view, int componentType, std::size_t count, const char* type) {
  json a = {{"componentType", componentType}, {"count", count}, {"type", type}};
  if (view >= 0) a["bufferView"] = view;
  return a;
}

json document(const std::string& bin, std::size_t binBytes) {
  return {{"asset", {{"version", "2.0"}}},
          {"buffers", {{{"uri", bin}, {"byteLength", binBytes}}}},
          {"nodes", {{{"mesh", 0}}}},
          {"scenes", {{{"nodes", {0}}}}},
          {"scene", 0}};
}

template <typename T>
void append(std::vector<char>& bytes, const std::vector<T>& values) {
  const char* first = reinterpret_cast<const char*>(values.data());
  bytes.insert(bytes.end(), first, first + values.size() * sizeof(T));
}

fs::path writePlain(const fs::path& folder, const BoxData& data) {
  std::vector<char> bin;
  std::vector<json> views;
  auto view = [&](const auto& values) {
    const std::size_t offset = bin.size();
    append(bin, values);
    views.push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bin.size() - offset}});
  };
  view(data.positions);
  view(data.normals);
  view(data.uvs);
  view(data.box.indices);
  view(data.colours);
  std::ofstream(folder / "plain.bin", std::ios::binary).write(bin.data(), static_cast<std::streamsize>(bin.size()));
  json d = document("plain.bin", bin.size());
  d["bufferViews"] = views;
  d["accessors"] = {accessor(0, 5126, data.count(), "VEC3"), accessor(1, 5126, data.count(), "VEC3"),
                    accessor(2, 5126, data.count(), "VEC2"), accessor(3, 5125, data.box.indices.size(), "SCALAR"),
                    accessor(4, 5121, data.count(), "VEC4")};
  d["accessors"][4]["normalized"] = true;
  d["meshes"] = {{{"primitives",
                   {{{"attributes", {{"POSITION", 0}, {"NORMAL", 1}, {"TEXCOORD_0", 2}, {"COLOR_0", 4}}}, {"indices", 3}}}}}};
  std::ofstream(folder / "plain.gltf") << d.dump();
  return folder / "plain.gltf";
}

// The box as a Draco mesh in the file's point order, sequentially encoded (which keeps it), and the
// attributes' unique ids.
struct DracoBox {
  std::vector<char> stream;
  std::uint32_t position = 0, normal = 0, uv = 0, colour = 0;
};

DracoBox encodeDraco(const BoxData& data) {
  draco::Mesh mesh;
  mesh.set_num_points(static_cast<std::uint32_t>(data.count()));
  auto add = [&]<typename T>(draco::GeometryAttribute::Type type, int components, const std::vector<T>& values) {
    draco::GeometryAttribute attribute;
    // Unsigned bytes as draco3d's encoder writes a colour: not flagged normalised in the stream.
    attribute.Init(type, nullptr, static_cast<std::uint8_t>(components),
                   std::is_same_v<T, float> ? draco::DT_FLOAT32 : draco::DT_UINT8, false,
                   static_cast<std::int64_t>(sizeof(T)) * components, 0);
    const int id = mesh.AddAttribute(attribute, true, static_cast<std::uint32_t>(data.count()));
    for (std::size_t i = 0; i < data.count(); ++i) {
      mesh.attribute(id)->SetAttributeValue(draco::AttributeValueIndex(static_cast<std::uint32_t>(i)),
                                            &values[i * static_cast<std::size_t>(components)]);
    }
    return mesh.attribute(id)->unique_id();
  };
  DracoBox result;
  result.position = add(draco::GeometryAttribute::POSITION, 3, data.positions);
  result.normal = add(draco::GeometryAttribute::NORMAL, 3, data.normals);
  result.uv = add(draco::GeometryAttribute::TEX_COORD, 2, data.uvs);
  result.colour = add(draco::GeometryAttribute::COLOR, 4, data.colours);
  for (std::size_t t = 0; t + 2 < data.box.indices.size(); t += 3) {
    draco::Mesh::Face face;
    for (int k = 0; k < 3; ++k) face[k] = draco::PointIndex(data.box.indices[t + static_cast<std::size_t>(k)]);
    mesh.AddFace(face);
  }
  draco::Encoder encoder;
  encoder.SetEncodingMethod(draco::MESH_SEQUENTIAL_ENCODING);
  draco::EncoderBuffer out;
  const draco::Status status = encoder.EncodeMeshToBuffer(mesh, &out);
  EXPECT_TRUE(status.ok()) << status.error_msg_string();
  result.stream.assign(out.data(), out.data() + out.size());
  return result;
}

fs::path writeDraco(const fs::path& folder, const BoxData& data, const DracoBox& draco, std::size_t streamBytes,
                    std::uint32_t uvId) {
  std::ofstream(folder / "draco.bin", std::ios::binary).write(draco.stream.data(), static_cast<std::streamsize>(streamBytes));
  json d = document("draco.bin", streamBytes);
  d["extensionsUsed"] = {"KHR_draco_mesh_compression"};
  d["extensionsRequired"] = {"KHR_draco_mesh_compression"};
  d["bufferViews"] = {{{"buffer", 0}, {"byteLength", streamBytes}}};
  d["accessors"] = {accessor(-1, 5126, data.count(), "VEC3"), accessor(-1, 5126, data.count(), "VEC3"),
                    accessor(-1, 5126, data.count(), "VEC2"), accessor(-1, 5125, data.box.indices.size(), "SCALAR"),
                    accessor(-1, 5121, data.count(), "VEC4")};
  d["accessors"][4]["normalized"] = true;
  json primitive = {{"attributes", {{"POSITION", 0}, {"NORMAL", 1}, {"TEXCOORD_0", 2}, {"COLOR_0", 4}}}, {"indices", 3}};
  primitive["extensions"]["KHR_draco_mesh_compression"] = {
      {"bufferView", 0},
      {"attributes", {{"POSITION", draco.position}, {"NORMAL", draco.normal}, {"TEXCOORD_0", uvId}, {"COLOR_0", draco.colour}}}};
  d["meshes"] = {{{"primitives", {primitive}}}};
  std::ofstream(folder / "draco.gltf") << d.dump();
  return folder / "draco.gltf";
}

std::string loadError(const fs::path& path) {
  try {
    scene::loadGltf(path);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(GltfCompression, ADracoBoxLoadsAsItsUncompressedTwin) {
  const fs::path folder = test::temporaryFolder("gltf_draco");
  const BoxData data;
  const DracoBox draco = encodeDraco(data);
  ASSERT_GT(draco.stream.size(), 100u);
  const Scene plain = scene::loadGltf(writePlain(folder, data));
  const Scene decoded = scene::loadGltf(writeDraco(folder, data, draco, draco.stream.size(), draco.uv));
  ASSERT_EQ(plain.meshes.size(), 1u);
  ASSERT_EQ(decoded.meshes.size(), 1u);
  const Mesh& a = plain.meshes[0];
  const Mesh& b = decoded.meshes[0];
  ASSERT_EQ(a.indices.size(), data.box.indices.size());
  ASSERT_EQ(b.indices.size(), a.indices.size());
  // Corner for corner: the same triangles, whatever order the vertices were stored in.
  for (std::size_t i = 0; i < a.indices.size(); ++i) {
    const scene::Vertex& va = a.vertices[a.indices[i]];
    const scene::Vertex& vb = b.vertices[b.indices[i]];
    ASSERT_EQ(va.position, vb.position) << "corner " << i;
    ASSERT_EQ(va.normal, vb.normal) << "corner " << i;
    ASSERT_EQ(va.uv, vb.uv) << "corner " << i;
    ASSERT_EQ(va.colour, vb.colour) << "corner " << i;  // normalised as the accessor says
  }
  EXPECT_TRUE(decoded.unreadFeatures.empty());

  // A truncated stream, and an attribute id the stream does not have: one line each, naming the
  // file, the mesh and the primitive.
  const std::string truncated = loadError(writeDraco(folder, data, draco, draco.stream.size() / 2, draco.uv));
  EXPECT_NE(truncated.find("draco.gltf: mesh 0 primitive 0: KHR_draco_mesh_compression: the stream does not decode"),
            std::string::npos)
      << truncated;
  EXPECT_EQ(truncated.find('\n'), std::string::npos) << truncated;
  const std::string missing = loadError(writeDraco(folder, data, draco, draco.stream.size(), 9));
  EXPECT_NE(missing.find("KHR_draco_mesh_compression TEXCOORD_0: the stream has no attribute 9"), std::string::npos) << missing;
}

}  // namespace
}  // namespace glint

namespace glint {
namespace {

// The box's data as a meshopt-compressed file would hold it uncompressed: positions and uvs as
// floats, normals octahedrally encoded (EXT_meshopt_compression's OCTAHEDRAL filter: signed bytes,
// read through KHR_mesh_quantization as a normalised BYTE VEC3 of stride 4), 32-bit indices and
// unsigned-byte colours. Each view: its bytes, element size and count, and how it is compressed.
struct MeshoptView {
  std::vector<unsigned char> bytes;  // uncompressed: what the view holds
  std::vector<unsigned char> compressed;
  std::size_t stride = 0, count = 0;
  const char* mode = "ATTRIBUTES";
  const char* filter = "NONE";
};

std::vector<MeshoptView> meshoptBoxViews(const BoxData& data) {
  auto bytesOf = [](const auto& values) {
    const auto* first = reinterpret_cast<const unsigned char*>(values.data());
    return std::vector<unsigned char>(first, first + values.size() * sizeof(values[0]));
  };
  auto attribute = [](std::vector<unsigned char> bytes, std::size_t stride) {
    MeshoptView view;
    view.bytes = std::move(bytes);
    view.stride = stride;
    view.count = view.bytes.size() / stride;
    view.compressed.resize(meshopt_encodeVertexBufferBound(view.count, stride));
    view.compressed.resize(meshopt_encodeVertexBuffer(view.compressed.data(), view.compressed.size(), view.bytes.data(),
                                                      view.count, stride));
    return view;
  };
  std::vector<MeshoptView> views;
  views.push_back(attribute(bytesOf(data.positions), 12));
  // The normals through the filter: encoded to 8-bit octahedral, then compressed; what a loader
  // must read is the filter's decoding of those bytes.
  std::vector<float> normals4;
  for (std::size_t i = 0; i < data.count(); ++i) {
    normals4.insert(normals4.end(), {data.normals[3 * i], data.normals[3 * i + 1], data.normals[3 * i + 2], 1.0f});
  }
  std::vector<unsigned char> octahedral(data.count() * 4);
  meshopt_encodeFilterOct(octahedral.data(), data.count(), 4, 8, normals4.data());
  MeshoptView normals = attribute(octahedral, 4);
  meshopt_decodeFilterOct(normals.bytes.data(), normals.count, 4);
  normals.filter = "OCTAHEDRAL";
  views.push_back(std::move(normals));
  views.push_back(attribute(bytesOf(data.uvs), 8));
  MeshoptView indices;
  indices.bytes = bytesOf(data.box.indices);
  indices.stride = 4;
  indices.count = data.box.indices.size();
  indices.mode = "TRIANGLES";
  indices.compressed.resize(meshopt_encodeIndexBufferBound(indices.count, data.count()));
  indices.compressed.resize(
      meshopt_encodeIndexBuffer(indices.compressed.data(), indices.compressed.size(), data.box.indices.data(), indices.count));
  views.push_back(std::move(indices));
  views.push_back(attribute(bytesOf(data.colours), 4));
  return views;
}

// The box written plain (every view in one buffer) or meshopt-compressed (the compressed streams in
// buffer 0, the views' placements in a fallback buffer without data). `edit` changes the file's
// JSON before it is written.
fs::path writeMeshopt(const fs::path& folder, const std::string& stem, const BoxData& data, const std::vector<MeshoptView>& views,
                      bool compress, const std::function<void(json&)>& edit = {}) {
  std::vector<char> bin, fallback;
  json bufferViews = json::array();
  for (const MeshoptView& view : views) {
    json v = {{"buffer", compress ? 1 : 0}, {"byteOffset", compress ? fallback.size() : bin.size()}, {"byteLength", view.bytes.size()}};
    if (std::string(view.mode) == "ATTRIBUTES") v["byteStride"] = view.stride;
    if (compress) {
      v["extensions"]["EXT_meshopt_compression"] = {{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", view.compressed.size()},
                                                    {"byteStride", view.stride}, {"count", view.count}, {"mode", view.mode},
                                                    {"filter", view.filter}};
      append(bin, view.compressed);
      fallback.resize(fallback.size() + view.bytes.size());
    } else {
      append(bin, view.bytes);
    }
    bufferViews.push_back(v);
    while (bin.size() % 4 != 0) bin.push_back(0);
    while (fallback.size() % 4 != 0) fallback.push_back(0);
  }
  std::ofstream(folder / (stem + ".bin"), std::ios::binary).write(bin.data(), static_cast<std::streamsize>(bin.size()));
  json d = document(stem + ".bin", bin.size());
  if (compress) {
    d["buffers"].push_back({{"byteLength", fallback.size()}, {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}});
    d["extensionsUsed"] = {"EXT_meshopt_compression", "KHR_mesh_quantization"};
    d["extensionsRequired"] = {"EXT_meshopt_compression", "KHR_mesh_quantization"};
  } else {
    d["extensionsUsed"] = {"KHR_mesh_quantization"};
    d["extensionsRequired"] = {"KHR_mesh_quantization"};
  }
  d["bufferViews"] = bufferViews;
  d["accessors"] = {accessor(0, 5126, data.count(), "VEC3"), accessor(1, 5120, data.count(), "VEC3"),
                    accessor(2, 5126, data.count(), "VEC2"), accessor(3, 5125, data.box.indices.size(), "SCALAR"),
                    accessor(4, 5121, data.count(), "VEC4")};
  d["accessors"][1]["normalized"] = true;
  d["accessors"][4]["normalized"] = true;
  d["meshes"] = {{{"primitives",
                   {{{"attributes", {{"POSITION", 0}, {"NORMAL", 1}, {"TEXCOORD_0", 2}, {"COLOR_0", 4}}}, {"indices", 3}}}}}};
  if (edit) edit(d);
  std::ofstream(folder / (stem + ".gltf")) << d.dump();
  return folder / (stem + ".gltf");
}

TEST(GltfCompression, AMeshoptBoxLoadsAsItsUncompressedTwin) {
  const fs::path folder = test::temporaryFolder("gltf_meshopt");
  const BoxData data;
  const std::vector<MeshoptView> views = meshoptBoxViews(data);
  const Scene plain = scene::loadGltf(writeMeshopt(folder, "plain", data, views, false));
  const Scene decoded = scene::loadGltf(writeMeshopt(folder, "meshopt", data, views, true));
  ASSERT_EQ(plain.meshes.size(), 1u);
  ASSERT_EQ(decoded.meshes.size(), 1u);
  const Mesh& a = plain.meshes[0];
  const Mesh& b = decoded.meshes[0];
  ASSERT_EQ(a.indices.size(), data.box.indices.size());
  ASSERT_EQ(b.indices.size(), a.indices.size());
  // The same triangles with the same winding: the index codec may start a triangle at another of
  // its corners (EXT_meshopt_compression allows it).
  for (std::size_t t = 0; t < a.indices.size(); t += 3) {
    std::size_t turn = 0;
    while (turn < 3 && b.indices[t + turn] != a.indices[t]) ++turn;
    ASSERT_LT(turn, 3u) << "triangle " << t / 3;
    for (std::size_t k = 0; k < 3; ++k) ASSERT_EQ(b.indices[t + (turn + k) % 3], a.indices[t + k]) << "triangle " << t / 3;
  }
  ASSERT_EQ(b.vertices.size(), a.vertices.size());
  for (std::size_t i = 0; i < a.vertices.size(); ++i) {
    ASSERT_EQ(a.vertices[i].position, b.vertices[i].position) << "vertex " << i;
    ASSERT_EQ(a.vertices[i].normal, b.vertices[i].normal) << "vertex " << i;
    ASSERT_EQ(a.vertices[i].uv, b.vertices[i].uv) << "vertex " << i;
    ASSERT_EQ(a.vertices[i].colour, b.vertices[i].colour) << "vertex " << i;
    // The 8-bit octahedral normal is the box's within its quantisation.
    EXPECT_LT(glm::length(b.vertices[i].normal - data.box.vertices[i].normal), 0.02f) << "vertex " << i;
  }
  EXPECT_TRUE(decoded.unreadFeatures.empty());

  // A truncated stream, a mode glint does not know and a count that does not fill the view: one
  // line each, naming the file and the buffer view.
  const std::string truncated = loadError(writeMeshopt(folder, "truncated", data, views, true, [&](json& d) {
    d["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["byteLength"] = views[0].compressed.size() / 2;
  }));
  EXPECT_NE(truncated.find("truncated.gltf: buffer view 0: EXT_meshopt_compression: the stream does not decode"), std::string::npos)
      << truncated;
  EXPECT_EQ(truncated.find('\n'), std::string::npos) << truncated;
  const std::string mode = loadError(writeMeshopt(folder, "mode", data, views, true, [](json& d) {
    d["bufferViews"][3]["extensions"]["EXT_meshopt_compression"]["mode"] = "STRIPS";
  }));
  EXPECT_NE(mode.find("buffer view 3: EXT_meshopt_compression: mode must be"), std::string::npos) << mode;
  const std::string count = loadError(writeMeshopt(folder, "count", data, views, true, [](json& d) {
    d["bufferViews"][2]["extensions"]["EXT_meshopt_compression"]["count"] = 3;
  }));
  EXPECT_NE(count.find("buffer view 2: EXT_meshopt_compression: count 3 x byteStride 8 is not the buffer view's byteLength"),
            std::string::npos)
      << count;
  // A count that is not a whole number, or beyond int32 (tinygltf would wrap it), and a view that is
  // not compressed but lies in the fallback buffer, which holds no data (an image's view there
  // would have been read past the one byte that stands in for it).
  for (const json& bad : {json(1e300), json(3.5), json(std::int64_t{1} << 33)}) {
    const std::string message = loadError(writeMeshopt(folder, "huge", data, views, true, [&](json& d) {
      d["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["count"] = bad;
    }));
    EXPECT_NE(message.find("buffer view 0: EXT_meshopt_compression: count must be a whole number in [0, 2147483647]"),
              std::string::npos)
        << message;
  }
  const std::string uncompressed = loadError(writeMeshopt(folder, "uncompressed", data, views, true, [](json& d) {
    d["bufferViews"][4].erase("extensions");
  }));
  EXPECT_NE(uncompressed.find("buffer view 4: its buffer 1 is a EXT_meshopt_compression fallback, which holds no data"),
            std::string::npos)
      << uncompressed;
}

}  // namespace
}  // namespace glint
