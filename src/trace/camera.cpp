#include "trace/camera.h"

#include <cmath>

namespace glint::trace {

ProjectiveCamera::ProjectiveCamera(const scene::Camera& camera, int width, int height)
    : orthographic_(camera.projection == scene::Camera::Projection::Orthographic),
      position_(camera.position),
      halfHeight_(orthographic_ ? camera.orthographicHalfHeight
                                : std::tan(glm::radians(camera.verticalFovDegrees) * 0.5f)),
      aspect_(static_cast<float>(width) / static_cast<float>(height)),
      width_(width),
      height_(height) {
  // glm::lookAt's basis: f = normalize(target - eye), s = normalize(cross(f, up)), u = cross(s, f);
  // the view looks along -z of that frame, which is f.
  forward_ = glm::normalize(camera.target - camera.position);
  right_ = glm::normalize(glm::cross(forward_, camera.up));
  up_ = glm::cross(right_, forward_);
}

Ray ProjectiveCamera::ray(glm::vec2 filmPoint) const {
  // Normalised device coordinates: x right, y up (image rows go down).
  const float ndcX = 2.0f * filmPoint.x / static_cast<float>(width_) - 1.0f;
  const float ndcY = 1.0f - 2.0f * filmPoint.y / static_cast<float>(height_);
  const glm::vec3 film = right_ * (ndcX * halfHeight_ * aspect_) + up_ * (ndcY * halfHeight_);
  if (orthographic_) return {position_ + film, forward_};
  return {position_, glm::normalize(film + forward_)};
}

RayDifferential ProjectiveCamera::generateRay(glm::vec2 filmPoint) const {
  RayDifferential r;
  r.ray = ray(filmPoint);
  r.rx = ray(filmPoint + glm::vec2(1.0f, 0.0f));
  r.ry = ray(filmPoint + glm::vec2(0.0f, 1.0f));
  return r;
}

RayDifferential ProjectiveCamera::approximateRays(glm::vec3 p) const {
  RayDifferential r;
  if (orthographic_) {
    // Parallel rays a pixel's width apart, from a unit before p (any start on the line would do).
    const float pixelWidth = 2.0f * halfHeight_ / static_cast<float>(height_);
    const glm::vec3 origin = p - forward_;
    r.ray = {origin, forward_};
    r.rx = {origin + pixelWidth * right_, forward_};
    r.ry = {origin - pixelWidth * up_, forward_};
    return r;
  }
  const glm::vec3 toPoint = p - position_;
  const float distance = glm::length(toPoint);
  if (!(distance > 0.0f)) {
    r.ray = r.rx = r.ry = {position_, forward_};
    return r;
  }
  const glm::vec3 d = toPoint / distance;
  // One pixel's angle at the image centre (square pixels: the same along both axes), applied on
  // axes perpendicular to d that follow the camera's right and down as closely as possible.
  const float pixelAngle = 2.0f * halfHeight_ / static_cast<float>(height_);
  glm::vec3 across = glm::cross(d, up_);
  if (glm::dot(across, across) < 1e-8f) across = glm::cross(d, forward_);
  across = glm::normalize(across);  // towards the camera's right
  const glm::vec3 down = glm::cross(d, across);  // cross(right, forward) is up
  r.ray = {position_, d};
  r.rx = {position_, glm::normalize(d + pixelAngle * across)};
  r.ry = {position_, glm::normalize(d + pixelAngle * down)};
  return r;
}

}  // namespace glint::trace
