#include "gl/shadow_maps.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "glint/error.h"

namespace glint::gl {

namespace {

// The bounds' farthest corner from a point: the far plane of a positional light's map, a little
// beyond so that the farthest surface still stores a depth below the cleared 1.
float farthestCorner(glm::vec3 point, glm::vec3 boundsMin, glm::vec3 boundsMax) {
  float farthest = 0.0f;
  for (int corner = 0; corner < 8; ++corner) {
    const glm::vec3 c((corner & 1) ? boundsMax.x : boundsMin.x, (corner & 2) ? boundsMax.y : boundsMin.y,
                      (corner & 4) ? boundsMax.z : boundsMin.z);
    farthest = std::max(farthest, glm::length(c - point));
  }
  return std::max(1.01f * farthest, 1e-3f);
}

// Positional maps clip at this fraction of their far plane; nearer occluders cast nothing.
constexpr float kNearFraction = 1e-4f;

// Any unit vector not along `axis`, for lookAt's up.
glm::vec3 upFor(glm::vec3 axis) {
  return std::abs(axis.y) < 0.9f ? glm::vec3(0.0f, 1.0f, 0.0f) : glm::vec3(1.0f, 0.0f, 0.0f);
}

bool usesCube(const scene::Light& light) {
  return light.type == scene::Light::Type::Point ||
         (light.type == scene::Light::Type::Spot && light.outerConeAngle > kWidestSpotMap);
}

}  // namespace

ShadowLookup shadowLookup(const scene::Light& light, glm::vec3 boundsMin, glm::vec3 boundsMax) {
  ShadowLookup lookup;
  lookup.cube = usesCube(light);
  if (light.type == scene::Light::Type::Directional) {
    // Orthographic along the light, fit to the bounds' corners seen from it (2% margin, so that
    // the filter's taps at the border stay inside), square so that texels are.
    const glm::vec3 direction = glm::normalize(light.direction);
    const glm::vec3 centre = 0.5f * (boundsMin + boundsMax);
    const glm::mat4 view = glm::lookAt(centre - direction, centre, upFor(direction));
    glm::vec3 low(INFINITY), high(-INFINITY);
    for (int corner = 0; corner < 8; ++corner) {
      const glm::vec3 c((corner & 1) ? boundsMax.x : boundsMin.x, (corner & 2) ? boundsMax.y : boundsMin.y,
                        (corner & 4) ? boundsMax.z : boundsMin.z);
      const glm::vec3 v = glm::vec3(view * glm::vec4(c, 1.0f));
      low = glm::min(low, v);
      high = glm::max(high, v);
    }
    const glm::vec2 middle = 0.5f * (glm::vec2(low) + glm::vec2(high));
    const float half = std::max(1.02f * 0.5f * std::max(high.x - low.x, high.y - low.y), 1e-3f);
    const float depthMargin = 0.01f * std::max(high.z - low.z, 1e-3f);
    const float nearPlane = -high.z - depthMargin;  // view space looks down -z
    const float farPlane = -low.z + depthMargin;
    lookup.matrix = glm::ortho(middle.x - half, middle.x + half, middle.y - half, middle.y + half, nearPlane, farPlane) * view;
    lookup.depthScale = 1.0f / (farPlane - nearPlane);
    lookup.texel = 2.0f * half / static_cast<float>(kShadowMapSize);
    return lookup;
  }
  const float farPlane = farthestCorner(light.position, boundsMin, boundsMax);
  lookup.depthScale = 1.0f / farPlane;
  if (lookup.cube) {
    lookup.texel = 2.0f / static_cast<float>(kShadowCubeSize);  // a 90-degree face
    return lookup;
  }
  // A spot: a perspective map around its outer cone, a few texels wider for the filter.
  const glm::vec3 axis = light.spotAxis();
  const float halfAngle = std::min(light.outerConeAngle * 1.02f + 4.0f / kShadowMapSize, 1.45f);
  lookup.matrix = glm::perspective(2.0f * halfAngle, 1.0f, kNearFraction * farPlane, farPlane) *
                  glm::lookAt(light.position, light.position + axis, upFor(axis));
  lookup.texel = 2.0f * std::tan(halfAngle) / static_cast<float>(kShadowMapSize);
  return lookup;
}

glm::mat4 cubeFaceViewProjection(glm::vec3 lightPosition, int face, float farPlane) {
  // OpenGL's cube faces +x, -x, +y, -y, +z, -z with the up vectors that make a face's image the
  // one a lookup along its axis reads (the specification's major-axis table).
  static const glm::vec3 axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  static const glm::vec3 ups[6] = {{0, -1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}, {0, -1, 0}, {0, -1, 0}};
  const std::size_t f = static_cast<std::size_t>(face);
  return glm::perspective(glm::radians(90.0f), 1.0f, kNearFraction * farPlane, farPlane) *
         glm::lookAt(lightPosition, lightPosition + axes[f], ups[f]);
}

ShadowMaps::~ShadowMaps() {
  glDeleteTextures(1, &maps_);
  glDeleteTextures(1, &cubes_);
  glDeleteFramebuffers(1, &framebuffer_);
}

int ShadowMaps::cubeMask() const {
  int mask = 0;
  for (std::size_t i = 0; i < lookups_.size(); ++i) mask |= lookups_[i].cube ? 1 << i : 0;
  return mask;
}

void ShadowMaps::allocate(int planes, int cubes) {
  auto depthTexture = [](GLenum target, int size, int layers) {
    GLuint texture = 0;
    glCreateTextures(target, 1, &texture);
    glTextureStorage3D(texture, 1, GL_DEPTH_COMPONENT32F, size, size, layers);
    // Bilinear depth comparisons (percentage-closer filtering, shadows.glsl), edges clamped.
    glTextureParameteri(texture, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(texture, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(texture, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(texture, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTextureParameteri(texture, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    glTextureParameteri(texture, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
    return texture;
  };
  // At least one layer each, so that both samplers are complete whatever the lights.
  planes = std::max(planes, 1);
  cubes = std::max(cubes, 1);
  if (planes != planeLayers_) {
    glDeleteTextures(1, &maps_);
    maps_ = depthTexture(GL_TEXTURE_2D_ARRAY, kShadowMapSize, planes);
    planeLayers_ = planes;
  }
  if (cubes != cubeCount_) {
    glDeleteTextures(1, &cubes_);
    cubes_ = depthTexture(GL_TEXTURE_CUBE_MAP_ARRAY, kShadowCubeSize, 6 * cubes);
    cubeCount_ = cubes;
  }
  if (!framebuffer_) {
    glCreateFramebuffers(1, &framebuffer_);
    glNamedFramebufferDrawBuffer(framebuffer_, GL_NONE);
    glNamedFramebufferReadBuffer(framebuffer_, GL_NONE);
  }
}

void ShadowMaps::update(const std::vector<scene::Light>& lights, glm::vec3 boundsMin, glm::vec3 boundsMax,
                        const std::vector<float>& key, const DrawOccluders& draw) {
  if (valid_ && key == key_) return;
  lookups_.clear();
  int planes = 0, cubes = 0;
  for (const scene::Light& light : lights) {
    ShadowLookup lookup = shadowLookup(light, boundsMin, boundsMax);
    lookup.layer = lookup.cube ? cubes++ : planes++;
    lookups_.push_back(lookup);
  }
  allocate(planes, cubes);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glDisable(GL_CULL_FACE);  // the tracer's shadow rays stop at either side of a triangle
  glDisable(GL_STENCIL_TEST);
  glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  auto drawInto = [&](GLuint texture, int layer, int size, const glm::mat4& viewProjection, bool linear,
                      glm::vec3 origin, float depthScale) {
    glNamedFramebufferTextureLayer(framebuffer_, GL_DEPTH_ATTACHMENT, texture, 0, layer);
    if (glCheckNamedFramebufferStatus(framebuffer_, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
      throw Error("OpenGL: cannot draw into a " + std::to_string(size) + "x" + std::to_string(size) + " shadow map");
    }
    glViewport(0, 0, size, size);
    const float one = 1.0f;
    glClearNamedFramebufferfv(framebuffer_, GL_DEPTH, 0, &one);
    draw(viewProjection, linear, origin, depthScale);
  };
  for (std::size_t i = 0; i < lights.size(); ++i) {
    const ShadowLookup& lookup = lookups_[i];
    const scene::Light& light = lights[i];
    if (lookup.cube) {
      for (int face = 0; face < 6; ++face) {
        drawInto(cubes_, 6 * lookup.layer + face, kShadowCubeSize,
                 cubeFaceViewProjection(light.position, face, 1.0f / lookup.depthScale), true, light.position,
                 lookup.depthScale);
      }
    } else {
      drawInto(maps_, lookup.layer, kShadowMapSize, lookup.matrix, light.positional(), light.position, lookup.depthScale);
    }
  }
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  key_ = key;
  valid_ = true;
}

void ShadowMaps::bind() const {
  glBindTextureUnit(13, maps_);
  glBindTextureUnit(14, cubes_);
}

}  // namespace glint::gl
