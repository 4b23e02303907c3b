#include "scene/camera_moves.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace glint::scene {

namespace {

constexpr float kMinDistance = 1e-4f;
constexpr float kMaxDistance = 1e6f;

glm::vec3 rotated(glm::vec3 v, float angle, glm::vec3 axis) {
  return glm::vec3(glm::rotate(glm::mat4(1.0f), angle, axis) * glm::vec4(v, 0.0f));
}

}  // namespace

Camera orbitCamera(const Camera& camera, float yaw, float pitch) {
  const glm::vec3 up = glm::normalize(camera.up);
  glm::vec3 offset = rotated(camera.position - camera.target, yaw, up);
  const float distance = glm::length(offset);
  if (!(distance > 0.0f)) return camera;
  // The angle between the offset and up, kept within [1, 179] degrees.
  const float limit = glm::radians(1.0f);
  const float elevation = std::acos(std::clamp(glm::dot(offset / distance, up), -1.0f, 1.0f));
  const float turned = std::clamp(elevation - pitch, limit, glm::radians(180.0f) - limit);
  // Turning about offset x up by a positive angle takes the offset towards up.
  const glm::vec3 axis = glm::cross(offset, up);
  if (glm::dot(axis, axis) > 0.0f) offset = rotated(offset, elevation - turned, glm::normalize(axis));
  Camera moved = camera;
  moved.position = camera.target + offset;
  return moved;
}

Camera zoomCamera(const Camera& camera, float factor) {
  Camera moved = camera;
  if (camera.projection == Camera::Projection::Orthographic) {
    moved.orthographicHalfHeight = std::clamp(camera.orthographicHalfHeight * factor, kMinDistance, kMaxDistance);
    return moved;
  }
  const glm::vec3 offset = camera.position - camera.target;
  const float distance = glm::length(offset);
  if (!(distance > 0.0f)) return camera;
  moved.position = camera.target + offset * (std::clamp(distance * factor, kMinDistance, kMaxDistance) / distance);
  return moved;
}

Camera panCamera(const Camera& camera, glm::vec2 pixels, int frameHeight) {
  const glm::vec3 forward = glm::normalize(camera.target - camera.position);
  const glm::vec3 right = glm::normalize(glm::cross(forward, camera.up));
  const glm::vec3 up = glm::cross(right, forward);
  // The height of one pixel at the target's depth.
  const float viewHeight = camera.projection == Camera::Projection::Orthographic
                               ? 2.0f * camera.orthographicHalfHeight
                               : 2.0f * glm::length(camera.target - camera.position) *
                                     std::tan(glm::radians(0.5f * camera.verticalFovDegrees));
  const float pixel = viewHeight / static_cast<float>(std::max(frameHeight, 1));
  // The scene follows the cursor: the camera moves the other way.
  const glm::vec3 shift = pixel * (-pixels.x * right + pixels.y * up);
  Camera moved = camera;
  moved.position += shift;
  moved.target += shift;
  return moved;
}

Camera turntableCamera(const Camera& camera, glm::vec3 pivot, float angle) {
  // No turn leaves the camera bit for bit: through the pivot, (p - pivot) + pivot rounds away
  // from p, and the first frame of a sequence must be the still.
  if (angle == 0.0f) return camera;
  const glm::vec3 axis = glm::normalize(camera.up);
  Camera moved = camera;
  moved.position = pivot + rotated(camera.position - pivot, angle, axis);
  moved.target = pivot + rotated(camera.target - pivot, angle, axis);
  return moved;
}

}  // namespace glint::scene
