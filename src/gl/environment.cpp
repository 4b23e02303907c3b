#include "gl/environment.h"

#include <cmath>

#include "scene/environment_map.h"

namespace glint::gl {

glm::vec3 equirectDirection(float u, float v) { return scene::directionFromEquirect({u, v}); }

std::array<glm::vec3, 9> irradianceSh(const scene::Environment& environment) {
  std::array<glm::vec3, 9> c{};
  if (environment.pixels.empty()) {
    // Uniform radiance L: E(n) = pi L, all in the constant band (Y_0 = 0.282095).
    c[0] = environment.uniform * environment.intensity * static_cast<float>(M_PI) / 0.282095f;
    return c;
  }
  const int w = environment.width;
  const int h = environment.height;
  double weightSum = 0.0;
  for (int y = 0; y < h; ++y) {
    const float v = (static_cast<float>(y) + 0.5f) / static_cast<float>(h);
    const double solidAngle = (2.0 * M_PI / w) * (M_PI / h) * std::sin(v * M_PI);
    for (int x = 0; x < w; ++x) {
      const glm::vec3 d =
          environment.worldDirection(equirectDirection((static_cast<float>(x) + 0.5f) / static_cast<float>(w), v));
      const glm::vec3 radiance = environment.pixels[static_cast<std::size_t>(y) * w + x] * environment.intensity;
      const float basis[9] = {0.282095f,          0.488603f * d.y,       0.488603f * d.z,
                              0.488603f * d.x,    1.092548f * d.x * d.y, 1.092548f * d.y * d.z,
                              0.315392f * (3.0f * d.z * d.z - 1.0f), 1.092548f * d.x * d.z,
                              0.546274f * (d.x * d.x - d.y * d.y)};
      for (int i = 0; i < 9; ++i) c[i] += radiance * basis[i] * static_cast<float>(solidAngle);
      weightSum += solidAngle;
    }
  }
  // Normalise the quadrature to exactly 4 pi, then apply the cosine-lobe factors per band.
  const float normalise = static_cast<float>(4.0 * M_PI / weightSum);
  const float band[9] = {static_cast<float>(M_PI),        2.0f * static_cast<float>(M_PI) / 3.0f,
                         2.0f * static_cast<float>(M_PI) / 3.0f, 2.0f * static_cast<float>(M_PI) / 3.0f,
                         static_cast<float>(M_PI) / 4.0f, static_cast<float>(M_PI) / 4.0f,
                         static_cast<float>(M_PI) / 4.0f, static_cast<float>(M_PI) / 4.0f,
                         static_cast<float>(M_PI) / 4.0f};
  for (int i = 0; i < 9; ++i) c[i] *= normalise * band[i];
  return c;
}

}  // namespace glint::gl
