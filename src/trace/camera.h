// The pinhole camera of the path tracer, with the real-time renderer's projection: gl::viewProjection
// builds glm::perspective(verticalFovDegrees, width / height) * glm::lookAt(position, target, up);
// the ray through film point (x, y) pierces the point that the rasteriser shades at window
// coordinates (x, height - y). Film points are in pixels from the image's top-left corner, rows
// downwards; pixel (i, j) covers [i, i + 1) x [j, j + 1), its centre at (i + 0.5, j + 0.5).
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

class PinholeCamera {
 public:
  PinholeCamera(const scene::Camera& camera, int width, int height);

  // The primary ray through a film point, with the offset rays one pixel right and down.
  RayDifferential generateRay(glm::vec2 filmPoint) const;
  glm::vec3 direction(glm::vec2 filmPoint) const;  // unit length

  // Offset rays for a point p that is not seen directly (a path's later vertices), after pbrt-v4's
  // Camera::Approximate_dp_dxy: rays from the camera to p and to the points one pixel's angle away,
  // so that the footprint there is the one a pixel of this camera would have at that distance.
  RayDifferential approximateRays(glm::vec3 p) const;

  glm::vec3 position() const { return position_; }
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  glm::vec3 position_;
  glm::vec3 right_;
  glm::vec3 up_;
  glm::vec3 forward_;
  float tanHalfFov_;
  float aspect_;
  int width_;
  int height_;
};

}  // namespace glint::trace
