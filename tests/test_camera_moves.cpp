// The viewer's camera moves (scene/camera_moves.h): orbit, zoom and pan, checked against the
// rasteriser's own projection where it matters (what the user sees move on screen).
#include <cmath>

#include <gtest/gtest.h>

#include "gl/renderer.h"
#include "scene/camera_moves.h"

namespace glint {
namespace {

using scene::Camera;

Camera obliqueCamera(Camera::Projection projection) {
  Camera camera;
  camera.position = {1.3f, 0.7f, 2.9f};
  camera.target = {-0.2f, 0.1f, 0.0f};
  camera.up = {0.0f, 1.0f, 0.0f};
  camera.verticalFovDegrees = 37.0f;
  camera.projection = projection;
  camera.orthographicHalfHeight = 1.2f;
  return camera;
}

// Image coordinates (x right, y down, in pixels) of a world point, by gl::viewProjection.
glm::dvec2 imagePoint(const Camera& camera, glm::vec3 p, int width, int height) {
  const glm::dvec4 clip =
      glm::dmat4(gl::viewProjection(camera, width, height, glm::vec2(0.0f), glm::vec3(-2.0f), glm::vec3(2.0f))) *
      glm::dvec4(glm::dvec3(p), 1.0);
  return {(clip.x / clip.w + 1.0) * 0.5 * width, (1.0 - clip.y / clip.w) * 0.5 * height};
}

float angleToUp(const Camera& camera) {
  return std::acos(glm::dot(glm::normalize(camera.position - camera.target), glm::normalize(camera.up)));
}

TEST(CameraMoves, OrbitTurnsAboutTheTargetAtTheSameDistance) {
  const Camera start = obliqueCamera(Camera::Projection::Perspective);
  const float distance = glm::length(start.position - start.target);
  // A yaw turns the offset about up by that angle, leaving its height.
  const Camera turned = scene::orbitCamera(start, 0.5f, 0.0f);
  EXPECT_EQ(turned.target, start.target);
  EXPECT_NEAR(glm::length(turned.position - turned.target), distance, 1e-5f);
  EXPECT_NEAR(turned.position.y, start.position.y, 1e-5f);
  const glm::vec2 before(start.position.x - start.target.x, start.position.z - start.target.z);
  const glm::vec2 after(turned.position.x - turned.target.x, turned.position.z - turned.target.z);
  EXPECT_NEAR(std::acos(glm::dot(before, after) / (glm::length(before) * glm::length(after))), 0.5f, 1e-5f);
  // A whole turn comes back.
  const Camera round = scene::orbitCamera(start, 2.0f * 3.14159265f, 0.0f);
  EXPECT_NEAR(glm::length(round.position - start.position), 0.0f, 1e-5f);
  // A positive pitch raises the camera by that angle, towards up.
  const Camera raised = scene::orbitCamera(start, 0.0f, 0.2f);
  EXPECT_NEAR(angleToUp(raised), angleToUp(start) - 0.2f, 1e-5f);
  EXPECT_NEAR(glm::length(raised.position - raised.target), distance, 1e-5f);
  EXPECT_GT(raised.position.y, start.position.y);
  // The pitch stops a degree short of straight above and below, where the view would flip.
  EXPECT_NEAR(angleToUp(scene::orbitCamera(start, 0.0f, 10.0f)), glm::radians(1.0f), 1e-4f);
  EXPECT_NEAR(angleToUp(scene::orbitCamera(start, 0.0f, -10.0f)), glm::radians(179.0f), 1e-4f);
}

TEST(CameraMoves, ZoomScalesTheDistanceOrTheOrthographicView) {
  const Camera perspective = obliqueCamera(Camera::Projection::Perspective);
  const Camera closer = scene::zoomCamera(perspective, 0.5f);
  EXPECT_NEAR(glm::length(closer.position - closer.target), 0.5f * glm::length(perspective.position - perspective.target),
              1e-5f);
  EXPECT_NEAR(glm::length(glm::normalize(closer.position - closer.target) -
                          glm::normalize(perspective.position - perspective.target)),
              0.0f, 1e-6f);
  const Camera orthographic = obliqueCamera(Camera::Projection::Orthographic);
  const Camera narrower = scene::zoomCamera(orthographic, 0.5f);
  EXPECT_FLOAT_EQ(narrower.orthographicHalfHeight, 0.6f);
  EXPECT_EQ(narrower.position, orthographic.position);  // a parallel view does not grow by coming closer
  // Bounded: a runaway scroll neither reaches the target nor leaves for infinity.
  EXPECT_GT(glm::length(scene::zoomCamera(perspective, 0.0f).position - perspective.target), 0.0f);
  EXPECT_LE(scene::zoomCamera(orthographic, 1e30f).orthographicHalfHeight, 1e6f);
}

TEST(CameraMoves, PanMovesTheTargetsDepthByThePixelsDragged) {
  const int width = 320;
  const int height = 240;
  for (const auto projection : {Camera::Projection::Perspective, Camera::Projection::Orthographic}) {
    const Camera start = obliqueCamera(projection);
    const glm::vec2 drag(25.0f, -12.0f);  // right and up on screen
    const Camera moved = scene::panCamera(start, drag, height);
    // A slide, not a turn: camera and target move alike.
    EXPECT_NEAR(glm::length((moved.target - start.target) - (moved.position - start.position)), 0.0f, 1e-6f);
    // The old target, a point at the target's depth, followed the cursor.
    const glm::dvec2 was = imagePoint(start, start.target, width, height);
    const glm::dvec2 now = imagePoint(moved, start.target, width, height);
    EXPECT_NEAR(was.x, 0.5 * width, 1e-3);
    EXPECT_NEAR(was.y, 0.5 * height, 1e-3);
    EXPECT_NEAR(now.x - was.x, drag.x, 1e-2) << static_cast<int>(projection);
    EXPECT_NEAR(now.y - was.y, drag.y, 1e-2) << static_cast<int>(projection);
  }
}

TEST(CameraMoves, TurntableTurnsCameraAndTargetAboutTheUpAxisThroughThePivot) {
  Camera start;
  start.position = {1.0f, 0.5f, 5.0f};
  start.target = {1.0f, 0.0f, 3.0f};
  start.up = {0.0f, 2.0f, 0.0f};  // not unit length
  const glm::vec3 pivot(1.0f, -4.0f, 2.0f);
  // A quarter turn about +y takes +z to +x: the offsets (0, ., 3) and (0, ., 1) from the pivot's
  // axis become (3, ., 0) and (1, ., 0), heights unchanged.
  const Camera quarter = scene::turntableCamera(start, pivot, 0.5f * 3.14159265f);
  EXPECT_NEAR(glm::length(quarter.position - glm::vec3(4.0f, 0.5f, 2.0f)), 0.0f, 1e-5f);
  EXPECT_NEAR(glm::length(quarter.target - glm::vec3(2.0f, 0.0f, 2.0f)), 0.0f, 1e-5f);
  EXPECT_EQ(quarter.up, start.up);
  EXPECT_EQ(quarter.verticalFovDegrees, start.verticalFovDegrees);
  // No turn is the camera itself, bit for bit, wherever the pivot is (a still is not moved by
  // float rounding through the pivot): the first frame of a sequence is the still.
  Camera oblique = obliqueCamera(Camera::Projection::Perspective);
  for (const glm::vec3 somewhere : {glm::vec3(0.3f, -1.7f, 0.11f), glm::vec3(1.3e3f, 0.7f, -2.9f)}) {
    const Camera none = scene::turntableCamera(oblique, somewhere, 0.0f);
    EXPECT_EQ(none.position, oblique.position);
    EXPECT_EQ(none.target, oblique.target);
  }
}

}  // namespace
}  // namespace glint
