#include "scene/view_controls.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/quaternion.hpp>

namespace glint::scene {

namespace {

// The unit direction of an azimuth and elevation (LightControls' convention).
glm::vec3 directionOf(float azimuth, float elevation) {
  return {std::cos(elevation) * std::sin(azimuth), std::sin(elevation), std::cos(elevation) * std::cos(azimuth)};
}

// From the pivot towards the light, not normalised; zero for a light at the pivot.
glm::vec3 towardsLight(const Light& light, glm::vec3 pivot) {
  return light.positional() ? light.position - pivot : -light.direction;
}

float strengthOf(glm::vec3 intensity) { return std::max({intensity.x, intensity.y, intensity.z}); }

}  // namespace

MaterialControls materialControls(const Material& material) {
  const GlintLayer& layer = material.glint;
  return {layer.alpha, layer.rho, layer.logDensity, layer.relativeArea, material.specular};
}

Material applyMaterialControls(const Material& material, const MaterialControls& controls) {
  Material edited = material;
  edited.glint.alpha = controls.alpha;
  edited.glint.rho = controls.rho;
  edited.glint.logDensity = controls.logDensity;
  edited.glint.relativeArea = controls.relativeArea;
  edited.specular = controls.specular;
  return edited;
}

LightControls lightControls(const Light& light, glm::vec3 pivot) {
  const glm::vec3 towards = towardsLight(light, pivot);
  LightControls controls;
  controls.strength = strengthOf(light.intensity);
  const float length = glm::length(towards);
  if (!(length > 0.0f)) {
    controls.elevation = glm::half_pi<float>();
    return controls;
  }
  const glm::vec3 d = towards / length;
  controls.azimuth = std::atan2(d.x, d.z);
  controls.elevation = std::asin(std::clamp(d.y, -1.0f, 1.0f));
  return controls;
}

Light applyLightControls(const Light& light, const LightControls& controls, glm::vec3 pivot) {
  const LightControls own = lightControls(light, pivot);
  Light edited = light;
  if (controls.azimuth != own.azimuth || controls.elevation != own.elevation) {
    const glm::vec3 direction = directionOf(controls.azimuth, controls.elevation);
    if (!light.positional()) {
      edited.direction = -direction;
    } else {
      const glm::vec3 towards = towardsLight(light, pivot);
      const float distance = glm::length(towards);
      edited.position = pivot + direction * distance;
      if (light.type == Light::Type::Spot && distance > 0.0f) {
        edited.direction = glm::normalize(glm::quat(towards / distance, direction) * light.direction);
      }
    }
  }
  if (controls.strength != own.strength) {
    edited.intensity = own.strength > 0.0f ? light.intensity * (controls.strength / own.strength)
                                           : glm::vec3(controls.strength);
  }
  return edited;
}

glm::vec3 lightPivot(const Scene& scene) { return 0.5f * (scene.boundsMin() + scene.boundsMax()); }

ViewControls viewControls(const Scene& scene, glm::vec3 pivot) {
  ViewControls controls;
  for (const Material& material : scene.materials) controls.materials.push_back(materialControls(material));
  for (const Light& light : scene.lights) controls.lights.push_back(lightControls(light, pivot));
  return controls;
}

void applyViewControls(const Scene& scene, const ViewControls& controls, glm::vec3 pivot,
                       std::vector<Material>& materials, std::vector<Light>& lights) {
  materials.resize(scene.materials.size());
  for (std::size_t i = 0; i < scene.materials.size(); ++i) {
    materials[i] = applyMaterialControls(scene.materials[i], controls.materials.at(i));
  }
  lights.resize(scene.lights.size());
  for (std::size_t i = 0; i < scene.lights.size(); ++i) {
    lights[i] = applyLightControls(scene.lights[i], controls.lights.at(i), pivot);
  }
}

}  // namespace glint::scene
