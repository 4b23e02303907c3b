// The scene's triangles in Embree 3 (one triangle geometry per mesh, geometry id = mesh index, so
// a hit names its mesh and triangle; meshes of glTF alphaMode MASK materials let rays through
// where their base colour's alpha is below the cutoff), the surface at a hit interpolated from the mesh's vertices,
// and the uv footprint of a ray differential there (pbrt-v3, section 10.1.1).
#pragma once

#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"
#include "trace/camera.h"

typedef struct RTCDeviceTy* RTCDevice;
typedef struct RTCSceneTy* RTCScene;

namespace glint::trace {

struct Hit {
  float t = 0.0f;
  std::uint32_t mesh = 0;
  std::uint32_t triangle = 0;
  glm::vec2 barycentric{0.0f};  // Embree's (u, v): p = (1 - u - v) p0 + u p1 + v p2
};

class SceneGeometry {
 public:
  // Builds the acceleration structure; throws Error when Embree reports a problem.
  explicit SceneGeometry(const scene::Scene& scene);
  ~SceneGeometry();
  SceneGeometry(const SceneGeometry&) = delete;
  SceneGeometry& operator=(const SceneGeometry&) = delete;

  // The closest hit along the ray within (0, tMax), passing through the back of single-sided
  // triangles (glTF's back-face culling). Thread-safe.
  std::optional<Hit> intersect(const Ray& ray, float tMax = std::numeric_limits<float>::infinity()) const;
  // Whether anything lies along the ray within (0, tMax), either side of any triangle (as the
  // rasteriser's shadow maps). Thread-safe.
  bool occluded(const Ray& ray, float tMax) const;
  // Whether glTF alphaMode MASK cuts the surface away at this point of a triangle (where rays go
  // through it): for points that no ray found, such as a light's samples.
  bool maskedOut(const Hit& at) const;

 private:
  struct AlphaMask;  // glTF alphaMode MASK: what an Embree filter needs to drop a hit
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
  struct HitFilter;  // a mesh's Embree filter: its alpha mask, back-face culling
  std::vector<std::unique_ptr<AlphaMask>> masks_;  // one per masked mesh
  std::vector<std::unique_ptr<HitFilter>> filters_;  // the filters' user data, one per filtered mesh
  std::vector<const AlphaMask*> maskOfMesh_;         // per mesh, null when it has none
};

// The surface at a hit: vertex attributes interpolated with the hit's barycentrics, as the
// rasteriser interpolates them (perspective-correct interpolation is interpolation on the triangle).
struct SurfacePoint {
  glm::vec3 position{0.0f};
  glm::vec3 geometricNormal{0.0f, 0.0f, 1.0f};  // unit, on the counter-clockwise front side
  glm::vec3 normal{0.0f, 0.0f, 1.0f};           // interpolated, unit
  glm::vec4 tangent{1.0f, 0.0f, 0.0f, 1.0f};    // interpolated (xyz not normalised), w its sign
  glm::vec2 uv{0.0f};                           // mesh uv
  glm::vec4 colour{1.0f};                       // interpolated vertex colour (glTF COLOR_0)
  glm::vec3 dpdu{0.0f};                         // the triangle's position derivatives in uv
  glm::vec3 dpdv{0.0f};
  bool uvDegenerate = true;                     // the triangle's uvs span no area
  int material = 0;
};
SurfacePoint surfacePoint(const scene::Scene& scene, const Hit& hit);

// Screen-space derivatives of the mesh uv at p: the offset rays meet the plane of the triangle
// (its geometric normal, as the rasteriser's quads see it) at p + dp/dx and p + dp/dy, and
// duv/dx, duv/dy solve dp/dx = dp/du du/dx + dp/dv dv/dx in the least-squares sense. Zero where
// they are not defined (uv without area, offset rays parallel to the plane).
struct UvDerivatives {
  glm::vec2 duvdx{0.0f};
  glm::vec2 duvdy{0.0f};
};
UvDerivatives uvDerivatives(const SurfacePoint& point, const RayDifferential& rays);

// A ray leaving `point` in direction w, its origin pushed off the surface on w's side so that it
// does not hit its own triangle again.
Ray spawnRay(const SurfacePoint& point, glm::vec3 w);

}  // namespace glint::trace
