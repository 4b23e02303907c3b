#include "scene/environment_map.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "glint/radiance_hdr.h"

namespace glint::scene {

namespace {

constexpr double kPiD = 3.14159265358979323846;
constexpr float kPiF = static_cast<float>(kPiD);

}  // namespace

glm::vec2 equirectFromDirection(glm::vec3 d) {
  return {std::atan2(d.x, -d.z) / (2.0f * kPiF) + 0.5f, std::acos(std::clamp(d.y, -1.0f, 1.0f)) / kPiF};
}

glm::vec3 directionFromEquirect(glm::vec2 uv) {
  const float phi = (uv.x - 0.5f) * 2.0f * kPiF;
  const float theta = uv.y * kPiF;
  return {std::sin(theta) * std::sin(phi), std::cos(theta), -std::sin(theta) * std::cos(phi)};
}

double equirectTexelSolidAngle(int y, int width, int height) {
  return (2.0 * kPiD / width) * (kPiD / height) * std::sin(kPiD * (y + 0.5) / height);
}

Environment loadEnvironmentMap(const std::filesystem::path& path) {
  ImageRgbF image = readRadianceImage(path);
  Environment environment;
  environment.width = image.width;
  environment.height = image.height;
  environment.pixels = std::move(image.pixels);
  return environment;
}

glm::vec3 skyRadiance(float elevation) {
  const glm::vec3 zenith(0.22f, 0.42f, 0.85f);
  const glm::vec3 horizon(0.78f, 0.82f, 0.9f);
  const glm::vec3 ground(0.3f, 0.29f, 0.28f);
  const float h = std::sin(elevation);
  return h >= 0.0f ? glm::mix(horizon, zenith, std::sqrt(h)) : glm::mix(horizon, ground, std::min(1.0f, 8.0f * -h));
}

glm::vec3 sunSkyDirection(const SunSky& sky) {
  const float azimuth = glm::radians(sky.sunAzimuthDegrees);
  const float elevation = glm::radians(sky.sunElevationDegrees);
  return {-std::sin(azimuth) * std::cos(elevation), std::sin(elevation), -std::cos(azimuth) * std::cos(elevation)};
}

Environment sunSkyEnvironment(const SunSky& sky) {
  Environment environment;
  environment.width = sky.width;
  environment.height = sky.height;
  environment.pixels.resize(static_cast<std::size_t>(sky.width) * static_cast<std::size_t>(sky.height));
  const glm::vec3 sun = sunSkyDirection(sky);
  const double cosRadius = std::cos(glm::radians(0.5 * sky.sunDiameterDegrees));
  // Uniform radiance over the disc: E = L * Omega, Omega = 2 pi (1 - cos(radius)) (the cosine over
  // a disc of a few degrees differs from 1 by under 1e-3). A warm white of luminance 1, scaled.
  const glm::vec3 warmWhite = glm::vec3(1.0f, 0.93f, 0.82f) / luminance(glm::vec3(1.0f, 0.93f, 0.82f));
  const glm::vec3 sunRadiance = warmWhite * static_cast<float>(sky.sunIrradiance / (2.0 * kPiD * (1.0 - cosRadius)));
  constexpr int kSubsamples = 4;
  for (int y = 0; y < sky.height; ++y) {
    const float elevation = 0.5f * kPiF - kPiF * (static_cast<float>(y) + 0.5f) / static_cast<float>(sky.height);
    const glm::vec3 background = skyRadiance(elevation);
    for (int x = 0; x < sky.width; ++x) {
      int covered = 0;
      for (int j = 0; j < kSubsamples; ++j) {
        for (int i = 0; i < kSubsamples; ++i) {
          const glm::vec2 uv((x + (i + 0.5f) / kSubsamples) / sky.width, (y + (j + 0.5f) / kSubsamples) / sky.height);
          if (glm::dot(directionFromEquirect(uv), sun) >= cosRadius) ++covered;
        }
      }
      environment.pixels[static_cast<std::size_t>(y) * sky.width + x] =
          background + sunRadiance * (static_cast<float>(covered) / (kSubsamples * kSubsamples));
    }
  }
  return environment;
}

EnvironmentLights extractEnvironmentLights(const Environment& environment, int maxLights) {
  EnvironmentLights result;
  result.residual = environment;
  if (environment.pixels.empty() || maxLights <= 0) return result;
  const int w = environment.width;
  const int h = environment.height;
  const auto index = [w](int x, int y) { return static_cast<std::size_t>(y) * w + static_cast<std::size_t>(x); };
  std::vector<double> solidAngle(static_cast<std::size_t>(h));
  for (int y = 0; y < h; ++y) solidAngle[static_cast<std::size_t>(y)] = equirectTexelSolidAngle(y, w, h);

  double totalPower = 0.0;
  double totalSolidAngle = 0.0;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      totalPower += luminance(environment.pixels[index(x, y)]) * solidAngle[static_cast<std::size_t>(y)];
      totalSolidAngle += solidAngle[static_cast<std::size_t>(y)];
    }
  }
  if (!(totalPower > 0.0)) return result;
  const double threshold = kEnvironmentLightContrast * totalPower / totalSolidAngle;
  std::vector<char> bright(environment.pixels.size());
  for (std::size_t i = 0; i < bright.size(); ++i) bright[i] = luminance(environment.pixels[i]) > threshold;

  // Regions of edge-connected bright texels (u wraps around), found by a flood fill.
  struct Region {
    std::vector<std::size_t> texels;
    glm::vec3 background{0.0f};
    double power = 0.0;  // luminance above the background, times solid angle
    double solidAngle = 0.0;
  };
  std::vector<Region> regions;
  std::vector<int> regionOf(environment.pixels.size(), -1);
  std::vector<int> borderOf(environment.pixels.size(), -1);  // the last region whose border counted the texel
  for (std::size_t start = 0; start < bright.size(); ++start) {
    if (!bright[start] || regionOf[start] >= 0) continue;
    Region region;
    const int id = static_cast<int>(regions.size());
    std::vector<std::size_t> stack = {start};
    regionOf[start] = id;
    glm::dvec3 borderSum(0.0);
    int borderCount = 0;
    while (!stack.empty()) {
      const std::size_t t = stack.back();
      stack.pop_back();
      region.texels.push_back(t);
      const int x = static_cast<int>(t % static_cast<std::size_t>(w));
      const int y = static_cast<int>(t / static_cast<std::size_t>(w));
      const int neighbours[4][2] = {{(x + 1) % w, y}, {(x + w - 1) % w, y}, {x, y - 1}, {x, y + 1}};
      for (const auto& n : neighbours) {
        if (n[1] < 0 || n[1] >= h) continue;
        const std::size_t u = index(n[0], n[1]);
        if (bright[u]) {
          if (regionOf[u] < 0) {
            regionOf[u] = id;
            stack.push_back(u);
          }
        } else {
          if (borderOf[u] != id) {
            borderOf[u] = id;
            borderSum += glm::dvec3(environment.pixels[u]);
            ++borderCount;
          }
        }
      }
    }
    // (A region without a border covers the whole map: its solid angle keeps it from being a light.)
    region.background = borderCount > 0 ? glm::vec3(borderSum / static_cast<double>(borderCount)) : glm::vec3(0.0f);
    for (std::size_t t : region.texels) {
      const double omega = solidAngle[t / static_cast<std::size_t>(w)];
      region.solidAngle += omega;
      region.power += std::max(0.0f, luminance(environment.pixels[t] - region.background)) * omega;
    }
    regions.push_back(std::move(region));
  }

  std::vector<std::size_t> order(regions.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return regions[a].power > regions[b].power; });
  for (std::size_t r : order) {
    if (static_cast<int>(result.lights.size()) >= maxLights) break;
    const Region& region = regions[r];
    if (region.solidAngle > kEnvironmentLightMaxSolidAngle ||
        region.power < kEnvironmentLightMinPower * totalPower) {
      continue;
    }
    glm::dvec3 irradiance(0.0);
    glm::dvec3 centroid(0.0);
    for (std::size_t t : region.texels) {
      const int x = static_cast<int>(t % static_cast<std::size_t>(w));
      const int y = static_cast<int>(t / static_cast<std::size_t>(w));
      const double omega = solidAngle[static_cast<std::size_t>(y)];
      const glm::vec3 excess = glm::max(environment.pixels[t] - region.background, glm::vec3(0.0f));
      irradiance += glm::dvec3(excess) * omega;
      const glm::vec3 d = directionFromEquirect({(x + 0.5f) / w, (y + 0.5f) / h});
      centroid += glm::dvec3(d) * (static_cast<double>(luminance(excess)) * omega);
      // The residual keeps the background, never more than the texel had.
      result.residual.pixels[t] = glm::min(environment.pixels[t], region.background);
    }
    Light light;
    light.type = Light::Type::Directional;
    light.direction = -environment.worldDirection(glm::vec3(glm::normalize(centroid)));
    light.intensity = glm::vec3(irradiance) * environment.intensity;
    result.lights.push_back(light);
    result.solidAngles.push_back(region.solidAngle);
    result.powerFractions.push_back(region.power / totalPower);
  }
  return result;
}

}  // namespace glint::scene
