// The moments of a normal map's slopes that normal-map filtering reads (kernel/normal_map_filtering.h),
// made from a glTF normal texture: level 0 of the two moment textures; both renderers build their
// mip chains as box averages, which is what keeps the moments exact over any footprint.
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace glint::scene {

struct NormalMapMoments {
  int width = 0;
  int height = 0;
  std::vector<glm::vec3> first;   // (E[sx], E[sy], E[sx^2]) per texel, rows from the top
  std::vector<glm::vec3> second;  // (E[sy^2], E[sx sy], 0)
};

// The slopes s = (-n.x / n.z, -n.y / n.z) of the tangent-space normals n = 2 texel - 1 with
// glTF's normalTexture.scale applied to n.x and n.y, as the shaders perturb the normal; n.z is
// taken at least 0.01 (a normal at or below the surface would have no finite slope). Throws Error
// naming the texture when its data does not match its size.
NormalMapMoments normalMapMoments(const Texture& normalTexture, float normalScale);

}  // namespace glint::scene
