// The path tracer's camera, with the real-time renderer's projection (gl::viewProjection):
// glm::perspective(verticalFovDegrees, width / height), or glm::ortho over a view
// 2 * orthographicHalfHeight high, times glm::lookAt(position, target, up). The ray through film
// point (x, y) pierces the point that the rasteriser shades at window coordinates (x, height - y).
// Film points are in pixels from the image's top-left corner, rows downwards; pixel (i, j) covers
// [i, i + 1) x [j, j + 1), its centre at (i + 0.5, j + 0.5).
#pragma once

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace glint::trace {

struct Ray {
  glm::vec3 origin{0.0f};
  glm::vec3 direction{0.0f, 0.0f, -1.0f};  // unit length
};

// A ray and its two offset rays (pbrt-v3's RayDifferential): through the film point one pixel to
// the right (x + 1) and one pixel down (y + 1, the next image row).
struct RayDifferential {
  Ray ray;
  Ray rx;
  Ray ry;
};

// A pinhole (perspective) or a parallel (orthographic) projection, as scene::Camera says.
class ProjectiveCamera {
 public:
  ProjectiveCamera(const scene::Camera& camera, int width, int height);

  // The primary ray through a film point, with the offset rays one pixel right and down.
  RayDifferential generateRay(glm::vec2 filmPoint) const;
  Ray ray(glm::vec2 filmPoint) const;
  glm::vec3 direction(glm::vec2 filmPoint) const { return ray(filmPoint).direction; }

  // Offset rays for a point p that is not seen directly (a path's later vertices), after pbrt-v4's
  // Camera::Approximate_dp_dxy: rays to p and to the points one pixel away (a pixel's angle from a
  // pinhole, a pixel's width for a parallel projection), so that the footprint there is the one a
  // pixel of this camera would have at that distance.
  RayDifferential approximateRays(glm::vec3 p) const;

  int width() const { return width_; }
  int height() const { return height_; }

 private:
  bool orthographic_;
  glm::vec3 position_;
  glm::vec3 right_;
  glm::vec3 up_;
  glm::vec3 forward_;
  float halfHeight_;  // of the film: at unit distance from a pinhole, in scene units when parallel
  float aspect_;
  int width_;
  int height_;
};

}  // namespace glint::trace
