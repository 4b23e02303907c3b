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

namespace {
// A width x height map of black texels, for the procedural maps to fill.
Environment blankEnvironment(int width, int height) {
  Environment environment;
  environment.width = width;
  environment.height = height;
  environment.pixels.resize(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
  return environment;
}
}  // namespace

Environment studioEnvironment(int width, int height) {
  Environment environment = blankEnvironment(width, height);
  for (int y = 0; y < height; ++y) {
    const float elevation = 90.0f - 180.0f * (static_cast<float>(y) + 0.5f) / static_cast<float>(height);
    for (int x = 0; x < width; ++x) {
      // The texel's azimuth, to the left of -z: directionFromEquirect's (-sin a cos e, ., -cos a cos e).
      const glm::vec3 d = directionFromEquirect(glm::vec2((x + 0.5f) / width, (y + 0.5f) / height));
      const float azimuth = glm::degrees(std::atan2(-d.x, -d.z));
      glm::vec3 radiance(elevation >= 0.0f ? 0.05f : 0.02f);
      for (const Softbox& box : kStudioSoftboxes) {
        const float across = std::remainder(azimuth - box.azimuthDegrees, 360.0f);
        if (std::abs(across) <= 0.5f * box.widthDegrees && std::abs(elevation - box.elevationDegrees) <= 0.5f * box.heightDegrees) {
          radiance = glm::vec3(box.radiance);
        }
      }
      environment.pixels[static_cast<std::size_t>(y) * width + x] = radiance;
    }
  }
  return environment;
}

Environment overcastEnvironment(int width, int height) {
  Environment environment = blankEnvironment(width, height);
  for (int y = 0; y < height; ++y) {
    const float elevation = 0.5f * kPiF - kPiF * (static_cast<float>(y) + 0.5f) / static_cast<float>(height);
    const float radiance = elevation >= 0.0f ? (1.0f + 2.0f * std::sin(elevation)) / 3.0f : 0.1f;
    for (int x = 0; x < width; ++x) environment.pixels[static_cast<std::size_t>(y) * width + x] = glm::vec3(radiance);
  }
  return environment;
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

namespace glint::scene {

namespace {

// One rectangle of the coarse grid environmentGlintRegions splits the map on, with its sums: solid
// angle, luminance and squared luminance times solid angle, and radiance times solid angle.
struct GridRectangle {
  int x0, y0, x1, y1;  // cells [x0, x1) x [y0, y1)
  double weight = 0.0;
  double luminanceSum = 0.0;
  double squareSum = 0.0;
  glm::dvec3 radianceSum{0.0};
  double meanLuminance() const { return weight > 0.0 ? luminanceSum / weight : 0.0; }
  // The solid-angle weighted squared deviation from the mean luminance: what a split lowers.
  double spread() const { return weight > 0.0 ? squareSum - luminanceSum * luminanceSum / weight : 0.0; }
  // The larger of its angular height and its width at its middle row, in radians.
  double extent(int width, int height) const {
    const double theta = (0.5 * (y0 + y1) / height) * 3.14159265358979;
    return std::max((y1 - y0) * 3.14159265358979 / height, (x1 - x0) * 2.0 * 3.14159265358979 / width * std::sin(theta));
  }
};

}  // namespace

EnvironmentRegions environmentGlintRegions(const Environment& environment, int maxRegions) {
  EnvironmentRegions result;
  result.residual = environment;
  std::vector<EnvironmentRegion>& regions = result.regions;
  if (maxRegions <= 0 || environment.pixels.empty() || environment.width <= 0 || environment.height <= 0) return result;
  // The grid: the map's texels (averaged into cells beyond 512 x 256), each cell's sums weighted
  // by the texels' solid angles.
  const int gridWidth = std::min(environment.width, kEnvironmentRegionGridWidth);
  const int gridHeight = std::max(1, std::min(environment.height, kEnvironmentRegionGridWidth / 2));
  std::vector<GridRectangle> cells(static_cast<std::size_t>(gridWidth * gridHeight));
  for (int y = 0; y < environment.height; ++y) {
    const double solidAngle = equirectTexelSolidAngle(y, environment.width, environment.height);
    const int cy = y * gridHeight / environment.height;
    for (int x = 0; x < environment.width; ++x) {
      const int cx = x * gridWidth / environment.width;
      GridRectangle& c = cells[static_cast<std::size_t>(cy * gridWidth + cx)];
      const glm::vec3 radiance = environment.pixels[static_cast<std::size_t>(y) * environment.width + x] * environment.intensity;
      const double l = luminance(radiance);
      c.weight += solidAngle;
      c.luminanceSum += l * solidAngle;
      c.squareSum += l * l * solidAngle;
      c.radianceSum += glm::dvec3(radiance) * solidAngle;
    }
  }
  // Summed-area tables of the cells' sums, so that any rectangle's sums cost four lookups.
  const std::size_t stride = static_cast<std::size_t>(gridWidth) + 1;
  std::vector<GridRectangle> table(stride * (static_cast<std::size_t>(gridHeight) + 1));
  auto add = [](GridRectangle& into, const GridRectangle& c, double sign) {
    into.weight += sign * c.weight;
    into.luminanceSum += sign * c.luminanceSum;
    into.squareSum += sign * c.squareSum;
    into.radianceSum += sign * c.radianceSum;
  };
  for (int y = 0; y < gridHeight; ++y) {
    for (int x = 0; x < gridWidth; ++x) {
      GridRectangle& t = table[(y + 1) * stride + x + 1];
      add(t, cells[static_cast<std::size_t>(y * gridWidth + x)], 1.0);
      add(t, table[y * stride + x + 1], 1.0);
      add(t, table[(y + 1) * stride + x], 1.0);
      add(t, table[y * stride + x], -1.0);
    }
  }
  auto sums = [&](int x0, int y0, int x1, int y1) {
    GridRectangle r{x0, y0, x1, y1};
    add(r, table[y1 * stride + x1], 1.0);
    add(r, table[y0 * stride + x1], -1.0);
    add(r, table[y1 * stride + x0], -1.0);
    add(r, table[y0 * stride + x0], 1.0);
    return r;
  };
  // Split in two where the two halves' spreads sum least, across either axis; false when it is one cell.
  auto bestSplit = [&](const GridRectangle& r, GridRectangle& a, GridRectangle& b) {
    double best = -1.0;
    for (int x = r.x0 + 1; x < r.x1; ++x) {
      GridRectangle left = sums(r.x0, r.y0, x, r.y1), right = sums(x, r.y0, r.x1, r.y1);
      const double s = left.spread() + right.spread();
      if (best < 0.0 || s < best) { best = s; a = left; b = right; }
    }
    for (int y = r.y0 + 1; y < r.y1; ++y) {
      GridRectangle top = sums(r.x0, r.y0, r.x1, y), bottom = sums(r.x0, y, r.x1, r.y1);
      const double s = top.spread() + bottom.spread();
      if (best < 0.0 || s < best) { best = s; a = top; b = bottom; }
    }
    return best >= 0.0;
  };
  // 1. A k-d split of the whole map by luminance spread, from eight tiles of 90 x 90 degrees, until
  //    it has kEnvironmentRegionLeaves rectangles: the regions of nearly constant radiance.
  std::vector<GridRectangle> leaves;
  for (int ty = 0; ty < 2; ++ty) {
    for (int tx = 0; tx < 4; ++tx) {
      leaves.push_back(sums(tx * gridWidth / 4, ty * gridHeight / 2, (tx + 1) * gridWidth / 4, (ty + 1) * gridHeight / 2));
    }
  }
  while (static_cast<int>(leaves.size()) < kEnvironmentRegionLeaves) {
    auto widest = std::max_element(leaves.begin(), leaves.end(),
                                   [](const GridRectangle& a, const GridRectangle& b) { return a.spread() < b.spread(); });
    GridRectangle a{}, b{};
    if (widest->spread() <= 0.0 || !bestSplit(*widest, a, b)) break;
    *widest = a;
    leaves.push_back(b);
  }
  // 2. The brightest rectangles light glints, each at most kEnvironmentRegionMaxExtent across (a
  //    wider one is halved along its longer side and both halves go back among the candidates), so
  //    that the polygon of its corners' and edges' midpoints' half vectors stays close to its region
  //    of slopes (measured up to 60 degrees, ExtendedLightsStat.AreaLightSmoothLobe...).
  const double mapMean = [&] {
    double w = 0.0, l = 0.0;
    for (const GridRectangle& c : cells) { w += c.weight; l += c.luminanceSum; }
    return w > 0.0 ? l / w : 0.0;
  }();
  auto brighter = [](const GridRectangle& a, const GridRectangle& b) { return a.meanLuminance() > b.meanLuminance(); };
  std::sort(leaves.begin(), leaves.end(), brighter);
  std::vector<GridRectangle> chosen;
  while (!leaves.empty() && static_cast<int>(chosen.size()) < maxRegions) {
    GridRectangle r = leaves.front();
    leaves.erase(leaves.begin());
    if (!(r.meanLuminance() > mapMean)) break;  // no brighter than the map's mean: its glints stay in the smooth lobe
    if (r.extent(gridWidth, gridHeight) > kEnvironmentRegionMaxExtent && (r.x1 - r.x0 > 1 || r.y1 - r.y0 > 1)) {
      const double theta = (0.5 * (r.y0 + r.y1) / gridHeight) * 3.14159265358979;
      const bool acrossX = (r.x1 - r.x0) * 2.0 / gridWidth * std::sin(theta) > (r.y1 - r.y0) * 1.0 / gridHeight || r.y1 - r.y0 == 1;
      const int cut = acrossX ? (r.x0 + r.x1) / 2 : (r.y0 + r.y1) / 2;
      leaves.push_back(acrossX ? sums(r.x0, r.y0, cut, r.y1) : sums(r.x0, r.y0, r.x1, cut));
      leaves.push_back(acrossX ? sums(cut, r.y0, r.x1, r.y1) : sums(r.x0, cut, r.x1, r.y1));
      std::sort(leaves.begin(), leaves.end(), brighter);
      continue;
    }
    chosen.push_back(r);
  }
  for (const GridRectangle& r : chosen) {
    EnvironmentRegion region;
    const glm::vec2 uv[4] = {{r.x0, r.y0}, {r.x1, r.y0}, {r.x1, r.y1}, {r.x0, r.y1}};
    for (int k = 0; k < 4; ++k) {
      region.corners[static_cast<std::size_t>(k)] =
          environment.worldDirection(directionFromEquirect(uv[k] / glm::vec2(gridWidth, gridHeight)));
    }
    region.radiance = glm::vec3(r.radianceSum / r.weight);
    region.solidAngle = r.weight;
    regions.push_back(region);
    // The residual loses the region's mean over its texels (those of its grid cells), in the map's
    // own units (before the environment's intensity, which the rasteriser applies to the map).
    const glm::vec3 mean = region.radiance / std::max(environment.intensity, 1e-30f);
    for (int y = 0; y < environment.height; ++y) {
      const int cy = y * gridHeight / environment.height;
      if (cy < r.y0 || cy >= r.y1) continue;
      for (int x = 0; x < environment.width; ++x) {
        const int cx = x * gridWidth / environment.width;
        if (cx >= r.x0 && cx < r.x1) result.residual.pixels[static_cast<std::size_t>(y) * environment.width + x] -= mean;
      }
    }
  }
  return result;
}

}  // namespace glint::scene
