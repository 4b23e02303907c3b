#include "trace/path_tracer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "glint/error.h"
#include "glint/kernel/lights.h"
#include "trace/sampling.h"

namespace glint::trace {

namespace {

constexpr int kTileSize = 16;
constexpr int kRouletteDepth = 3;  // Russian roulette on rays leaving vertices of this depth and deeper

bool isBlack(glm::vec3 c) { return !(c.x > 0.0f || c.y > 0.0f || c.z > 0.0f); }

// Embree traces rays whose origins lie within about +-1.8e18 (its ray validity check aborts
// beyond); every origin is the camera (and, for an orthographic one, its film) or a point of the
// scene, so a scene and camera within kMaxCoordinate leave a margin of 1e3 for the offsets and
// rounding on the way. The rasteriser has no such limit.
constexpr double kMaxCoordinate = 1e15;

void checkRayRange(const scene::Scene& scene, const scene::Camera& camera, int width, int height) {
  double largest = 0.0;
  const auto include = [&](glm::vec3 p) {
    for (int i = 0; i < 3; ++i) largest = std::max(largest, std::abs(static_cast<double>(p[i])));
  };
  if (!scene.meshes.empty()) {
    include(scene.boundsMin());
    include(scene.boundsMax());
  }
  include(camera.position);
  double film = 0.0;  // the orthographic film's half diagonal
  if (camera.projection == scene::Camera::Projection::Orthographic) {
    const double halfHeight = std::abs(static_cast<double>(camera.orthographicHalfHeight));
    film = halfHeight * std::hypot(1.0, static_cast<double>(width) / height);
  }
  if (!(largest + film <= kMaxCoordinate)) {
    char reach[32];
    std::snprintf(reach, sizeof reach, "%.3g", largest + film);
    throw Error(std::string("the scene and its camera reach coordinates of ") + reach +
                ", beyond the path tracer's range of 1e15 (Embree's rays); scale the scene down");
  }
}

const TraceSettings& validated(const scene::Scene& scene, const TraceSettings& settings) {
  validateTraceSettings(settings);
  checkRayRange(scene, settings.camera, settings.width, settings.height);
  return settings;
}

}  // namespace

GlintSampler glintSamplerFromString(const std::string& name) {
  if (name == "mixture") return GlintSampler::Mixture;
  if (name == "gaussian") return GlintSampler::Gaussian;
  throw Error("unknown sampler '" + name + "' (choices: mixture, gaussian)");
}

const char* glintSamplerName(GlintSampler sampler) {
  switch (sampler) {
    case GlintSampler::Mixture: return "mixture";
    case GlintSampler::Gaussian: return "gaussian";
  }
  return "unknown";
}

void validateTraceSettings(const TraceSettings& s) {
  if (s.width < 1 || s.height < 1 || s.width > 8192 || s.height > 8192) {
    throw Error("--size must be between 1x1 and 8192x8192, got " + std::to_string(s.width) + "x" +
                std::to_string(s.height));
  }
  if (s.spp < 1 || s.spp > 65536) throw Error("--spp must be in [1, 65536], got " + std::to_string(s.spp));
  if (s.maxDepth < 1 || s.maxDepth > 64) {
    throw Error("--max-depth must be in [1, 64], got " + std::to_string(s.maxDepth));
  }
}

PathTracer::PathTracer(const scene::Scene& scene, const Dictionary& dictionary, const TraceSettings& settings)
    : scene_(scene),
      settings_(validated(scene, settings)),
      camera_(settings.camera, settings.width, settings.height),
      geometry_(scene),
      materials_(scene, dictionary, settings.brdf, settings.sampler, settings.normalMapFiltering,
                 settings.footprintPolicy),
      environment_(scene.environment),
      useEnvironment_(!settings.directOnly && !environment_.black()),
      emitters_(scene, materials_),
      useEmitters_(!settings.directOnly && !emitters_.empty()) {}

glm::vec3 PathTracer::deltaLights(const SurfacePoint& point, const ShadedPoint& shaded) const {
  glm::vec3 sum(0.0f);
  for (const scene::Light& light : scene_.lights) {
    // As forward.frag: point and spot lights give intensity / distance^2 (a spot's times its cone,
    // a light with a range times its window), directional lights irradiance.
    glm::vec3 toLight;
    float distance = std::numeric_limits<float>::infinity();
    float falloff = 1.0f;
    if (light.positional()) {
      toLight = light.position - point.position;
      const float distance2 = glm::dot(toLight, toLight);
      if (!(distance2 > 0.0f)) continue;
      distance = std::sqrt(distance2);
      toLight /= distance;
      falloff = kernel::glintSpotAttenuation(light.spotAxis(), toLight, light.coneScaleOffset()) *
                kernel::glintRangeWindow(distance2, light.inverseRange()) / distance2;
      if (!(falloff > 0.0f)) continue;
    } else {
      toLight = -glm::normalize(light.direction);
    }
    const glm::vec3 wi = shaded.frame.toLocal(toLight);
    if (!(wi.z > 0.0f)) continue;
    // The shadow ray first: it costs less than the glint BRDF.
    const Ray shadow = spawnRay(point, toLight);
    // Stop the shadow ray short of a point light by the same margin it starts off the surface.
    const float tMax = std::isinf(distance) ? distance : distance - glm::length(shadow.origin - point.position);
    if (geometry_.occluded(shadow, tMax)) continue;
    sum += shaded.material.f(shaded.wo, wi) * wi.z * light.intensity * falloff;
  }
  return sum;
}

glm::vec3 PathTracer::emitterLight(const SurfacePoint& point, const ShadedPoint& shaded, Pcg32& rng) const {
  const float uTriangle = uniformFloat(rng);
  const glm::vec2 uPoint = uniformFloat2(rng);
  const EmitterSample sample = emitters_.sample(uTriangle, uPoint);
  if (!(sample.areaPdf > 0.0f) || geometry_.maskedOut(sample.at)) return glm::vec3(0.0f);
  const SurfacePoint light = surfacePoint(scene_, sample.at);
  glm::vec3 toLight = light.position - point.position;
  const float distance2 = glm::dot(toLight, toLight);
  if (!(distance2 > 0.0f)) return glm::vec3(0.0f);
  const float distance = std::sqrt(distance2);
  toLight /= distance;
  const glm::vec3 wi = shaded.frame.toLocal(toLight);
  const float cosLight = std::abs(glm::dot(light.geometricNormal, toLight));
  if (!(wi.z > 0.0f) || !(cosLight > 0.0f)) return glm::vec3(0.0f);
  // Emissive textures at the footprint a camera pixel has there, as where a path hits them.
  const bool textured = scene_.materials[static_cast<std::size_t>(light.material)].emissiveTexture >= 0;
  const Spectrum emitted = materials_.emission(
      light, textured ? uvDerivatives(light, camera_.approximateRays(light.position)) : UvDerivatives{}, -toLight);
  if (isBlack(emitted)) return glm::vec3(0.0f);
  // Area density to solid angle (pbrt-v3, equation 5.6): dA = r^2 / cos(theta_light) d omega.
  const float pdf = sample.areaPdf * distance2 / cosLight;
  if (!(pdf > 0.0f) || !std::isfinite(pdf)) return glm::vec3(0.0f);
  // The shadow ray runs between both points, each pushed off its surface towards the other, so
  // that it finds neither the shaded triangle nor the emitting one.
  const glm::vec3 from = spawnRay(point, toLight).origin;
  const glm::vec3 to = spawnRay(light, -toLight).origin;
  const float length = glm::length(to - from);
  if (!(length > 0.0f) || geometry_.occluded(Ray{from, (to - from) / length}, length)) return glm::vec3(0.0f);
  const Spectrum f = shaded.material.f(shaded.wo, wi);
  if (isBlack(f)) return glm::vec3(0.0f);
  const float weight = powerHeuristic(pdf, shaded.material.pdf(shaded.wo, wi));
  return f * emitted * (wi.z * weight / pdf);
}

float PathTracer::emitterPdf(const Hit& hit, const SurfacePoint& emitterPoint, glm::vec3 direction) const {
  if (!useEmitters_) return 0.0f;
  const float cosLight = std::abs(glm::dot(emitterPoint.geometricNormal, direction));
  const float pdf = emitters_.areaPdf(hit.mesh, hit.triangle) * hit.t * hit.t / cosLight;
  return std::isfinite(pdf) ? pdf : 0.0f;
}

glm::vec3 PathTracer::radiance(const RayDifferential& cameraRay, Pcg32& rng) const {
  glm::vec3 result(0.0f);
  glm::vec3 throughput(1.0f);
  Ray ray = cameraRay.ray;
  float previousPdf = 0.0f;           // solid-angle pdf of the BSDF sample that made `ray`
  glm::vec3 previousNormal(0.0f);     // shading normal where it left
  for (int depth = 0;; ++depth) {
    const std::optional<Hit> hit = geometry_.intersect(ray);
    if (!hit) {
      if (useEnvironment_) {
        const glm::vec3 le = environment_.radiance(ray.direction);
        // Seen directly, or found by BSDF sampling: weighed against the light sample that could
        // have found it too.
        const float weight = depth == 0 || !settings_.sampleEnvironment
                                 ? 1.0f
                                 : powerHeuristic(previousPdf, environment_.pdf(ray.direction, previousNormal));
        result += throughput * le * weight;
      }
      break;
    }
    const SurfacePoint point = surfacePoint(scene_, *hit);
    const UvDerivatives footprint =
        uvDerivatives(point, depth == 0 ? cameraRay : camera_.approximateRays(point.position));
    const ShadedPoint shaded = materials_.shade(point, footprint, -ray.direction);
    if (!isBlack(shaded.emitted)) {
      // Seen directly, or found by BSDF sampling: weighed against the emitter sample that could
      // have found it too.
      const float weight = depth == 0 ? 1.0f : powerHeuristic(previousPdf, emitterPdf(*hit, point, ray.direction));
      result += throughput * shaded.emitted * weight;
    }
    if (depth == settings_.maxDepth) break;

    result += throughput * deltaLights(point, shaded);
    if (settings_.directOnly) break;
    if (useEmitters_) result += throughput * emitterLight(point, shaded, rng);

    if (useEnvironment_ && settings_.sampleEnvironment) {
      const glm::vec2 uLight = uniformFloat2(rng);
      if (const auto light = environment_.sample(uLight, shaded.frame.n)) {
        const glm::vec3 wi = shaded.frame.toLocal(light->direction);
        if (wi.z > 0.0f && !isBlack(light->radiance) &&
            !geometry_.occluded(spawnRay(point, light->direction), std::numeric_limits<float>::infinity())) {
          const Spectrum f = shaded.material.f(shaded.wo, wi);
          if (!isBlack(f)) {
            const float weight = powerHeuristic(light->pdf, shaded.material.pdf(shaded.wo, wi));
            result += throughput * f * light->radiance * (wi.z * weight / light->pdf);
          }
        }
      }
    }

    const float uChoice = uniformFloat(rng);
    const glm::vec2 uDirection = uniformFloat2(rng);
    const std::optional<MaterialSample> bounce = shaded.material.sample(shaded.wo, uChoice, uDirection);
    if (!bounce || isBlack(bounce->weight)) break;
    throughput *= bounce->weight;
    const glm::vec3 wiWorld = shaded.frame.toWorld(bounce->wi);
    previousPdf = bounce->pdf;
    previousNormal = shaded.frame.n;
    ray = spawnRay(point, glm::normalize(wiWorld));

    if (depth >= kRouletteDepth) {
      // Continue with the probability of the throughput's largest channel (at least 5%), and
      // divide by it: unbiased, and paths that carry little stop early.
      const float survive = std::clamp(std::max({throughput.x, throughput.y, throughput.z}), 0.05f, 1.0f);
      if (uniformFloat(rng) >= survive) break;
      throughput /= survive;
    }
  }
  return result;
}

glm::vec3 PathTracer::samplePixel(int x, int y, int sampleIndex) const {
  const auto pixel = static_cast<std::uint32_t>(y) * static_cast<std::uint32_t>(settings_.width) +
                     static_cast<std::uint32_t>(x);
  Pcg32 rng = sampleStream(pixel, static_cast<std::uint32_t>(sampleIndex));
  const glm::vec2 offset = settings_.pixelCentres ? glm::vec2(0.5f) : uniformFloat2(rng);
  const RayDifferential cameraRay = camera_.generateRay(glm::vec2(static_cast<float>(x), static_cast<float>(y)) + offset);
  const glm::vec3 value = radiance(cameraRay, rng);
  if (!std::isfinite(value.x) || !std::isfinite(value.y) || !std::isfinite(value.z)) {
    nonFinite_.fetch_add(1, std::memory_order_relaxed);
    return glm::vec3(0.0f);
  }
  return value;
}

ImageRgbF PathTracer::render(const std::function<void(double)>& progress) const {
  ImageRgbF image = ImageRgbF::filled(settings_.width, settings_.height);
  const int tilesX = (settings_.width + kTileSize - 1) / kTileSize;
  const int tilesY = (settings_.height + kTileSize - 1) / kTileSize;
  const int tileCount = tilesX * tilesY;
  std::atomic<int> tilesDone{0};
  tbb::parallel_for(tbb::blocked_range<int>(0, tileCount, 1), [&](const tbb::blocked_range<int>& range) {
    for (int tile = range.begin(); tile != range.end(); ++tile) {
      const int x0 = (tile % tilesX) * kTileSize;
      const int y0 = (tile / tilesX) * kTileSize;
      const int x1 = std::min(x0 + kTileSize, settings_.width);
      const int y1 = std::min(y0 + kTileSize, settings_.height);
      for (int y = y0; y < y1; ++y) {
        for (int x = x0; x < x1; ++x) {
          // Summed in double in sample order: the same bits whichever thread renders the tile.
          glm::dvec3 sum(0.0);
          for (int s = 0; s < settings_.spp; ++s) sum += glm::dvec3(samplePixel(x, y, s));
          image.at(x, y) = glm::vec3(sum / static_cast<double>(settings_.spp));
        }
      }
      const int done = tilesDone.fetch_add(1) + 1;
      if (progress) progress(static_cast<double>(done) / tileCount);
    }
  });
  return image;
}

}  // namespace glint::trace
