// The viewer's camera moves (glint view: drag to orbit, scroll to zoom, right-drag to pan), as pure
// functions of a Camera so that they are tested without a window.
#pragma once

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace glint::scene {

// Turns the camera about its target: by `yaw` radians about its up vector (a turntable), then by
// `pitch` radians towards it (positive: the camera rises, looking more down). The distance to the
// target is kept, and the view stays at least a degree away from up and from down, where the
// turntable would flip.
Camera orbitCamera(const Camera& camera, float yaw, float pitch);

// Comes closer by `factor` (< 1) or backs away (> 1): a perspective camera's distance to its
// target, an orthographic camera's view height. Distances stay within [1e-4, 1e6].
Camera zoomCamera(const Camera& camera, float factor);

// Slides the camera and its target across the view so that what lies at the target's depth moves
// by `pixels` on a frame `frameHeight` pixels high (x right, y down, as image rows).
Camera panCamera(const Camera& camera, glm::vec2 pixels, int frameHeight);

// Turns the camera and its target by `angle` radians about the axis through `pivot` along the
// camera's up vector: frame after frame, a turntable around the pivot (glint render --orbit). An
// angle of 0 returns the camera unchanged, bit for bit.
Camera turntableCamera(const Camera& camera, glm::vec3 pivot, float angle);

}  // namespace glint::scene
