#include "trace/emitters.h"

#include <cmath>

namespace glint::trace {

EmissiveTriangles::EmissiveTriangles(const scene::Scene& scene, const SceneMaterials& materials)
    : firstOfMesh_(scene.meshes.size(), -1) {
  std::vector<float> power;
  for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
    const scene::Mesh& mesh = scene.meshes[m];
    const scene::Material& material = scene.materials[static_cast<std::size_t>(mesh.material)];
    if (material.emissive == glm::vec3(0.0f) || mesh.indices.size() < 3) continue;
    const float sides = material.doubleSided ? 2.0f : 1.0f;
    firstOfMesh_[m] = static_cast<std::int64_t>(triangles_.size());
    for (std::size_t t = 0; t < mesh.indices.size() / 3; ++t) {
      const scene::Vertex& a = mesh.vertices[mesh.indices[3 * t]];
      const scene::Vertex& b = mesh.vertices[mesh.indices[3 * t + 1]];
      const scene::Vertex& c = mesh.vertices[mesh.indices[3 * t + 2]];
      const float area = 0.5f * glm::length(glm::cross(b.position - a.position, c.position - a.position));
      const SurfacePoint centre =
          surfacePoint(scene, Hit{0.0f, static_cast<std::uint32_t>(m), static_cast<std::uint32_t>(t), glm::vec2(1.0f / 3.0f)});
      // Two edges in uv as the footprint: the texture's level of detail spans the triangle.
      const UvDerivatives extent{b.uv - a.uv, c.uv - a.uv};
      const float radiance = luminance(materials.emission(centre, extent, centre.geometricNormal));
      const float weight = sides * radiance * area;
      const bool usable = area > 0.0f && weight > 0.0f && std::isfinite(weight);
      triangles_.push_back({static_cast<std::uint32_t>(m), static_cast<std::uint32_t>(t), usable ? area : 0.0f});
      power.push_back(usable ? weight : 0.0f);
    }
  }
  double total = 0.0;
  for (float p : power) total += p;
  if (!(total > 0.0) || !std::isfinite(total)) {
    // Distribution1D would fall back to uniform over triangles that emit nothing.
    triangles_.clear();
    firstOfMesh_.assign(scene.meshes.size(), -1);
    return;
  }
  power_ = Distribution1D(power);
}

EmitterSample EmissiveTriangles::sample(float uTriangle, glm::vec2 uPoint) const {
  int cell = 0;
  power_.sample(uTriangle, nullptr, &cell);
  const Triangle& triangle = triangles_[static_cast<std::size_t>(cell)];
  // Uniform on the triangle (pbrt-v3, UniformSampleTriangle): barycentrics (1 - sqrt(u0),
  // u1 sqrt(u0)) of the first two corners; Embree's (u, v) weigh the second and third.
  const float root = std::sqrt(uPoint.x);
  const float w0 = 1.0f - root;
  const float w1 = uPoint.y * root;
  EmitterSample s;
  s.at = Hit{0.0f, triangle.mesh, triangle.triangle, glm::vec2(w1, 1.0f - w0 - w1)};
  s.areaPdf = triangle.area > 0.0f ? power_.cellProbability(cell) / triangle.area : 0.0f;
  return s;
}

float EmissiveTriangles::areaPdf(std::uint32_t mesh, std::uint32_t triangle) const {
  if (mesh >= firstOfMesh_.size() || firstOfMesh_[mesh] < 0) return 0.0f;
  const auto index = static_cast<std::size_t>(firstOfMesh_[mesh]) + triangle;
  const Triangle& t = triangles_[index];
  return t.area > 0.0f ? power_.cellProbability(static_cast<int>(index)) / t.area : 0.0f;
}

}  // namespace glint::trace
