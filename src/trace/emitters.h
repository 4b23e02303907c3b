// Emissive triangles as lights of the path tracer (docs/trace.md, "Integrator"): every triangle
// whose material emits, chosen in proportion to an estimate of its emitted power and sampled
// uniformly by area (pbrt-v3, sections 13.6.5 and 14.2). The estimate is the luminance of the
// emission at the triangle's centre, its texture filtered over the triangle's uv extent, times its
// area, twice for double-sided materials. A triangle estimated dark is never sampled, and its
// light is left to BSDF sampling (whose weight there is 1): unbiased either way. The integrator
// turns the area density into solid angle at the shaded point.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"
#include "trace/geometry.h"
#include "trace/material.h"
#include "trace/sampling.h"

namespace glint::trace {

struct EmitterSample {
  Hit at;              // the sampled point: mesh, triangle and barycentrics (t unused)
  float areaPdf = 0.0f;  // per square metre of the scene
};

class EmissiveTriangles {
 public:
  EmissiveTriangles(const scene::Scene& scene, const SceneMaterials& materials);

  // No triangle emits (as estimated), or none has area: nothing to sample.
  bool empty() const { return triangles_.empty(); }
  // uTriangle picks the triangle, uPoint the point on it (uniform: sqrt parametrisation).
  EmitterSample sample(float uTriangle, glm::vec2 uPoint) const;
  // The area density of sample() at any point of a mesh's triangle: 0 where nothing is sampled.
  float areaPdf(std::uint32_t mesh, std::uint32_t triangle) const;

 private:
  struct Triangle {
    std::uint32_t mesh;
    std::uint32_t triangle;
    float area;  // 0 for triangles that are never sampled
  };
  std::vector<Triangle> triangles_;  // every triangle of the emitting meshes, in mesh order
  std::vector<std::int64_t> firstOfMesh_;  // per mesh, its first triangle in triangles_, or -1
  Distribution1D power_{std::vector<float>{}};
};

}  // namespace glint::trace
