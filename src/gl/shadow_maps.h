// Shadow maps of the rasteriser's lights (docs/renderer.md, "Shadows"), read by shaders/shadows.glsl:
// a directional light's orthographic map fit to the scene's bounds, a spot light's perspective
// map around its outer cone, a point light's cube map. Needs a current OpenGL context.
#pragma once

#include <functional>
#include <vector>

#include <glad/gl.h>
#include <glm/glm.hpp>

#include "scene/scene.h"

namespace glint::gl {

// Texels a side of a directional or spot light's map, and of each face of a point light's cube.
// At these sizes the built-in scenes' shadow edges are a few millimetres wide (docs/renderer.md).
constexpr int kShadowMapSize = 2048;
constexpr int kShadowCubeSize = 1024;
// A spot whose outer cone is wider than this (radians from its axis) gets a cube map, as a point
// light: a single perspective map would spread its texels too thin towards the edges.
constexpr float kWidestSpotMap = 1.2f;

// Where a light's map is and how forward.frag reads it (shadows.glsl's uniforms).
struct ShadowLookup {
  bool cube = false;
  int layer = 0;           // layer of the 2D array, or cube of the cube-map array
  glm::mat4 matrix{1.0f};  // world to the 2D map's clip space
  float depthScale = 1.0f;  // world length to map depth
  float texel = 0.0f;      // a texel's world size: at distance 1 for point and spot lights
};

// The map of one light (cube: false) or one cube face, for the scene's bounds: the view-projection
// it is drawn with and its lookup. Positional lights' maps hold distance * depthScale, drawn with
// linear depth; a directional light's is an orthographic map whose depth is linear already.
ShadowLookup shadowLookup(const scene::Light& light, glm::vec3 boundsMin, glm::vec3 boundsMax);
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

  // Makes the maps of `lights` unless they are those of the last call with the same `key` (what
  // else changes the occluders: the renderer's materials' alpha masks). Leaves the framebuffer
  // unbound.
  void update(const std::vector<scene::Light>& lights, glm::vec3 boundsMin, glm::vec3 boundsMax,
              const std::vector<float>& key, const DrawOccluders& draw);
  const std::vector<ShadowLookup>& lookups() const { return lookups_; }
  // Bit i: light i has a cube map (forward.frag's SHADOW_CUBES).
  int cubeMask() const;
  void bind() const;  // texture units 13 (2D maps) and 14 (cubes), as shadows.glsl reads them

 private:
  void allocate(int planes, int cubes);
  std::vector<ShadowLookup> lookups_;
  std::vector<float> key_;
  bool valid_ = false;
  GLuint maps_ = 0;
  GLuint cubes_ = 0;
  GLuint framebuffer_ = 0;
  int planeLayers_ = 0;
  int cubeCount_ = 0;
};

}  // namespace glint::gl
