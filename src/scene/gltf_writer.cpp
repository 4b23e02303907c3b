#include "scene/gltf_writer.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <variant>

#include <glm/gtc/type_ptr.hpp>
// Debian's libtinygltf-dev ships the implementation compiled (libtinygltf.so), writer included.
#include <tiny_gltf.h>

#include "glint/error.h"
#include "glint/file_io.h"
#include "glint/image.h"
#include "glint/image_io.h"
#include "scene/geometry.h"
#include "scene/gltf_glint.h"

namespace glint::scene {

namespace {

// A float as the double of its shortest decimal form (0.3f as 0.3, not 0.30000001192092896): the
// JSON stays readable and reads back, through float, as the same float.
double decimal(float value) {
  char text[32];
  const auto written = std::to_chars(text, text + sizeof text, value);
  double result = 0.0;
  std::from_chars(text, written.ptr, result);
  return result;
}

tinygltf::Value number(float value) { return tinygltf::Value(decimal(value)); }

tinygltf::Value pair(glm::vec2 value) {
  return tinygltf::Value(tinygltf::Value::Array{number(value.x), number(value.y)});
}

// A material's specular target as the glint fields spell it (in EXT_materials_glint, or in
// extras.glint_specular for a material without a layer).
void writeSpecularTarget(tinygltf::Value::Object& fields, const MicrofacetTarget& specular, GlintSpelling spelling) {
  fields[glintFieldName(GlintField::Ndf, spelling)] = tinygltf::Value(std::string(ndfName(specular.ndf)));
  fields[glintFieldName(GlintField::Masking, spelling)] = tinygltf::Value(std::string(maskingName(specular.masking)));
  fields[glintFieldName(GlintField::MultipleScattering, spelling)] = tinygltf::Value(specular.multipleScattering);
}

// The glint layer as EXT_materials_glint, exactly as the loader reads it back
// (extensions/EXT_materials_glint/README.md): every field, so that the file does not depend on a
// reader's defaults; textures as textureInfo objects.
tinygltf::Value glintExtension(const GlintLayer& layer, const MicrofacetTarget& specular) {
  constexpr GlintSpelling kSpelling = GlintSpelling::Extension;
  auto name = [](GlintField field) { return glintFieldName(field, kSpelling); };
  tinygltf::Value::Object glint;
  writeSpecularTarget(glint, specular, kSpelling);
  // Every field of the block through its row's member, as its kind writes it; the specular target's
  // fields are the material's, written above.
  for (const GlintFieldSpec& spec : kGlintFields) {
    if (isSpecularTargetField(spec.field)) continue;
    tinygltf::Value value;
    if (const auto* member = std::get_if<float kernel::GlintMaterial::*>(&spec.member)) {
      value = number(layer.**member);
    } else if (const auto* vector = std::get_if<glm::vec2 kernel::GlintMaterial::*>(&spec.member)) {
      value = pair(layer.**vector);
    } else if (const auto* word = std::get_if<kernel::uint kernel::GlintMaterial::*>(&spec.member)) {
      const kernel::uint held = layer.**word;
      // tinygltf's integers are 32-bit ints: a seed beyond them is written as a whole double.
      value = spec.kind == GlintFieldKind::Boolean ? tinygltf::Value(held != 0u)
              : held <= static_cast<kernel::uint>(std::numeric_limits<int>::max())
                  ? tinygltf::Value(static_cast<int>(held))
                  : tinygltf::Value(static_cast<double>(held));
    } else if (const auto* choice = std::get_if<int kernel::GlintMaterial::*>(&spec.member)) {
      value = tinygltf::Value(std::string(glintChoiceName(spec.field, layer.**choice)));
    } else {
      continue;  // a texture: below
    }
    glint[name(spec.field)] = std::move(value);
  }
  const std::pair<GlintField, int> textures[] = {{GlintField::RoughnessTexture, layer.roughnessTexture},
                                                 {GlintField::LogDensityTexture, layer.logDensityTexture},
                                                 {GlintField::RelativeAreaTexture, layer.relativeAreaTexture}};
  for (const auto& [field, index] : textures) {
    if (index < 0) continue;
    tinygltf::Value::Object textureInfo;
    textureInfo["index"] = tinygltf::Value(index);
    glint[name(field)] = tinygltf::Value(std::move(textureInfo));
  }
  return tinygltf::Value(std::move(glint));
}

std::vector<double> decimals(std::initializer_list<float> values) {
  std::vector<double> result;
  for (float v : values) result.push_back(decimal(v));
  return result;
}

// A rigid camera or light frame as a glTF node matrix (column-major): its -z looks along `forward`,
// its +y is `up` made perpendicular, its origin is `position`.
std::vector<double> frameMatrix(glm::dvec3 position, glm::dvec3 forward, glm::dvec3 up) {
  forward = glm::normalize(forward);
  glm::dvec3 right = glm::cross(forward, up);
  if (!(glm::length(right) > 1e-12)) right = glm::dvec3(anyPerpendicular(glm::vec3(forward)));
  right = glm::normalize(right);
  const glm::dvec3 trueUp = glm::cross(right, forward);
  const glm::dvec3 columns[4] = {right, trueUp, -forward, position};
  std::vector<double> matrix;
  for (int c = 0; c < 4; ++c) {
    for (int r = 0; r < 3; ++r) matrix.push_back(columns[c][r]);
    matrix.push_back(c == 3 ? 1.0 : 0.0);
  }
  return matrix;
}

class GltfWriter {
 public:
  GltfWriter(const Scene& scene, bool withDefaults) : scene_(scene), withDefaults_(withDefaults) {}

  tinygltf::Model write() {
    model_.asset.version = "2.0";
    model_.asset.generator = "glint";
    model_.buffers.emplace_back();
    model_.buffers[0].name = "glint";
    for (std::size_t i = 0; i < scene_.textures.size(); ++i) addTexture(i);
    for (std::size_t i = 0; i < scene_.materials.size(); ++i) addMaterial(i);
    tinygltf::Scene root;
    root.name = scene_.name;
    for (std::size_t i = 0; i < scene_.meshes.size(); ++i) root.nodes.push_back(addMesh(i));
    for (const Light& light : writtenLights(scene_, withDefaults_)) root.nodes.push_back(addLight(light));
    for (const auto& [name, camera] : writtenCameras(scene_, withDefaults_)) root.nodes.push_back(addCamera(name, camera));
    model_.scenes.push_back(std::move(root));
    model_.defaultScene = 0;
    if (usesTextureTransforms_) model_.extensionsUsed.push_back("KHR_texture_transform");
    if (usesEmissiveStrength_) model_.extensionsUsed.push_back("KHR_materials_emissive_strength");
    if (usesClearcoat_) model_.extensionsUsed.push_back("KHR_materials_clearcoat");
    // Used, not required: a viewer without it draws the core material, the layer's smooth average
    // (extensions/EXT_materials_glint/README.md, "Fallback").
    if (usesGlint_) model_.extensionsUsed.push_back(kGlintExtensionName);
    // KHR_lights_punctual is added to extensionsUsed by tinygltf when there are lights.
    return std::move(model_);
  }

 private:
  std::vector<unsigned char>& bytes() { return model_.buffers[0].data; }

  // A buffer view over `size` new bytes at the end of the buffer, 4-byte aligned (as glTF asks of
  // float and 32-bit integer accessors); returns its index.
  int addView(const void* data, std::size_t size, int target) {
    std::vector<unsigned char>& buffer = bytes();
    buffer.resize((buffer.size() + 3) / 4 * 4, 0);
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = buffer.size();
    view.byteLength = size;
    view.target = target;
    const auto* begin = static_cast<const unsigned char*>(data);
    buffer.insert(buffer.end(), begin, begin + size);
    model_.bufferViews.push_back(view);
    return static_cast<int>(model_.bufferViews.size()) - 1;
  }

  // A float accessor of `components` per element over `values`.
  int addFloats(const std::vector<float>& values, int components, int type, bool bounds) {
    tinygltf::Accessor accessor;
    accessor.bufferView = addView(values.data(), values.size() * sizeof(float), TINYGLTF_TARGET_ARRAY_BUFFER);
    accessor.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
    accessor.count = values.size() / static_cast<std::size_t>(components);
    accessor.type = type;
    if (bounds) {  // glTF requires POSITION's min and max
      accessor.minValues.assign(static_cast<std::size_t>(components), std::numeric_limits<double>::max());
      accessor.maxValues.assign(static_cast<std::size_t>(components), std::numeric_limits<double>::lowest());
      for (std::size_t i = 0; i < values.size(); ++i) {
        const std::size_t c = i % static_cast<std::size_t>(components);
        accessor.minValues[c] = std::min(accessor.minValues[c], static_cast<double>(values[i]));
        accessor.maxValues[c] = std::max(accessor.maxValues[c], static_cast<double>(values[i]));
      }
    }
    model_.accessors.push_back(accessor);
    return static_cast<int>(model_.accessors.size()) - 1;
  }

  void addTexture(std::size_t index) {
    const Texture& texture = scene_.textures[index];
    const std::size_t expected = static_cast<std::size_t>(std::max(texture.width, 0)) *
                                 static_cast<std::size_t>(std::max(texture.height, 0)) * 4;
    if (texture.width <= 0 || texture.height <= 0 || texture.rgba.size() != expected) {
      throw Error("texture " + std::to_string(index) + " '" + texture.name + "': " + std::to_string(texture.rgba.size()) +
                  " bytes for " + std::to_string(texture.width) + " x " + std::to_string(texture.height) + " RGBA texels");
    }
    const std::vector<std::byte> png = encodePng(texture.width, texture.height, 4, texture.rgba.data());
    tinygltf::Image image;
    image.name = texture.name;
    image.mimeType = "image/png";
    image.bufferView = addView(png.data(), png.size(), 0);
    model_.images.push_back(std::move(image));
    tinygltf::Texture gltfTexture;
    gltfTexture.name = texture.name;
    gltfTexture.source = static_cast<int>(index);
    if (!(texture.sampler == TextureSampler{})) {
      gltfTexture.sampler = static_cast<int>(model_.samplers.size());
      model_.samplers.push_back(gltfSampler(texture.sampler));
    }
    model_.textures.push_back(std::move(gltfTexture));
  }

  // A texture's sampler as glTF writes it (OpenGL's enums); the filters glint uses when a file
  // names none (trilinear) are left unnamed.
  static tinygltf::Sampler gltfSampler(const TextureSampler& sampler) {
    auto wrap = [](TextureSampler::Wrap mode) {
      return mode == TextureSampler::Wrap::ClampToEdge ? 33071 : mode == TextureSampler::Wrap::MirroredRepeat ? 33648 : 10497;
    };
    tinygltf::Sampler out;
    out.wrapS = wrap(sampler.wrapS);
    out.wrapT = wrap(sampler.wrapT);
    out.magFilter = sampler.magnifyNearest ? 9728 : -1;
    const int linear = sampler.minifyNearest ? 0 : 1;  // NEAREST and LINEAR are one apart, as are their mipmap forms
    switch (sampler.mipmap) {
      case TextureSampler::Mipmap::None: out.minFilter = 9728 + linear; break;
      case TextureSampler::Mipmap::Nearest: out.minFilter = 9984 + linear; break;
      case TextureSampler::Mipmap::Linear: out.minFilter = sampler.minifyNearest ? 9986 : -1; break;
    }
    return out;
  }

  int textureIndex(int index, const char* what, const Material& material) const {
    if (index < -1 || (index >= 0 && static_cast<std::size_t>(index) >= scene_.textures.size())) {
      throw Error("material '" + material.name + "': " + what + " " + std::to_string(index) + " is not a texture");
    }
    return index;
  }

  // A texture reference with its KHR_texture_transform, where it is not the identity.
  template <typename Info>
  void setTexture(Info& info, int index, const UvTransform& transform, const char* what, const Material& material) {
    info.index = textureIndex(index, what, material);
    if (index < 0 || transform.identity()) return;
    tinygltf::Value::Object extension;
    extension["offset"] = pair(transform.offset);
    extension["rotation"] = number(transform.rotation);
    extension["scale"] = pair(transform.scale);
    info.extensions["KHR_texture_transform"] = tinygltf::Value(std::move(extension));
    usesTextureTransforms_ = true;
  }

  // A texture reference inside an extension's object (setTexture's, as JSON), with a normal map's
  // scale where given.
  tinygltf::Value textureValue(int index, const UvTransform& transform, const char* what, const Material& material,
                               std::optional<float> scale = std::nullopt) {
    tinygltf::NormalTextureInfo info;
    setTexture(info, index, transform, what, material);
    tinygltf::Value::Object object;
    object["index"] = tinygltf::Value(info.index);
    if (!info.extensions.empty()) {
      object["extensions"] = tinygltf::Value(tinygltf::Value::Object(info.extensions.begin(), info.extensions.end()));
    }
    if (scale) object["scale"] = number(*scale);
    return tinygltf::Value(std::move(object));
  }

  // KHR_materials_clearcoat's object of a coated material.
  tinygltf::Value clearcoatExtension(const Material& m) {
    const Material::Clearcoat& coat = m.clearcoat;
    checkUnit(coat.factor, "clearcoat factor", m);
    checkUnit(coat.roughness, "clearcoat roughness", m);
    tinygltf::Value::Object extension;
    extension["clearcoatFactor"] = number(coat.factor);
    extension["clearcoatRoughnessFactor"] = number(coat.roughness);
    if (coat.texture >= 0) extension["clearcoatTexture"] = textureValue(coat.texture, coat.uv, "clearcoat texture", m);
    if (coat.roughnessTexture >= 0) {
      extension["clearcoatRoughnessTexture"] = textureValue(coat.roughnessTexture, coat.roughnessUv, "clearcoat roughness texture", m);
    }
    if (coat.normalTexture >= 0) {
      extension["clearcoatNormalTexture"] =
          textureValue(coat.normalTexture, coat.normalUv, "clearcoat normal texture", m, coat.normalScale);
    }
    usesClearcoat_ = true;
    return tinygltf::Value(std::move(extension));
  }

  static void checkUnit(float value, const std::string& what, const Material& material) {
    if (!(value >= 0.0f && value <= 1.0f)) {
      throw Error("material '" + material.name + "': " + what + " " + std::to_string(value) + " is outside [0, 1]");
    }
  }

  void addMaterial(std::size_t index) {
    const Material& m = scene_.materials[index];
    tinygltf::Material out;
    out.name = m.name;
    for (int c = 0; c < 4; ++c) checkUnit(m.baseColour[c], "base colour", m);
    checkUnit(m.metallic, "metallic", m);
    checkUnit(m.roughness, "roughness", m);
    checkUnit(m.occlusionStrength, "occlusion strength", m);
    out.pbrMetallicRoughness.baseColorFactor = decimals({m.baseColour.r, m.baseColour.g, m.baseColour.b, m.baseColour.a});
    out.pbrMetallicRoughness.metallicFactor = decimal(m.metallic);
    out.pbrMetallicRoughness.roughnessFactor = decimal(m.roughness);
    setTexture(out.pbrMetallicRoughness.baseColorTexture, m.baseColourTexture, m.baseColourUv, "base colour texture", m);
    setTexture(out.pbrMetallicRoughness.metallicRoughnessTexture, m.metallicRoughnessTexture, m.metallicRoughnessUv,
               "metallic-roughness texture", m);
    setTexture(out.normalTexture, m.normalTexture, m.normalUv, "normal texture", m);
    out.normalTexture.scale = decimal(m.normalScale);
    setTexture(out.occlusionTexture, m.occlusionTexture, m.occlusionUv, "occlusion texture", m);
    out.occlusionTexture.strength = decimal(m.occlusionStrength);
    setTexture(out.emissiveTexture, m.emissiveTexture, m.emissiveUv, "emissive texture", m);
    // glTF keeps emissiveFactor in [0, 1]; a brighter emission is a factor times
    // KHR_materials_emissive_strength's strength, a power of two so that factor times strength
    // gives back the very floats.
    const float brightest = std::max({m.emissive.r, m.emissive.g, m.emissive.b});
    if (!(std::isfinite(brightest) && std::min({m.emissive.r, m.emissive.g, m.emissive.b}) >= 0.0f)) {
      throw Error("material '" + m.name + "': the emission must be finite and not negative");
    }
    float strength = 1.0f;
    while (brightest / strength > 1.0f) strength *= 2.0f;
    const glm::vec3 factor = m.emissive / strength;
    out.emissiveFactor = decimals({factor.r, factor.g, factor.b});
    if (strength != 1.0f) {
      tinygltf::Value::Object extension;
      extension["emissiveStrength"] = number(strength);
      out.extensions["KHR_materials_emissive_strength"] = tinygltf::Value(std::move(extension));
      usesEmissiveStrength_ = true;
    }
    if (m.clearcoat.enabled()) out.extensions["KHR_materials_clearcoat"] = clearcoatExtension(m);
    out.doubleSided = m.doubleSided;
    out.alphaMode = m.alphaMode == Material::AlphaMode::Mask    ? "MASK"
                    : m.alphaMode == Material::AlphaMode::Blend ? "BLEND"
                                                                : "OPAQUE";
    out.alphaCutoff = decimal(m.alphaCutoff);
    if (m.glint.enabled) {
      for (int t : {m.glint.roughnessTexture, m.glint.logDensityTexture, m.glint.relativeAreaTexture}) {
        textureIndex(t, "glint texture", m);
      }
      out.extensions[kGlintExtensionName] = glintExtension(m.glint, m.specular);
      usesGlint_ = true;
    } else if (m.specular.ndf != kGltfSpecular.ndf || m.specular.masking != kGltfSpecular.masking ||
               m.specular.multipleScattering != kGltfSpecular.multipleScattering) {
      // A material without a glint layer whose lobe is not glTF's (a built-in scene's): said in
      // extras.glint_specular, so that the file renders as the scene did.
      tinygltf::Value::Object target;
      writeSpecularTarget(target, m.specular, GlintSpelling::Extras);
      tinygltf::Value::Object extras;
      extras["glint_specular"] = tinygltf::Value(std::move(target));
      out.extras = tinygltf::Value(std::move(extras));
    }
    model_.materials.push_back(std::move(out));
  }

  int addMesh(std::size_t index) {
    const Mesh& mesh = scene_.meshes[index];
    if (mesh.material < 0 || static_cast<std::size_t>(mesh.material) >= scene_.materials.size()) {
      throw Error("mesh '" + mesh.name + "': material " + std::to_string(mesh.material) + " does not exist");
    }
    for (std::uint32_t i : mesh.indices) {
      if (i >= mesh.vertices.size()) throw Error("mesh '" + mesh.name + "': index " + std::to_string(i) + " out of range");
    }
    std::vector<float> positions, normals, tangents, uvs, colours;
    bool white = true;
    for (const Vertex& v : mesh.vertices) {
      positions.insert(positions.end(), {v.position.x, v.position.y, v.position.z});
      normals.insert(normals.end(), {v.normal.x, v.normal.y, v.normal.z});
      tangents.insert(tangents.end(), {v.tangent.x, v.tangent.y, v.tangent.z, v.tangent.w < 0.0f ? -1.0f : 1.0f});
      uvs.insert(uvs.end(), {v.uv.x, v.uv.y});
      colours.insert(colours.end(), {v.colour.r, v.colour.g, v.colour.b, v.colour.a});
      white = white && v.colour == glm::vec4(1.0f);
      for (int c = 0; c < 4; ++c) {
        if (!(v.colour[c] >= 0.0f && v.colour[c] <= 1.0f)) {
          throw Error("mesh '" + mesh.name + "': a vertex colour is outside [0, 1]");
        }
      }
    }
    tinygltf::Primitive primitive;
    primitive.mode = TINYGLTF_MODE_TRIANGLES;
    primitive.material = mesh.material;
    primitive.attributes["POSITION"] = addFloats(positions, 3, TINYGLTF_TYPE_VEC3, true);
    primitive.attributes["NORMAL"] = addFloats(normals, 3, TINYGLTF_TYPE_VEC3, false);
    primitive.attributes["TANGENT"] = addFloats(tangents, 4, TINYGLTF_TYPE_VEC4, false);
    primitive.attributes["TEXCOORD_0"] = addFloats(uvs, 2, TINYGLTF_TYPE_VEC2, false);
    if (!white) primitive.attributes["COLOR_0"] = addFloats(colours, 4, TINYGLTF_TYPE_VEC4, false);
    tinygltf::Accessor indices;
    indices.bufferView = addView(mesh.indices.data(), mesh.indices.size() * sizeof(std::uint32_t),
                                 TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
    indices.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
    indices.count = mesh.indices.size();
    indices.type = TINYGLTF_TYPE_SCALAR;
    model_.accessors.push_back(indices);
    primitive.indices = static_cast<int>(model_.accessors.size()) - 1;
    tinygltf::Mesh out;
    out.name = mesh.name;
    out.primitives.push_back(std::move(primitive));
    model_.meshes.push_back(std::move(out));
    tinygltf::Node node;
    node.name = mesh.name;
    node.mesh = static_cast<int>(model_.meshes.size()) - 1;
    return addNode(std::move(node));
  }

  int addNode(tinygltf::Node node) {
    model_.nodes.push_back(std::move(node));
    return static_cast<int>(model_.nodes.size()) - 1;
  }

  // KHR_lights_punctual in its photometric units, at the loader's 683 lm/W: the colour is the
  // intensity divided by its largest component, the intensity that component in candela or lux.
  int addLight(const Light& light) {
    tinygltf::Light out;
    out.type = light.type == Light::Type::Point ? "point" : light.type == Light::Type::Spot ? "spot" : "directional";
    const float largest = std::max({light.intensity.r, light.intensity.g, light.intensity.b});
    if (!(std::isfinite(largest) && std::min({light.intensity.r, light.intensity.g, light.intensity.b}) >= 0.0f)) {
      throw Error("a light's intensity must be finite and not negative");
    }
    constexpr double kLumensPerWatt = 683.0;
    out.intensity = static_cast<double>(largest) * kLumensPerWatt;  // exact: a float times 683 fits a double
    out.color = largest > 0.0f ? std::vector<double>{light.intensity.r / static_cast<double>(largest),
                                                     light.intensity.g / static_cast<double>(largest),
                                                     light.intensity.b / static_cast<double>(largest)}
                               : std::vector<double>{1.0, 1.0, 1.0};
    if (light.positional() && light.range > 0.0f) out.range = light.range;
    if (light.type == Light::Type::Spot) {
      out.spot.innerConeAngle = light.innerConeAngle;
      out.spot.outerConeAngle = light.outerConeAngle;
    }
    model_.lights.push_back(std::move(out));
    tinygltf::Node node;
    if (light.type == Light::Type::Point) {
      node.translation = {light.position.x, light.position.y, light.position.z};
    } else {
      // Spots and suns shine down their node's -z.
      const glm::dvec3 direction(light.type == Light::Type::Spot ? light.spotAxis() : light.direction);
      node.matrix = frameMatrix(glm::dvec3(light.position), direction, glm::dvec3(0, 1, 0));
    }
    tinygltf::Value::Object extension;
    extension["light"] = tinygltf::Value(static_cast<int>(model_.lights.size()) - 1);
    node.extensions["KHR_lights_punctual"] = tinygltf::Value(std::move(extension));
    return addNode(std::move(node));
  }

  int addCamera(const std::string& name, const Camera& camera) {
    const glm::dvec3 position(camera.position);
    const glm::dvec3 forward = glm::dvec3(camera.target) - position;
    if (!(glm::length(forward) > 0.0) || !(glm::length(glm::cross(forward, glm::dvec3(camera.up))) > 0.0)) {
      throw Error("camera '" + name + "': its target, position and up do not make a view");
    }
    // The clipping planes glTF asks for; glint's renderers choose their own from the scene's bounds.
    const glm::vec3 low = scene_.boundsMin();
    const glm::vec3 high = scene_.boundsMax();
    const double far = glm::length(0.5 * glm::dvec3(low + high) - position) + glm::length(glm::dvec3(high - low)) + 1e-3;
    tinygltf::Camera out;
    out.name = name;
    if (camera.projection == Camera::Projection::Perspective) {
      out.type = "perspective";
      out.perspective.yfov = glm::radians(static_cast<double>(camera.verticalFovDegrees));
      out.perspective.znear = 1e-4 * far;
      out.perspective.zfar = far;
    } else {
      out.type = "orthographic";
      out.orthographic.xmag = decimal(camera.orthographicHalfHeight);
      out.orthographic.ymag = decimal(camera.orthographicHalfHeight);
      out.orthographic.znear = 0.0;
      out.orthographic.zfar = far;
    }
    model_.cameras.push_back(std::move(out));
    tinygltf::Node node;
    node.name = name;
    node.camera = static_cast<int>(model_.cameras.size()) - 1;
    node.matrix = frameMatrix(position, forward, glm::dvec3(camera.up));
    return addNode(std::move(node));
  }

  const Scene& scene_;
  bool withDefaults_;
  tinygltf::Model model_;
  bool usesTextureTransforms_ = false;
  bool usesClearcoat_ = false;
  bool usesEmissiveStrength_ = false;
  bool usesGlint_ = false;
};

}  // namespace

std::vector<Light> writtenLights(const Scene& scene, bool withDefaults) {
  return scene.defaultLights && !withDefaults ? std::vector<Light>() : scene.lights;
}

std::vector<std::pair<std::string, Camera>> writtenCameras(const Scene& scene, bool withDefaults) {
  // glint's presets are the cameras it made when it loaded or built the scene (or, for a scene made
  // otherwise, standardCameras of its bounds), under their names and unchanged; "default" is
  // glint's name for another camera when it has that camera's view.
  const std::map<std::string, Camera> presets =
      scene.presetCameras.empty() ? standardCameras(scene.boundsMin(), scene.boundsMax()) : scene.presetCameras;
  const auto invented = [&](const std::string& name, const Camera& camera) {
    const auto preset = presets.find(name);
    return preset != presets.end() && sameView(preset->second, camera);
  };
  const auto fallback = scene.cameras.find("default");
  // The scene's own camera whose view "default" has: written once, under its own name.
  std::string aliased;
  if (!withDefaults && fallback != scene.cameras.end()) {
    for (const auto& [name, camera] : scene.cameras) {
      if (name != "default" && !invented(name, camera) && sameView(camera, fallback->second)) {
        aliased = name;
        break;
      }
    }
  }
  std::vector<std::pair<std::string, Camera>> cameras;
  for (const auto& [name, camera] : scene.cameras) {
    if ((withDefaults || !invented(name, camera)) && !(name == "default" && !aliased.empty())) {
      cameras.emplace_back(name, camera);
    }
  }
  if (fallback == scene.cameras.end() || cameras.empty()) return cameras;
  // A reader takes the first camera for its default view: the default view's camera goes first;
  // where glint's own default view stands among the scene's cameras, it is written too.
  const std::string first = aliased.empty() ? "default" : aliased;
  const auto at = std::find_if(cameras.begin(), cameras.end(), [&](const auto& named) { return named.first == first; });
  if (at != cameras.end()) {
    std::rotate(cameras.begin(), at, at + 1);
  } else {
    cameras.insert(cameras.begin(), *fallback);
  }
  return cameras;
}

std::vector<std::byte> encodeGltf(const Scene& scene, GltfEncoding encoding, bool withDefaults) {
  std::size_t triangles = 0;
  for (const Mesh& mesh : scene.meshes) triangles += mesh.indices.size() / 3;
  if (triangles == 0) throw Error("scene '" + scene.name + "' has no triangles to write");
  const tinygltf::Model model = GltfWriter(scene, withDefaults).write();
  std::ostringstream stream;
  tinygltf::TinyGLTF writer;
  const bool binary = encoding == GltfEncoding::Binary;
  if (!writer.WriteGltfSceneToStream(&model, stream, !binary, binary) || !stream) {
    throw Error("scene '" + scene.name + "': the glTF writer failed");
  }
  const std::string text = stream.str();
  std::vector<std::byte> result(text.size());
  std::memcpy(result.data(), text.data(), text.size());
  return result;
}

std::vector<std::string> gltfLosses(const Scene& scene) {
  std::vector<std::string> losses;
  const Environment& e = scene.environment;
  losses.push_back(e.pixels.empty() ? "the environment (a uniform ambient light)" : "the environment (an environment map)");
  if (scene.exposure != 1.0f) {
    char text[32];
    const auto written = std::to_chars(text, text + sizeof text, scene.exposure);
    losses.push_back("the exposure " + std::string(text, written.ptr));
  }
  return losses;
}

void writeGltf(const std::filesystem::path& path, const Scene& scene, bool withDefaults) {
  const std::string extension = lowercaseExtension(path);
  if (extension != ".glb" && extension != ".gltf") throw Error(path.string() + ": a glTF file must end in .glb or .gltf");
  std::vector<std::byte> bytes;
  try {
    bytes = encodeGltf(scene, extension == ".glb" ? GltfEncoding::Binary : GltfEncoding::Json, withDefaults);
  } catch (const Error& e) {
    throw Error(path.string() + ": " + e.what());
  }
  writeFileAtomically(path, bytes);
}

}  // namespace glint::scene
