#include "scene_support.h"

#include <cstdio>
#include <fstream>
#include <stdexcept>

#include "scene/geometry.h"
#include "scene/gltf_writer.h"

namespace glint::test {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// An 8 x 8 RGBA texture whose texels follow `texel(x, y)`.
scene::Texture smallTexture(const std::string& name, bool srgb, const std::function<glm::u8vec4(int, int)>& texel) {
  scene::Texture texture{name, 8, 8, {}, srgb, {}};
  for (int y = 0; y < texture.height; ++y) {
    for (int x = 0; x < texture.width; ++x) {
      const glm::u8vec4 t = texel(x, y);
      texture.rgba.insert(texture.rgba.end(), {t.r, t.g, t.b, t.a});
    }
  }
  return texture;
}

// Standard base64 (RFC 4648) as data URIs hold it; throws on anything else.
std::string decodeBase64(const std::string& text) {
  auto value = [](char c) -> int {
    if (c >= 'A' && c <= 'Z') return c - 'A';
    if (c >= 'a' && c <= 'z') return c - 'a' + 26;
    if (c >= '0' && c <= '9') return c - '0' + 52;
    if (c == '+') return 62;
    if (c == '/') return 63;
    return -1;
  };
  std::string out;
  unsigned bits = 0;
  int count = 0;
  for (char c : text) {
    if (c == '=') break;
    const int v = value(c);
    if (v < 0) throw std::runtime_error("not base64");
    bits = (bits << 6) | static_cast<unsigned>(v);
    count += 6;
    if (count >= 8) {
      count -= 8;
      out += static_cast<char>((bits >> count) & 0xFFu);
    }
  }
  return out;
}

}  // namespace

scene::Scene texturedTestScene() {
  using namespace scene;
  Scene s;
  s.name = "textured";
  s.textures.push_back(smallTexture("base colour", true, [](int x, int y) {
    return glm::u8vec4((x + y) % 2 ? 230 : 40, static_cast<std::uint8_t>(30 * x), static_cast<std::uint8_t>(30 * y), 255);
  }));
  s.textures.push_back(smallTexture("metallic roughness", false, [](int x, int y) {
    return glm::u8vec4(static_cast<std::uint8_t>(100 + 15 * x), static_cast<std::uint8_t>(90 + 20 * y), x > 4 ? 255 : 0, 255);
  }));
  s.textures.push_back(smallTexture("normal", false, [](int x, int) {
    return glm::u8vec4(static_cast<std::uint8_t>(108 + 5 * x), 128, 250, 255);
  }));
  s.textures.push_back(smallTexture("occlusion", false, [](int x, int y) {
    return glm::u8vec4(static_cast<std::uint8_t>(150 + 10 * ((x * y) % 10)), 0, 0, 255);
  }));
  // A glTF sampler other than the default: clamped along u, mirrored along v, nearest texels.
  s.textures.back().sampler = {.wrapS = TextureSampler::Wrap::ClampToEdge, .wrapT = TextureSampler::Wrap::MirroredRepeat,
                               .magnifyNearest = true, .minifyNearest = true, .mipmap = TextureSampler::Mipmap::Nearest};
  s.textures.push_back(smallTexture("emissive", true, [](int x, int y) {
    return glm::u8vec4(x == y ? 255 : 0, x == 7 - y ? 200 : 0, 20, 255);
  }));

  Material textured;
  textured.name = "textured";
  textured.baseColour = glm::vec4(0.9f, 0.8f, 0.7f, 1.0f);
  textured.baseColourTexture = 0;
  textured.baseColourUv.offset = glm::vec2(0.25f, -0.5f);
  textured.baseColourUv.rotation = 0.3f;
  textured.baseColourUv.scale = glm::vec2(2.0f, 3.0f);
  textured.metallic = 0.4f;
  textured.roughness = 0.6f;
  textured.metallicRoughnessTexture = 1;
  textured.normalTexture = 2;
  textured.normalScale = 0.8f;
  textured.occlusionTexture = 3;
  textured.occlusionStrength = 0.7f;
  textured.emissive = glm::vec3(3.0f, 0.5f, 0.0f);  // past 1: KHR_materials_emissive_strength
  textured.emissiveTexture = 4;
  textured.clearcoat.factor = 0.8f;
  textured.clearcoat.roughness = 0.15f;
  textured.clearcoat.texture = 3;
  textured.clearcoat.uv.rotation = 0.5f;
  textured.clearcoat.roughnessTexture = 1;
  textured.clearcoat.normalTexture = 2;
  textured.clearcoat.normalScale = 0.5f;
  textured.glint.enabled = true;
  textured.glint.alpha = glm::vec2(0.3f, 0.2f);
  textured.glint.rho = -0.35f;
  textured.glint.logDensity = 18.5f;
  textured.glint.relativeArea = 0.6f;
  textured.glint.densityRandomisation = 1.5f;
  textured.glint.maxAnisotropy = 12.0f;
  textured.glint.patternSeed = 3000000000u;  // beyond a 32-bit int
  textured.glint.uvScale = 3.0f;
  textured.glint.colouredCells = true;
  textured.glint.lod = kernel::GLINT_LOD_CONSISTENT;
  textured.glint.roughnessTexture = 1;
  textured.glint.logDensityRange = glm::vec2(12.0f, 30.0f);
  s.materials.push_back(textured);

  Material plain;
  plain.name = "plain";
  plain.baseColour = glm::vec4(0.5f, 0.55f, 0.6f, 0.75f);
  plain.metallic = 0.0f;
  plain.roughness = 0.9f;
  plain.doubleSided = true;
  plain.alphaMode = Material::AlphaMode::Mask;
  plain.alphaCutoff = 0.3f;
  s.materials.push_back(plain);

  s.meshes.push_back(makeUvSphere("ball", 0, glm::vec3(0.0f, 0.6f, 0.0f), 0.5f, 24, 12));
  Mesh floor = makeQuad("floor", 1, glm::vec3(0.0f), {1.5f, 0, 0}, {0, 0, 1.5f}, glm::vec2(2.0f));
  for (std::size_t i = 0; i < floor.vertices.size(); ++i) {
    floor.vertices[i].colour = glm::vec4(0.2f + 0.2f * static_cast<float>(i), 0.9f, 0.5f, 1.0f);
  }
  s.meshes.push_back(floor);

  Light point;
  point.type = Light::Type::Point;
  point.position = glm::vec3(1.0f, 2.5f, 2.0f);
  point.intensity = glm::vec3(20.0f, 18.0f, 15.0f);
  s.lights.push_back(point);
  Light spot;
  spot.type = Light::Type::Spot;
  spot.position = glm::vec3(-1.5f, 2.0f, 0.5f);
  spot.direction = glm::normalize(glm::vec3(0.6f, -1.0f, -0.2f));
  spot.intensity = glm::vec3(12.0f, 14.0f, 16.0f);
  spot.innerConeAngle = 0.25f;
  spot.outerConeAngle = 0.6f;
  spot.range = 6.0f;
  s.lights.push_back(spot);
  Light sun;
  sun.type = Light::Type::Directional;
  sun.direction = glm::normalize(glm::vec3(-0.3f, -1.0f, -0.5f));
  sun.intensity = glm::vec3(0.7f, 0.68f, 0.6f);
  s.lights.push_back(sun);

  s.environment.uniform = glm::vec3(0.1f);
  s.cameras = standardCameras(s.boundsMin(), s.boundsMax());
  Camera main;
  main.position = glm::vec3(0.5f, 1.5f, 3.0f);
  main.target = glm::vec3(0.0f, 0.4f, 0.0f);
  main.verticalFovDegrees = 40.0f;
  s.cameras["default"] = main;
  Camera plan;
  plan.projection = Camera::Projection::Orthographic;
  plan.position = glm::vec3(0.0f, 4.0f, 0.0f);
  plan.target = glm::vec3(0.0f);
  plan.up = glm::vec3(0, 0, -1);
  plan.orthographicHalfHeight = 1.8f;
  s.cameras["plan"] = plan;
  return s;
}

fs::path writeSeparateGltf(const scene::Scene& scene, const fs::path& folder, const std::string& stem) {
  const fs::path path = folder / (stem + ".gltf");
  scene::writeGltf(path, scene);
  json document = json::parse(std::ifstream(path));
  const std::string uri = document["buffers"][0]["uri"];
  const std::string bytes = decodeBase64(uri.substr(uri.find(',') + 1));
  std::ofstream(folder / (stem + ".bin"), std::ios::binary) << bytes;
  document["buffers"][0]["uri"] = stem + ".bin";
  for (std::size_t i = 0; document.contains("images") && i < document["images"].size(); ++i) {
    json& image = document["images"][i];
    const json& view = document["bufferViews"][image["bufferView"].get<std::size_t>()];
    const std::size_t offset = view.value("byteOffset", std::size_t{0});
    const std::string name = "image" + std::to_string(i) + ".png";
    std::ofstream(folder / name, std::ios::binary) << bytes.substr(offset, view["byteLength"].get<std::size_t>());
    image.erase("bufferView");
    image.erase("mimeType");
    image["uri"] = name;
  }
  std::ofstream(path) << document.dump(1);
  return path;
}

void editGltfJson(const fs::path& path, const std::function<void(json&)>& edit) {
  json document = json::parse(std::ifstream(path));
  edit(document);
  std::ofstream(path) << document.dump(1);
}

fs::path sharedAsset(const std::string& relative) {
  const fs::path path = fs::path(GLINT_SHARED_DIR) / relative;
  std::error_code ignored;
  return fs::exists(path, ignored) ? path : fs::path();
}

std::string sharedAssetMissing(const std::string& relative) {
  return "needs ../shared/" + relative + " (third-party asset, not in the repository)";
}

std::string triple(glm::vec3 v) {
  char text[128];
  std::snprintf(text, sizeof text, "%.9g,%.9g,%.9g", v.x, v.y, v.z);
  return text;
}

std::string cameraOptions(const scene::Camera& camera) {
  char fov[32];
  std::snprintf(fov, sizeof fov, "%.9g", camera.verticalFovDegrees);
  return " --look-from " + triple(camera.position) + " --look-at " + triple(camera.target) + " --up " + triple(camera.up) +
         " --fov " + fov;
}

}  // namespace glint::test
