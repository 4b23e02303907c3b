// Area lights: the emissive rectangles of a scene, which the rasteriser draws as lights (both lobes
// and the glint layer by their solid angle, docs/method.md section 8) as the path tracer draws
// every emissive triangle. The scene keeps one description of such a light, its emissive mesh: the
// path tracer samples its triangles, the rasteriser finds it here.
#pragma once

#include <array>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace glint::scene {

struct AreaLight {
  // World positions, in order around the light, counter-clockwise seen from its front (the side its
  // triangles face).
  std::array<glm::vec3, 4> corners;
  glm::vec3 radiance{0.0f};  // W/(m^2 sr): the emissive factor times KHR_materials_emissive_strength
  bool twoSided = false;     // the material's doubleSided: it emits from both faces
  int mesh = -1;             // the emissive mesh it is

  glm::vec3 centre() const { return 0.25f * (corners[0] + corners[1] + corners[2] + corners[3]); }
  glm::vec3 normal() const;  // unit, towards its front
  float area() const;
};

// A mesh is an area light when its material emits (emissive factor above zero) uniformly (no
// emissive texture) and its triangles cover one flat convex quadrilateral: exactly four distinct
// vertex positions, the fourth within 0.1% of the quadrilateral's diagonal of the plane of the
// other three, convex, every triangle facing the same side. Other emitters (textured, curved,
// discs, many-sided) glow in the rasteriser without lighting anything; the path tracer lights with
// them all. `skipped` names each emitter that is not an area light and why.
struct AreaLights {
  std::vector<AreaLight> lights;
  std::vector<std::string> skipped;
};
AreaLights findAreaLights(const Scene& scene);

// An emissive rectangle added to the scene as a mesh of its own material (radiance `radiance`,
// one-sided): `width` x `height` metres centred at `centre`, facing `target`, its width level (along
// the horizontal perpendicular to the direction it faces). Returns the mesh's index.
int addRectangleLight(Scene& scene, glm::vec3 centre, glm::vec3 target, float width, float height, glm::vec3 radiance);

}  // namespace glint::scene
