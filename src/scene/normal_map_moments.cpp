#include "scene/normal_map_moments.h"

#include <algorithm>

#include "glint/error.h"

namespace glint::scene {

NormalMapMoments normalMapMoments(const Texture& normalTexture, float normalScale) {
  const std::size_t count = static_cast<std::size_t>(normalTexture.width) * static_cast<std::size_t>(normalTexture.height);
  if (normalTexture.width < 1 || normalTexture.height < 1 || normalTexture.rgba.size() != 4 * count) {
    throw Error("normal texture '" + normalTexture.name + "': size and data do not agree");
  }
  NormalMapMoments moments;
  moments.width = normalTexture.width;
  moments.height = normalTexture.height;
  moments.first.resize(count);
  moments.second.resize(count);
  for (std::size_t i = 0; i < count; ++i) {
    glm::vec3 n;
    for (int c = 0; c < 3; ++c) n[c] = static_cast<float>(normalTexture.rgba[4 * i + static_cast<std::size_t>(c)]) / 255.0f * 2.0f - 1.0f;
    n.x *= normalScale;
    n.y *= normalScale;
    const float z = std::max(n.z, 0.01f);
    const glm::vec2 s(-n.x / z, -n.y / z);
    moments.first[i] = glm::vec3(s.x, s.y, s.x * s.x);
    moments.second[i] = glm::vec3(s.y * s.y, s.x * s.y, 0.0f);
  }
  return moments;
}

}  // namespace glint::scene
