// The real-time glint renderer: forward shading of a scene into a linear HDR target with OpenGL
// 4.5 (docs/renderer.md). Needs a current context (HeadlessContext or WindowContext).
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <glad/gl.h>
#include <glm/glm.hpp>

#include "glint/bsdf.h"
#include "glint/dictionary.h"
#include "glint/image_io.h"
#include "glint/specular_model.h"
#include "scene/area_lights.h"
#include "scene/environment_map.h"
#include "scene/scene.h"

namespace glint::gl {

class ShaderProgram;

// The most lights the rasteriser draws (the first ones of the scene): a forward program is
// compiled per light count (LIGHT_COUNT). The path tracer draws them all.
constexpr int kMaxLights = 8;
// The most regions of an environment map whose glints a frame draws (scene::environmentGlintRegions).
constexpr int kMaxEnvironmentRegions = 16;
// The most area lights (scene::findAreaLights) a frame draws; beyond them, the brightest.
constexpr int kMaxAreaLights = 8;
// The most cascades of a directional light's shadow maps, and its default
// (FrameSettings::shadowCascades, shadow_maps.h).
constexpr int kShadowCascades = 4;

// The uniform-buffer binding of the forward shader's glint material block
// (shaders/glint_material_block.glsl): each mesh's draw binds its material's range of the
// renderer's buffer of all materials there.
constexpr GLuint kGlintMaterialBinding = 0;

// Glint anti-aliasing (docs/antialiasing.md): None is the 2020 model, each pixel's P-SDF at one
// half vector; Ggaa filters it by the half vector's variation over the pixel (Chermain et al.
// 2021, kernel/glint_antialiasing.h); GgaaLean also filters the normal map, its slopes' mean tilting
// the normal and their covariance widening the glint layer (kernel/normal_map_filtering.h).
enum class AntiAliasing { None, Ggaa, GgaaLean };
std::vector<AntiAliasing> allAntiAliasingModes();
AntiAliasing antiAliasingFromString(const std::string& name);  // throws Error naming the choices
const char* toString(AntiAliasing mode);

// Cost tiers (`--quality`, docs/cli.md; chosen in docs/benchmarks.md, "Cost tiers"): named presets
// over the frame's glint footprint policy, anti-aliasing and a directional light's shadow cascades.
// `exact` is the defaults: the paper's footprint, anti-aliased, four cascades.
struct QualityPreset {
  const char* name;       // low, medium, high, exact
  const char* footprint;  // a footprint policy, as footprintPolicyFromString reads it
  AntiAliasing antiAliasing;
  int shadowCascades;
};
// Every tier, from the cheapest to the paper's.
const std::vector<QualityPreset>& qualityPresets();
// Throws Error naming the choices for an unknown name.
const QualityPreset& qualityPreset(const std::string& name);

struct FrameSettings {
  int width = 512;
  int height = 512;
  SpecularModel brdf = SpecularModel::Glint;
  AntiAliasing antiAliasing = AntiAliasing::GgaaLean;
  // Normal maps read at their finest level instead of the footprint's (the anti-aliasing
  // reference protocol: its jittered frames resolve the normal map themselves).
  bool normalMapFinestLevel = false;
  // The filter kernel's size: 1 gives the kernel the covariance of the pixel's box (the reference
  // averages over that box); 0 filters nothing.
  float filterScale = 1.0f;
  scene::Camera camera;
  glm::vec2 jitter{0.0f};  // sub-pixel offset of the frame, in pixels (supersampling)
  // The lights cast shadows, from shadow maps (docs/renderer.md, "Shadows"), as the path tracer's
  // shadow rays find them.
  bool shadows = true;
  // A directional light's shadow maps: cascades over the camera's view depth, 1 to
  // kShadowCascades; 1 fits one map to the whole scene (docs/renderer.md, "Shadows").
  int shadowCascades = kShadowCascades;
  // Samples a pixel of the geometry (docs/renderer.md, "Anti-aliased edges"): depth and coverage
  // per sample, each surface in the pixel shaded once, the samples averaged. 1: one sample, at the
  // centre; at most maxMsaaSamples(). Off by default: 4 samples cost llvmpipe 1.5 to 2.3 times the
  // frame (docs/benchmarks.md, "Shadows and anti-aliased edges").
  int msaa = 1;
  // How the glint footprint may depart from the paper's to bound the cost of its walk (`--footprint`;
  // docs/antialiasing.md, "Footprint policies"). Exact by default.
  kernel::GlintFootprintPolicy footprintPolicy = exactFootprintPolicy();
};

class Renderer {
 public:
  // Uploads the scene's meshes and textures and the dictionary; compiles the programs.
  Renderer(const scene::Scene& scene, const Dictionary& dictionary);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // Draws one frame into the HDR target (linear radiance, RGBA32F), resizing it if needed.
  void renderFrame(const FrameSettings& settings);
  // The last frame: RGBA floats, rows bottom-up (as GL stores them).
  std::vector<float> readRadiance() const;
  // The last frame's depth buffer (window depth in [0, 1], 1 where no mesh was drawn), rows
  // bottom-up, to place each pixel's surface point (viewProjection's inverse). Only for frames of
  // one sample a pixel: a multisampled depth has no single value (throws Error).
  std::vector<float> readDepth() const;
  GLuint radianceTexture() const;

  // What the renderer draws otherwise than the scene says, one line each, for the commands to warn
  // about (a texture larger than this OpenGL's limit, drawn downscaled).
  const std::vector<std::string>& warnings() const { return warnings_; }
  // The most samples a pixel FrameSettings::msaa may ask for on this OpenGL (a power of two).
  int maxMsaaSamples() const;

  // Materials and lights as drawn; the viewer edits them between frames.
  std::vector<scene::Material>& materials() { return materials_; }
  std::vector<scene::Light>& lights() { return lights_; }
  // The environment map's brightest small regions, drawn as directional lights after the scene's
  // (scene::extractEnvironmentLights, at most scene::Environment::rasterLights and the slots the
  // scene's lights leave of kMaxLights); the map's specular and irradiance lack their radiance.
  const std::vector<scene::Light>& environmentLights() const { return environmentLights_; }

 private:
  struct Gpu;
  struct FrameState;
  // The frame's passes, in the order renderFrame runs them (docs/renderer.md, "Passes").
  FrameState beginFrame(const FrameSettings& settings);
  void shadowPass(const FrameSettings& settings, FrameState& frame);
  void depthPrepass(const FrameState& frame);
  void shadingPass(const FrameSettings& settings, const FrameState& frame);
  void backgroundPass(const FrameState& frame);
  void resolve(const FrameSettings& settings);
  // Their parts.
  void drawDepths(const glm::mat4& viewProjection, bool linearDepth, glm::vec3 origin, float depthScale, bool cull);
  void setFrameUniforms(const ShaderProgram& program, const FrameSettings& settings, const FrameState& frame) const;
  // A mesh's material (alphaMask: its cutoff; normalMapMoments: its normal map's slope moments).
  void bindMaterial(const ShaderProgram& program, int material, bool alphaMask, bool normalMapMoments);
  void setCulling(int material) const;
  GLuint textureOr(int texture, GLuint fallback) const;  // the scene texture's name, else `fallback`

  const scene::Scene& scene_;
  std::vector<scene::Material> materials_;
  std::vector<scene::Light> lights_;
  std::vector<scene::Light> environmentLights_;
  // The rest of the map's brightest regions (scene::environmentGlintRegions, at most
  // scene::Environment::rasterRegions and kMaxEnvironmentRegions) and the scene's emissive
  // quadrilaterals (scene::findAreaLights, at most kMaxAreaLights), drawn as extended lights.
  std::vector<scene::EnvironmentRegion> environmentRegions_;
  std::vector<scene::AreaLight> areaLights_;
  std::vector<std::string> warnings_;
  std::unique_ptr<Gpu> gpu_;
};

// The mean of `spp` jittered frames, in linear radiance (the anti-aliasing paper's reference
// protocol averages 1,024); `onSample(k)` is called after sample k when given.
ImageRgbF renderSupersampled(Renderer& renderer, FrameSettings frame, int spp,
                             const std::function<void(int)>& onSample = {});

// The view-projection matrix of a camera for an image of the given size, with an optional
// sub-pixel jitter in pixels; near and far planes fit the scene's bounds.
glm::mat4 viewProjection(const scene::Camera& camera, int width, int height, glm::vec2 jitter, glm::vec3 boundsMin,
                         glm::vec3 boundsMax);

// The sub-pixel offset of sample k of a supersampled frame: sample 0 at the pixel centre, then
// the R2 sequence (Roberts 2018), which covers the pixel evenly for any sample count.
glm::vec2 supersampleJitter(int k);

}  // namespace glint::gl
