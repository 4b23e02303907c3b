// The scene's environment as a light at infinity: an equirectangular radiance map (the real-time
// renderer's mapping, shaders/environment.glsl environmentRadiance: u = atan(d.x, -d.z) / 2pi + 1/2,
// v = acos(d.y) / pi, +y up, rows from the top) importance-sampled by luminance times sin(theta)
// with a 2D piecewise-constant distribution; or a uniform radiance, sampled cosine-weighted
// about the shading normal.
#pragma once

#include <optional>

#include <glm/glm.hpp>

#include "scene/scene.h"
#include "trace/sampling.h"

namespace glint::trace {

// The shader's direction-to-map mapping and its inverse (scene/environment_map.h); the map's
// rotation (scene::Environment::rotation) turns directions before and after them.
glm::vec2 equirectFromDirection(glm::vec3 d);
glm::vec3 directionFromEquirect(glm::vec2 uv);

class EnvironmentLight {
 public:
  explicit EnvironmentLight(const scene::Environment& environment);

  bool black() const { return black_; }
  // Radiance arriving along -d, i.e. seen when looking in direction d (bilinear in the map).
  glm::vec3 radiance(glm::vec3 d) const;

  struct Sample {
    glm::vec3 direction;  // world, unit, towards the environment
    glm::vec3 radiance;
    float pdf;            // solid angle
  };
  // `normal` is the shading normal: a uniform environment is sampled about it.
  std::optional<Sample> sample(glm::vec2 u, glm::vec3 normal) const;
  float pdf(glm::vec3 d, glm::vec3 normal) const;

 private:
  const scene::Environment& environment_;
  bool uniform_;
  bool black_;
  std::optional<Distribution2D> distribution_;
};

}  // namespace glint::trace
