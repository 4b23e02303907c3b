#include "scene/area_lights.h"

#include <algorithm>
#include <cmath>

#include "scene/geometry.h"

namespace glint::scene {

glm::vec3 AreaLight::normal() const {
  return glm::normalize(glm::cross(corners[1] - corners[0], corners[3] - corners[0]));
}

float AreaLight::area() const {
  return 0.5f * glm::length(glm::cross(corners[2] - corners[0], corners[3] - corners[1]));
}

namespace {

// The mesh as an area light, or the reason it is not one.
bool quadrilateralOf(const Mesh& mesh, AreaLight& light, std::string& why) {
  std::vector<glm::vec3> distinct;
  glm::vec3 low(1e30f), high(-1e30f);
  for (const Vertex& v : mesh.vertices) {
    low = glm::min(low, v.position);
    high = glm::max(high, v.position);
  }
  const float size = glm::length(high - low);
  if (!(size > 0.0f) || !std::isfinite(size)) {
    why = "has no extent";
    return false;
  }
  for (const Vertex& v : mesh.vertices) {
    const bool known = std::any_of(distinct.begin(), distinct.end(),
                                   [&](glm::vec3 p) { return glm::length(p - v.position) <= 1e-5f * size; });
    if (!known) distinct.push_back(v.position);
    if (distinct.size() > 4) break;
  }
  if (distinct.size() != 4) {
    why = "is not a quadrilateral (" + std::string(distinct.size() > 4 ? "more than 4" : std::to_string(distinct.size())) +
          " distinct vertices)";
    return false;
  }
  if (mesh.indices.size() < 3) {
    why = "has no triangle";
    return false;
  }
  // The front: the first triangle's counter-clockwise normal, as the path tracer's geometric normal.
  const glm::vec3 a = mesh.vertices[mesh.indices[0]].position;
  const glm::vec3 b = mesh.vertices[mesh.indices[1]].position;
  const glm::vec3 c = mesh.vertices[mesh.indices[2]].position;
  const glm::vec3 front = glm::cross(b - a, c - a);
  if (!(glm::length(front) > 0.0f)) {
    why = "has a degenerate triangle";
    return false;
  }
  const glm::vec3 normal = glm::normalize(front);
  for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const glm::vec3 p = mesh.vertices[mesh.indices[t]].position;
    const glm::vec3 n = glm::cross(mesh.vertices[mesh.indices[t + 1]].position - p, mesh.vertices[mesh.indices[t + 2]].position - p);
    if (glm::dot(n, normal) < 0.0f) {
      why = "has triangles facing both ways";
      return false;
    }
  }
  glm::vec3 centre(0.0f);
  for (const glm::vec3& p : distinct) centre += 0.25f * p;
  for (const glm::vec3& p : distinct) {
    if (std::abs(glm::dot(p - centre, normal)) > 1e-3f * size) {
      why = "is not flat";
      return false;
    }
  }
  // In order around the centre, counter-clockwise about the normal.
  const glm::vec3 u = glm::normalize(distinct[0] - centre);
  const glm::vec3 v = glm::cross(normal, u);
  std::sort(distinct.begin(), distinct.end(), [&](glm::vec3 p, glm::vec3 q) {
    return std::atan2(glm::dot(p - centre, v), glm::dot(p - centre, u)) < std::atan2(glm::dot(q - centre, v), glm::dot(q - centre, u));
  });
  for (int k = 0; k < 4; ++k) {
    const glm::vec3 e0 = distinct[(k + 1) % 4] - distinct[k];
    const glm::vec3 e1 = distinct[(k + 2) % 4] - distinct[(k + 1) % 4];
    if (!(glm::dot(glm::cross(e0, e1), normal) > 0.0f)) {
      why = "is not convex";
      return false;
    }
  }
  for (int k = 0; k < 4; ++k) light.corners[static_cast<std::size_t>(k)] = distinct[static_cast<std::size_t>(k)];
  return true;
}

}  // namespace

AreaLights findAreaLights(const Scene& scene) {
  AreaLights found;
  for (std::size_t i = 0; i < scene.meshes.size(); ++i) {
    const Mesh& mesh = scene.meshes[i];
    if (mesh.material < 0 || mesh.material >= static_cast<int>(scene.materials.size())) continue;
    const Material& material = scene.materials[static_cast<std::size_t>(mesh.material)];
    if (!(glm::max(material.emissive.r, glm::max(material.emissive.g, material.emissive.b)) > 0.0f)) continue;
    const std::string name = "emissive mesh " + std::to_string(i) + " '" + mesh.name + "'";
    if (material.emissiveTexture >= 0) {
      found.skipped.push_back(name + " has an emissive texture");
      continue;
    }
    AreaLight light;
    std::string why;
    if (!quadrilateralOf(mesh, light, why)) {
      found.skipped.push_back(name + " " + why);
      continue;
    }
    light.radiance = material.emissive;
    light.twoSided = material.doubleSided;
    light.mesh = static_cast<int>(i);
    found.lights.push_back(light);
  }
  return found;
}

int addRectangleLight(Scene& scene, glm::vec3 centre, glm::vec3 target, float width, float height, glm::vec3 radiance) {
  glm::vec3 facing = target - centre;
  facing = glm::length(facing) > 0.0f ? glm::normalize(facing) : glm::vec3(0.0f, -1.0f, 0.0f);
  // Level: its width along the horizontal perpendicular to where it faces (x for a light facing
  // straight down or up).
  glm::vec3 across = glm::cross(glm::vec3(0.0f, 1.0f, 0.0f), facing);
  across = glm::length(across) > 1e-4f ? glm::normalize(across) : glm::vec3(1.0f, 0.0f, 0.0f);
  glm::vec3 up = glm::cross(facing, across);
  Material material;
  material.name = "rectangle light " + std::to_string(scene.meshes.size());
  material.baseColour = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
  material.roughness = 1.0f;
  material.emissive = radiance;
  scene.materials.push_back(material);
  // makeQuad faces cross(halfV, halfU): halfU = up, halfV = across faces cross(across, up) = facing.
  scene.meshes.push_back(makeQuad(material.name, static_cast<int>(scene.materials.size()) - 1, centre, 0.5f * height * up,
                                  0.5f * width * across));
  return static_cast<int>(scene.meshes.size()) - 1;
}

}  // namespace glint::scene
