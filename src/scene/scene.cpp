#include "scene/scene.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <sstream>

#include "glint/error.h"
#include "glint/kernel/lights.h"

namespace glint::scene {

// A turn about +y by `angle`: x' = x cos + z sin, z' = z cos - x sin (counter-clockwise seen from +y).
static glm::vec3 turnedAboutY(glm::vec3 d, float angle) {
  const float c = std::cos(angle);
  const float s = std::sin(angle);
  return {c * d.x + s * d.z, d.y, c * d.z - s * d.x};
}

glm::vec3 Environment::mapDirection(glm::vec3 world) const { return turnedAboutY(world, -rotation); }
glm::vec3 Environment::worldDirection(glm::vec3 map) const { return turnedAboutY(map, rotation); }

glm::vec3 Scene::boundsMin() const {
  glm::vec3 low(std::numeric_limits<float>::max());
  for (const Mesh& mesh : meshes) {
    for (const Vertex& v : mesh.vertices) low = glm::min(low, v.position);
  }
  return low;
}

glm::vec3 Scene::boundsMax() const {
  glm::vec3 high(std::numeric_limits<float>::lowest());
  for (const Mesh& mesh : meshes) {
    for (const Vertex& v : mesh.vertices) high = glm::max(high, v.position);
  }
  return high;
}

float alphaFromRoughness(float roughness) { return std::max(roughness * roughness, 0.01f); }

kernel::GlintMaterial glintMaterial(const GlintLayer& layer, const MicrofacetTarget& target) {
  kernel::GlintMaterial m = layer;  // the block as the layer holds it, then what the material decides
  m.hasLogDensityTexture = layer.logDensityTexture >= 0 ? 1u : 0u;
  m.ndf = target.ndf;
  m.masking = target.masking;
  m.multipleScattering = target.multipleScattering ? 1u : 0u;
  m.enabled = layer.enabled != 0u ? 1u : 0u;
  m.colouredCells = layer.colouredCells != 0u ? 1u : 0u;
  m.padding1 = m.padding2 = 0u;  // so that equal layers pack to equal bytes
  return m;
}

void validateGlintLayer(const GlintLayer& layer, std::size_t textureCount) {
  // The layer's own values, before any texture: the kernel's view of them, validated by its rules.
  const GlintParameters constants = kernel::glintMaterialConstants(glintMaterial(layer), exactFootprintPolicy());
  validateGlintParameters(constants);
  if (!(layer.uvScale > 0.0f) || !std::isfinite(layer.uvScale)) {
    std::ostringstream message;
    message << "uv_scale must be positive and finite, got " << layer.uvScale;
    throw Error(message.str());
  }
  // The ends of the range are log densities too: check them with the kernel's own rule.
  for (float end : {layer.logDensityRange.x, layer.logDensityRange.y}) {
    GlintParameters p = constants;
    p.logDensity = end;
    try {
      validateGlintParameters(p);
    } catch (const Error& e) {
      throw Error(std::string("log_density_range: ") + e.what());
    }
  }
  const std::pair<const char*, int> textures[] = {{"roughness_texture", layer.roughnessTexture},
                                                  {"log_density_texture", layer.logDensityTexture},
                                                  {"relative_area_texture", layer.relativeAreaTexture}};
  for (const auto& [field, index] : textures) {
    if (index < -1 || (index >= 0 && static_cast<std::size_t>(index) >= textureCount)) {
      std::ostringstream message;
      message << field << " " << index << " is not a texture (the scene has " << textureCount << ")";
      throw Error(message.str());
    }
  }
}

VisibleGlintDensity visibleGlintDensity(const Scene& scene, int material) {
  double uvArea = 0.0;
  double worldArea = 0.0;
  glm::dvec3 weightedCentre(0.0);
  for (const Mesh& mesh : scene.meshes) {
    if (mesh.material != material) continue;
    for (std::size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
      const Vertex& a = mesh.vertices[mesh.indices[i]];
      const Vertex& b = mesh.vertices[mesh.indices[i + 1]];
      const Vertex& c = mesh.vertices[mesh.indices[i + 2]];
      const glm::dvec3 ab = glm::dvec3(b.position) - glm::dvec3(a.position);
      const glm::dvec3 ac = glm::dvec3(c.position) - glm::dvec3(a.position);
      const double area = 0.5 * glm::length(glm::cross(ab, ac));
      const glm::dvec2 uvAb = glm::dvec2(b.uv) - glm::dvec2(a.uv);
      const glm::dvec2 uvAc = glm::dvec2(c.uv) - glm::dvec2(a.uv);
      uvArea += 0.5 * std::abs(uvAb.x * uvAc.y - uvAb.y * uvAc.x);
      worldArea += area;
      weightedCentre += area * (glm::dvec3(a.position) + glm::dvec3(b.position) + glm::dvec3(c.position)) / 3.0;
    }
  }
  VisibleGlintDensity density;
  if (!(uvArea > 0.0 && worldArea > 0.0 && std::isfinite(uvArea) && std::isfinite(worldArea))) return density;
  const auto found = scene.cameras.find("default");
  const Camera camera = found != scene.cameras.end() ? found->second
                                                     : standardCameras(scene.boundsMin(), scene.boundsMax()).at("default");
  const double frame = static_cast<double>(kVisibleGlintFrameSize);
  if (camera.projection == Camera::Projection::Orthographic) {
    density.pixelSide = 2.0 * camera.orthographicHalfHeight / frame;
  } else {
    const double distance = glm::length(weightedCentre / worldArea - glm::dvec3(camera.position));
    density.pixelSide = 2.0 * distance * std::tan(0.5 * glm::radians(double(camera.verticalFovDegrees))) / frame;
  }
  density.hasUvArea = true;
  // In the base colour texture's uv, where the layer lies (its KHR_texture_transform scales areas by
  // the determinant of its linear part).
  const glm::mat2 linear = scene.materials[static_cast<std::size_t>(material)].baseColourUv.linear();
  density.uvAreaPerSquareMetre = uvArea / worldArea * std::abs(double(glm::determinant(linear)));
  const double uvAreaPerPixel = density.uvAreaPerSquareMetre * density.pixelSide * density.pixelSide;
  // A camera at the material's centre sees no pixel there: the densest layer accepted.
  const double logDensity = uvAreaPerPixel > 0.0 ? std::log(kVisibleGlintMicrofacetsPerPixel / uvAreaPerPixel)
                                                 : double(kMaxLogDensity);
  density.logDensity = static_cast<float>(
      std::clamp(std::round(10.0 * logDensity) / 10.0, double(kMinLogDensity), double(kMaxLogDensity)));
  return density;
}

std::vector<std::size_t> applyGlint(Scene& scene, const std::vector<std::string>& materialNames) {
  std::vector<bool> named(scene.materials.size(), false);
  for (const std::string& name : materialNames) {
    bool found = false;
    for (std::size_t i = 0; i < scene.materials.size(); ++i) {
      if (name == "*" || scene.materials[i].name == name) {
        named[i] = true;
        found = true;
      }
    }
    if (!found) {
      std::ostringstream message;
      message << "no material '" << name << "' in scene '" << scene.name << "' (materials:";
      for (std::size_t i = 0; i < scene.materials.size(); ++i) {
        message << (i == 0 ? " '" : ", '") << scene.materials[i].name << "'";
      }
      if (scene.materials.empty()) message << " none";
      message << "; '*' names them all)";
      throw Error(message.str());
    }
  }
  std::vector<std::size_t> layered;
  for (std::size_t i = 0; i < scene.materials.size(); ++i) {
    Material& material = scene.materials[i];
    if (!named[i] || material.glint.enabled) continue;
    GlintLayer layer;
    layer.enabled = true;
    layer.alpha = glm::vec2(alphaFromRoughness(material.roughness));
    layer.logDensity = visibleGlintDensity(scene, static_cast<int>(i)).logDensity;
    material.glint = layer;
    layered.push_back(i);
  }
  return layered;
}

std::map<std::string, Camera> standardCameras(glm::vec3 low, glm::vec3 high) {
  const glm::vec3 centre = 0.5f * (low + high);
  // At least a millimetre, so that a flat or point-like scene still gets a usable camera.
  const float radius = std::max(0.5f * glm::length(high - low), 1e-3f);
  Camera base;
  base.target = centre;
  base.verticalFovDegrees = 45.0f;
  // The sphere is tangent to the view cone at distance radius / sin(fov / 2); 10% more is the margin.
  const float distance = 1.1f * radius / std::sin(glm::radians(0.5f * base.verticalFovDegrees));
  auto at = [&](glm::vec3 offset, glm::vec3 up) {
    Camera camera = base;
    camera.position = centre + offset;
    camera.up = up;
    return camera;
  };
  std::map<std::string, Camera> cameras = {
      {"front", at({0, 0, distance}, {0, 1, 0})},
      {"side", at({distance, 0, 0}, {0, 1, 0})},
      {"top", at({0, distance, 0}, {0, 0, -1})},
      {"close", at({0, 0, 0.5f * distance}, {0, 1, 0})},
  };
  // The default looks from the front (+z), unless the model is flat along y or x (a floor or a leaf
  // lying in the xz plane, a panel in the yz plane: under a tenth of its largest extent and thinner
  // than along z), which the front sees edge-on: then from above or from the side.
  const glm::vec3 extent = high - low;
  const float flat = 0.1f * std::max({extent.x, extent.y, extent.z});
  const char* view = extent.y <= flat && extent.y < extent.z   ? "top"
                     : extent.x <= flat && extent.x < extent.z ? "side"
                                                               : "front";
  cameras["default"] = cameras.at(view);
  return cameras;
}

bool sameView(const Camera& a, const Camera& b) {
  return a.position == b.position && a.target == b.target && a.up == b.up && a.projection == b.projection &&
         a.verticalFovDegrees == b.verticalFovDegrees && a.orthographicHalfHeight == b.orthographicHalfHeight;
}

glm::mat2 UvTransform::linear() const {
  const float c = std::cos(rotation);
  const float s = std::sin(rotation);
  // Columns: where (1, 0) and (0, 1) go.
  return glm::mat2(c * scale.x, -s * scale.x, s * scale.y, c * scale.y);
}

glm::vec2 Light::coneScaleOffset() const {
  return type == Type::Spot ? kernel::glintSpotConeScaleOffset(innerConeAngle, outerConeAngle) : glm::vec2(0.0f, 1.0f);
}

float Light::inverseRange() const { return positional() && range > 0.0f ? 1.0f / range : 0.0f; }

glm::vec3 Light::spotAxis() const { return type == Type::Spot ? glm::normalize(direction) : glm::vec3(0, -1, 0); }

void addDefaultLighting(Scene& scene) {
  const glm::vec3 low = scene.boundsMin();
  const glm::vec3 high = scene.boundsMax();
  const glm::vec3 centre = 0.5f * (low + high);
  const float radius = std::max(0.5f * glm::length(high - low), 1e-3f);

  // Irradiance 2 W/m^2 at the centre (inverse square law), so it does not depend on the scene's size.
  Light point;
  point.type = Light::Type::Point;
  const float distance = 3.0f * radius;
  point.position = centre + distance * glm::normalize(glm::vec3(0.6f, 0.9f, 1.0f));
  point.intensity = glm::vec3(2.0f * distance * distance);
  scene.lights.push_back(point);

  Light sun;
  sun.type = Light::Type::Directional;
  sun.direction = glm::normalize(glm::vec3(1.0f, -1.0f, -0.5f));
  sun.intensity = glm::vec3(1.0f, 0.97f, 0.92f);
  scene.lights.push_back(sun);
  scene.defaultLights = true;

  scene.environment = Environment{};
  scene.environment.uniform = glm::vec3(0.26f, 0.3f, 0.36f);
  scene.environment.intensity = 1.0f;
}

}  // namespace glint::scene
