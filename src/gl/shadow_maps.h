// Shadow maps of the rasteriser's lights (docs/renderer.md, "Shadows"), read by shaders/shadows.glsl:
// a directional light's cascade of orthographic maps over the part of the scene the camera sees, a
// spot light's perspective map around its outer cone, a point light's cube map. Needs a current
// OpenGL context.
#pragma once

#include <functional>
#include <vector>

#include <glad/gl.h>
#include <glm/glm.hpp>

#include "gl/renderer.h"
#include "scene/scene.h"

namespace glint::gl {

// Texels a side of a directional or spot light's map, and of each face of a point light's cube.
// At these sizes the built-in scenes' shadow edges are a few millimetres wide (docs/renderer.md).
constexpr int kShadowMapSize = 2048;
constexpr int kShadowCubeSize = 1024;
// A spot whose outer cone is wider than this (radians from its axis) gets a cube map, as a point
// light: a single perspective map would spread its texels too thin towards the edges.
constexpr float kWidestSpotMap = 1.2f;

// A directional light's cascades: the camera's view depth, clipped to the scene's bounds, is split
// into cascades, each with its own kShadowMapSize map fit to the scene inside it, so
// that near the camera a texel is millimetres where one map over a large scene makes it centimetres.
// The splits mix logarithmic ones (equal texels per pixel at every depth) with uniform ones (the
// log's first ranges are tiny when the near plane is close) by kCascadeSplitLogWeight. At most
// kShadowCascades (renderer.h) of them, 4 by default.
constexpr float kCascadeSplitLogWeight = 0.75f;
// Texels at a cascade's border that its points keep clear of, so that the lookup's normal offset
// and its filter's taps (about 2.5 texels, shadows.glsl) read inside the map: a point is looked
// up in the first cascade that holds it this far from the border (shadows.glsl's
// SHADOW_CASCADE_MARGIN).
constexpr int kCascadeMarginTexels = 4;

// Where one map of a light is and how forward.frag reads it (shadows.glsl's uniforms).
struct ShadowLookup {
  bool cube = false;
  int layer = 0;           // layer of the 2D array, or cube of the cube-map array
  glm::mat4 matrix{1.0f};  // world to the 2D map's clip space
  float depthScale = 1.0f;  // world length to map depth
  float texel = 0.0f;      // a texel's world size: at distance 1 for point and spot lights
};

// What a directional light's cascades cover: the camera's view frustum, given by its
// view-projection (without jitter) and its position, and the number of cascades (1: one map fit to
// the whole scene, as `--shadow-cascades 1`).
struct ShadowView {
  glm::mat4 viewProjection{1.0f};
  glm::vec3 cameraPosition{0.0f};
  int cascades = kShadowCascades;
};

// The view depths that split [nearDepth, farDepth] into `cascades` ranges: cascades + 1 of them,
// the first nearDepth and the last farDepth (kCascadeSplitLogWeight).
std::vector<float> cascadeSplits(float nearDepth, float farDepth, int cascades);

// A light's maps for the scene's bounds and the view: its view-projections and lookups, one for a
// spot or point light (cube: true, drawn face by face with cubeFaceViewProjection), view.cascades
// for a directional one, nearest first. Positional lights' maps hold distance * depthScale, drawn
// with linear depth; a directional light's are orthographic maps whose depth is linear already.
std::vector<ShadowLookup> shadowLookups(const scene::Light& light, glm::vec3 boundsMin, glm::vec3 boundsMax,
                                        const ShadowView& view);
glm::mat4 cubeFaceViewProjection(glm::vec3 lightPosition, int face, float farPlane);

class ShadowMaps {
 public:
  ShadowMaps() = default;
  ~ShadowMaps();
  ShadowMaps(const ShadowMaps&) = delete;
  ShadowMaps& operator=(const ShadowMaps&) = delete;

  // Draws the occluders' depth: every mesh, both sides, alpha masks applied; `linearDepth`: with
  // depth = distance from `origin` * `depthScale` (depth_prepass.frag, LINEAR_DEPTH).
  using DrawOccluders =
      std::function<void(const glm::mat4& viewProjection, bool linearDepth, glm::vec3 origin, float depthScale)>;

  // Makes the maps of `lights` seen from `view` unless they are those of the last call with the
  // same `key` (what else changes the occluders: the renderer's materials' alpha masks): a camera
  // that moves draws the cascades again only when they move, by whole texels. Leaves the
  // framebuffer unbound.
  void update(const std::vector<scene::Light>& lights, glm::vec3 boundsMin, glm::vec3 boundsMax,
              const ShadowView& view, const std::vector<float>& key, const DrawOccluders& draw);
  // Light i's maps: lookups()[i * kShadowCascades + c], c < 1 for a spot or point light, <
  // cascades() for a directional one (shadows.glsl's uniforms are laid out alike).
  const std::vector<ShadowLookup>& lookups() const { return lookups_; }
  int cascades() const { return cascades_; }
  // Bit i: light i has a cube map (forward.frag's SHADOW_CUBES).
  int cubeMask() const;
  void bind() const;  // texture units 13 (2D maps) and 14 (cubes), as shadows.glsl reads them

 private:
  void allocate(int planes, int cubes);
  std::vector<ShadowLookup> lookups_;
  std::vector<float> key_;
  bool valid_ = false;
  int cascades_ = kShadowCascades;
  GLuint maps_ = 0;
  GLuint cubes_ = 0;
  GLuint framebuffer_ = 0;
  int planeLayers_ = 0;
  int cubeCount_ = 0;
};

}  // namespace glint::gl
