#include "trace/environment.h"

#include <algorithm>
#include <cmath>

#include "glint/error.h"
#include "scene/environment_map.h"

namespace glint::trace {

namespace {

// An orthonormal basis around a unit vector (Duff et al. 2017, "Building an Orthonormal Basis,
// Revisited").
void basisAround(glm::vec3 n, glm::vec3& t, glm::vec3& b) {
  const float sign = std::copysign(1.0f, n.z);
  const float a = -1.0f / (sign + n.z);
  const float c = n.x * n.y * a;
  t = {1.0f + sign * n.x * n.x * a, sign * c, -sign * n.x};
  b = {c, sign + n.y * n.y * a, -n.y};
}

}  // namespace

glm::vec2 equirectFromDirection(glm::vec3 d) { return scene::equirectFromDirection(d); }

glm::vec3 directionFromEquirect(glm::vec2 uv) { return scene::directionFromEquirect(uv); }

EnvironmentLight::EnvironmentLight(const scene::Environment& environment)
    : environment_(environment), uniform_(environment.pixels.empty()) {
  if (!uniform_ && environment.pixels.size() != static_cast<std::size_t>(environment.width) * environment.height) {
    throw Error("environment: size and pixels do not agree");
  }
  bool anyLight = false;
  if (uniform_) {
    anyLight = glm::any(glm::greaterThan(environment.uniform * environment.intensity, glm::vec3(0.0f)));
  } else {
    // radiance() interpolates bilinearly between texel centres, so a texel's cell (edges at the
    // distribution's cell edges) sees its neighbours' radiance too: a dark texel beside the sun is
    // half as bright as the sun at their shared edge. Each cell is weighted by the largest value the
    // interpolation takes in it -- at the texel's centre, its edges' midpoints or its corners -- so
    // that radiance / pdf stays bounded there (weighting by the texel alone leaves those cells
    // almost never sampled, and BSDF samples that find them carry the variance:
    // EnvironmentTraceStat.ASmallBrightRegionConvergesFasterWithEnvironmentSampling).
    const int w = environment.width;
    const int h = environment.height;
    std::vector<float> texel(environment.pixels.size());
    for (std::size_t i = 0; i < texel.size(); ++i) {
      texel[i] = std::max(0.0f, scene::luminance(environment.pixels[i] * environment.intensity));
    }
    auto at = [&](int x, int y) {  // u wraps around, v stops at the poles, as in radiance()
      return texel[static_cast<std::size_t>(std::clamp(y, 0, h - 1)) * w + static_cast<std::size_t>(((x % w) + w) % w)];
    };
    std::vector<float> weights(environment.pixels.size());
    for (int y = 0; y < h; ++y) {
      // Texels near the poles cover less solid angle: weight by sin(theta) at the row's centre.
      const float sinTheta = std::sin(kPi * (static_cast<float>(y) + 0.5f) / static_cast<float>(h));
      for (int x = 0; x < w; ++x) {
        float largest = at(x, y);
        for (int dy = -1; dy <= 1; dy += 2) {
          for (int dx = -1; dx <= 1; dx += 2) {
            largest = std::max({largest, 0.5f * (at(x, y) + at(x + dx, y)), 0.5f * (at(x, y) + at(x, y + dy)),
                                0.25f * (at(x, y) + at(x + dx, y) + at(x, y + dy) + at(x + dx, y + dy))});
          }
        }
        const std::size_t i = static_cast<std::size_t>(y) * w + x;
        weights[i] = largest * sinTheta;
        anyLight = anyLight || weights[i] > 0.0f;
      }
    }
    if (anyLight) distribution_.emplace(weights, environment.width, environment.height);
  }
  black_ = !anyLight;
}

glm::vec3 EnvironmentLight::radiance(glm::vec3 d) const {
  if (black_) return glm::vec3(0.0f);
  if (uniform_) return environment_.uniform * environment_.intensity;
  const glm::vec2 uv = equirectFromDirection(environment_.mapDirection(d));
  const int w = environment_.width;
  const int h = environment_.height;
  // Bilinear between texel centres: u wraps around, v stops at the poles.
  const float x = uv.x * static_cast<float>(w) - 0.5f;
  const float y = std::clamp(uv.y * static_cast<float>(h) - 0.5f, 0.0f, static_cast<float>(h - 1));
  const float fx = std::floor(x);
  const float fy = std::floor(y);
  const float tx = x - fx;
  const float ty = y - fy;
  const int x0 = ((static_cast<int>(fx) % w) + w) % w;
  const int x1 = (x0 + 1) % w;
  const int y0 = static_cast<int>(fy);
  const int y1 = std::min(y0 + 1, h - 1);
  auto at = [&](int xx, int yy) { return environment_.pixels[static_cast<std::size_t>(yy) * w + xx]; };
  const glm::vec3 value =
      (1.0f - ty) * ((1.0f - tx) * at(x0, y0) + tx * at(x1, y0)) + ty * ((1.0f - tx) * at(x0, y1) + tx * at(x1, y1));
  return value * environment_.intensity;
}

std::optional<EnvironmentLight::Sample> EnvironmentLight::sample(glm::vec2 u, glm::vec3 normal) const {
  if (black_) return std::nullopt;
  Sample s;
  if (uniform_) {
    glm::vec3 t;
    glm::vec3 b;
    basisAround(normal, t, b);
    const glm::vec3 local = sampleCosineHemisphere(u);
    s.direction = glm::normalize(local.x * t + local.y * b + local.z * normal);
    s.pdf = cosineHemispherePdf(local.z);
  } else {
    float uvPdf = 0.0f;
    const glm::vec2 uv = distribution_->sample(u, &uvPdf);
    const float sinTheta = std::sin(uv.y * kPi);
    if (!(sinTheta > 0.0f) || !(uvPdf > 0.0f)) return std::nullopt;
    s.direction = environment_.worldDirection(directionFromEquirect(uv));
    // (u, v) -> (phi, theta) stretches by 2pi x pi; d(omega) = sin(theta) d(theta) d(phi).
    s.pdf = uvPdf / (2.0f * kPi * kPi * sinTheta);
  }
  if (!(s.pdf > 0.0f)) return std::nullopt;
  s.radiance = radiance(s.direction);
  return s;
}

float EnvironmentLight::pdf(glm::vec3 d, glm::vec3 normal) const {
  if (black_) return 0.0f;
  if (uniform_) return cosineHemispherePdf(glm::dot(d, normal));
  const glm::vec2 uv = equirectFromDirection(environment_.mapDirection(d));
  const float sinTheta = std::sin(uv.y * kPi);
  if (!(sinTheta > 0.0f)) return 0.0f;
  return distribution_->pdf(uv) / (2.0f * kPi * kPi * sinTheta);
}

}  // namespace glint::trace
