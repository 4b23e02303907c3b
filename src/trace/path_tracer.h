// `glint trace`: a CPU Monte Carlo path tracer of a scene::Scene with the glint BSDF (docs/trace.md).
// Unidirectional path tracing with next-event estimation: point, spot and directional lights (delta
// lights, no MIS), the environment and emissive triangles (importance-sampled, each combined with
// BSDF sampling by the power heuristic); Russian roulette after depth 3. Direct light matches the
// real-time renderer's shading (both assemble the surface with kernel/surface.h) with the footprint of each camera ray from
// its ray differentials.
// Deterministic: every sample draws from its own PCG32 stream seeded by (pixel, sample), so the
// image is the same for any number of threads.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>

#include "glint/bsdf.h"
#include "glint/dictionary.h"
#include "glint/image_io.h"
#include "scene/scene.h"
#include "trace/camera.h"
#include "trace/emitters.h"
#include "trace/environment.h"
#include "trace/geometry.h"
#include "trace/material.h"

namespace glint::trace {

struct TraceSettings {
  int width = 256;
  int height = 256;
  int spp = 16;
  int maxDepth = 4;          // bounces: 1 is direct light only (plus what BSDF sampling finds of the environment and emitters)
  SpecularModel brdf = SpecularModel::Glint;
  GlintSampler sampler = GlintSampler::Mixture;
  bool directOnly = false;   // only point and directional lights at the first hit, no environment, no emitters, no bounces
  bool pixelCentres = false; // every sample through its pixel's centre (the rasteriser's footprint)
  // Normal maps filtered as the rasteriser's --aa ggaa+lean does (kernel/normal_map_filtering.h):
  // at each hit's footprint, the mean of the normal map's slopes tilts the normal and their
  // covariance widens the glint layer. Off: the filtered normal texture only.
  bool normalMapFiltering = true;
  // Light samples drawn from the environment's importance distribution, combined with BSDF samples
  // by the power heuristic. Off: only BSDF samples find the environment (what the distribution
  // gains is measured against this, docs/trace.md).
  bool sampleEnvironment = true;
  // How the glint footprint may depart from the paper's to bound its cost (`--footprint`): the
  // rasteriser's FrameSettings::footprintPolicy, the same P-SDF and sampler.
  FootprintPolicy footprintPolicy = exactFootprintPolicy();
  scene::Camera camera;
};

// `--sampler`: "mixture" or "gaussian"; throws Error naming the choices.
GlintSampler glintSamplerFromString(const std::string& name);
const char* glintSamplerName(GlintSampler sampler);

// Throws Error for sizes, sample counts or depths out of range.
void validateTraceSettings(const TraceSettings& settings);

class PathTracer {
 public:
  // Builds the Embree scene and decodes the textures. The scene and the dictionary must outlive it.
  PathTracer(const scene::Scene& scene, const Dictionary& dictionary, const TraceSettings& settings);

  // The mean of settings.spp samples per pixel, linear radiance, rows from the top. In parallel
  // over 16 x 16 tiles (oneTBB); `progress(fraction)` is called after each tile from the thread
  // that finished it.
  ImageRgbF render(const std::function<void(double)>& progress = {}) const;

  // One sample of pixel (x, y): radiance along a camera ray. Samples whose estimate is not finite
  // count as 0 (and are counted, nonFiniteSamples()).
  glm::vec3 samplePixel(int x, int y, int sampleIndex) const;
  // The radiance along a camera ray (its offset rays give the footprint of the first hit).
  glm::vec3 radiance(const RayDifferential& cameraRay, Pcg32& rng) const;

  const ProjectiveCamera& camera() const { return camera_; }
  const SceneGeometry& geometry() const { return geometry_; }
  const SceneMaterials& materials() const { return materials_; }
  std::uint64_t nonFiniteSamples() const { return nonFinite_.load(); }

 private:
  // Light from the point and directional lights at a shaded point, shadow rays included.
  glm::vec3 deltaLights(const SurfacePoint& point, const ShadedPoint& shaded) const;
  // One sample of the light of the emissive triangles at a shaded point, shadow ray included,
  // weighted by the power heuristic against the material's pdf.
  glm::vec3 emitterLight(const SurfacePoint& point, const ShadedPoint& shaded, Pcg32& rng) const;
  // The solid-angle density with which emitterLight() samples the direction of a unit ray that
  // hit an emitter (at hit.t).
  float emitterPdf(const Hit& hit, const SurfacePoint& emitterPoint, glm::vec3 direction) const;

  const scene::Scene& scene_;
  TraceSettings settings_;
  ProjectiveCamera camera_;
  SceneGeometry geometry_;
  SceneMaterials materials_;
  EnvironmentLight environment_;
  bool useEnvironment_;
  EmissiveTriangles emitters_;
  bool useEmitters_;
  mutable std::atomic<std::uint64_t> nonFinite_{0};
};

}  // namespace glint::trace
