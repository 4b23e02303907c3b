#include "gl/shadow_maps.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "glint/error.h"

namespace glint::gl {

namespace {

// The 8 corners of a box, or of a view frustum's slice: bit 0 picks x (left, right), bit 1 y
// (bottom, top), bit 2 z (the box's min and max, the slice's near and far face).
using Hexahedron = std::array<glm::vec3, 8>;

Hexahedron boxCorners(glm::vec3 boundsMin, glm::vec3 boundsMax) {
  Hexahedron corners;
  for (int c = 0; c < 8; ++c) {
    corners[static_cast<std::size_t>(c)] = glm::vec3((c & 1) ? boundsMax.x : boundsMin.x, (c & 2) ? boundsMax.y : boundsMin.y,
                                                     (c & 4) ? boundsMax.z : boundsMin.z);
  }
  return corners;
}

// The bounds' farthest corner from a point: the far plane of a positional light's map, a little
// beyond so that the farthest surface still stores a depth below the cleared 1.
float farthestCorner(glm::vec3 point, glm::vec3 boundsMin, glm::vec3 boundsMax) {
  float farthest = 0.0f;
  for (const glm::vec3& c : boxCorners(boundsMin, boundsMax)) farthest = std::max(farthest, glm::length(c - point));
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

// A convex hexahedron's faces, each as its corners in order around it.
constexpr int kFaces[6][4] = {{0, 2, 6, 4}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 5, 7, 6}};

// The half-spaces whose intersection a convex hexahedron is: (n, d) with dot(n, p) + d >= 0 inside.
std::vector<glm::vec4> insidePlanes(const Hexahedron& h) {
  glm::vec3 centroid(0.0f);
  for (const glm::vec3& c : h) centroid += c / 8.0f;
  std::vector<glm::vec4> planes;
  for (const auto& face : kFaces) {
    const glm::vec3 a = h[static_cast<std::size_t>(face[0])];
    // The face's normal from its diagonals, so that a collapsed edge leaves it defined.
    glm::vec3 n = glm::cross(h[static_cast<std::size_t>(face[2])] - a,
                             h[static_cast<std::size_t>(face[3])] - h[static_cast<std::size_t>(face[1])]);
    if (glm::length(n) == 0.0f) continue;
    n = glm::normalize(n);
    if (glm::dot(n, centroid - a) < 0.0f) n = -n;
    planes.push_back(glm::vec4(n, -glm::dot(n, a)));
  }
  return planes;
}

// Sutherland-Hodgman: the part of a convex polygon inside every plane.
std::vector<glm::vec3> clipPolygon(std::vector<glm::vec3> polygon, const std::vector<glm::vec4>& planes) {
  for (const glm::vec4& plane : planes) {
    std::vector<glm::vec3> kept;
    for (std::size_t i = 0; i < polygon.size(); ++i) {
      const glm::vec3 a = polygon[i];
      const glm::vec3 b = polygon[(i + 1) % polygon.size()];
      const float da = glm::dot(glm::vec3(plane), a) + plane.w;
      const float db = glm::dot(glm::vec3(plane), b) + plane.w;
      if (da >= 0.0f) kept.push_back(a);
      if ((da >= 0.0f) != (db >= 0.0f)) kept.push_back(a + (b - a) * (da / (da - db)));
    }
    polygon = std::move(kept);
    if (polygon.empty()) break;
  }
  return polygon;
}

// The corners of the intersection of two convex hexahedra (with extra points on its edges): every
// point of its surface lies on a face of one, inside the other, so the faces of each clipped by the
// other's planes hold all of its corners.
std::vector<glm::vec3> intersectionPoints(const Hexahedron& a, const Hexahedron& b) {
  std::vector<glm::vec3> points;
  for (const auto& [clipped, by] : {std::pair<const Hexahedron*, const Hexahedron*>{&a, &b}, {&b, &a}}) {
    const std::vector<glm::vec4> planes = insidePlanes(*by);
    for (const auto& face : kFaces) {
      std::vector<glm::vec3> polygon;
      for (int corner : face) polygon.push_back((*clipped)[static_cast<std::size_t>(corner)]);
      const std::vector<glm::vec3> inside = clipPolygon(polygon, planes);
      points.insert(points.end(), inside.begin(), inside.end());
    }
  }
  return points;
}

// A directional light's orthographic view: along it, through the bounds' centre.
glm::mat4 directionalView(const scene::Light& light, glm::vec3 boundsMin, glm::vec3 boundsMax) {
  const glm::vec3 direction = glm::normalize(light.direction);
  const glm::vec3 centre = 0.5f * (boundsMin + boundsMax);
  return glm::lookAt(centre - direction, centre, upFor(direction));
}

// A square orthographic map around `middle` (the light view's x, y) of half side `half`, its depth
// range [low.z, high.z] of the light's view with a 1% margin: the scene's, so that every occluder
// between a point and the light is in every cascade.
ShadowLookup orthographicLookup(const glm::mat4& view, glm::vec2 middle, float half, glm::vec3 low, glm::vec3 high) {
  ShadowLookup lookup;
  const float depthMargin = 0.01f * std::max(high.z - low.z, 1e-3f);
  const float nearPlane = -high.z - depthMargin;  // view space looks down -z
  const float farPlane = -low.z + depthMargin;
  lookup.matrix = glm::ortho(middle.x - half, middle.x + half, middle.y - half, middle.y + half, nearPlane, farPlane) * view;
  lookup.depthScale = 1.0f / (farPlane - nearPlane);
  lookup.texel = 2.0f * half / static_cast<float>(kShadowMapSize);
  return lookup;
}

// The cascades of a directional light. Each is fit to the part of the scene's bounds inside its
// slice of the view frustum, seen from the light, and kept steady as the camera moves: its half
// side is rounded up to a power of 2^(1/8), so that it changes only in steps of 9%, and its centre
// moves by whole texels, so that the occluders fall on the same texels (no shimmering edges). The
// rounding and snapping stay inside the margin of kCascadeMarginTexels + 1 texels left at the
// border. A cascade no smaller than the map of the whole scene is that map.
std::vector<ShadowLookup> directionalLookups(const scene::Light& light, glm::vec3 boundsMin, glm::vec3 boundsMax,
                                             const ShadowView& shadowView) {
  const glm::mat4 view = directionalView(light, boundsMin, boundsMax);
  const Hexahedron box = boxCorners(boundsMin, boundsMax);
  auto lightSpaceBounds = [&](const std::vector<glm::vec3>& points, glm::vec3& low, glm::vec3& high) {
    low = glm::vec3(INFINITY);
    high = glm::vec3(-INFINITY);
    for (const glm::vec3& p : points) {
      const glm::vec3 v = glm::vec3(view * glm::vec4(p, 1.0f));
      low = glm::min(low, v);
      high = glm::max(high, v);
    }
  };
  // The whole scene's map (2% margin, so that the filter's taps at the border stay inside).
  glm::vec3 sceneLow, sceneHigh;
  lightSpaceBounds(std::vector<glm::vec3>(box.begin(), box.end()), sceneLow, sceneHigh);
  const glm::vec2 sceneMiddle = 0.5f * (glm::vec2(sceneLow) + glm::vec2(sceneHigh));
  const float sceneHalf = std::max(1.02f * 0.5f * std::max(sceneHigh.x - sceneLow.x, sceneHigh.y - sceneLow.y), 1e-3f);
  const ShadowLookup wholeScene = orthographicLookup(view, sceneMiddle, sceneHalf, sceneLow, sceneHigh);
  const int cascades = std::clamp(shadowView.cascades, 1, kShadowCascades);
  if (cascades == 1) return {wholeScene};

  // The camera's frustum: its near and far corners, and the view depth along its axis.
  const glm::mat4 inverse = glm::inverse(shadowView.viewProjection);
  Hexahedron frustum;
  for (int c = 0; c < 8; ++c) {
    const glm::vec4 p = inverse * glm::vec4((c & 1) ? 1.0f : -1.0f, (c & 2) ? 1.0f : -1.0f, (c & 4) ? 1.0f : -1.0f, 1.0f);
    frustum[static_cast<std::size_t>(c)] = glm::vec3(p) / p.w;
  }
  const glm::vec3 nearCentre = 0.25f * (frustum[0] + frustum[1] + frustum[2] + frustum[3]);
  const glm::vec3 farCentre = 0.25f * (frustum[4] + frustum[5] + frustum[6] + frustum[7]);
  const glm::vec3 axis = glm::normalize(farCentre - nearCentre);
  auto depthOf = [&](glm::vec3 p) { return glm::dot(p - shadowView.cameraPosition, axis); };
  const float frustumNear = depthOf(nearCentre);
  const float frustumFar = depthOf(farCentre);
  // The depths the scene's bounds span, inside the frustum's.
  float sceneNear = INFINITY, sceneFar = -INFINITY;
  for (const glm::vec3& c : box) {
    sceneNear = std::min(sceneNear, depthOf(c));
    sceneFar = std::max(sceneFar, depthOf(c));
  }
  const float nearDepth = std::max(sceneNear, frustumNear);
  const float farDepth = std::min(sceneFar, frustumFar);
  if (!(farDepth > nearDepth) || !(frustumFar > frustumNear)) return std::vector<ShadowLookup>(cascades, wholeScene);
  const std::vector<float> splits = cascadeSplits(nearDepth, farDepth, cascades);

  std::vector<ShadowLookup> lookups;
  for (int k = 0; k < cascades; ++k) {
    // The slice between two splits: each frustum edge at those depths (depth is linear along it).
    Hexahedron slice;
    for (int c = 0; c < 4; ++c) {
      const glm::vec3 n = frustum[static_cast<std::size_t>(c)];
      const glm::vec3 f = frustum[static_cast<std::size_t>(c + 4)];
      for (int end = 0; end < 2; ++end) {
        const float t = (splits[static_cast<std::size_t>(k + end)] - frustumNear) / (frustumFar - frustumNear);
        slice[static_cast<std::size_t>(c + 4 * end)] = n + t * (f - n);
      }
    }
    const std::vector<glm::vec3> seen = intersectionPoints(slice, box);
    if (seen.empty()) {
      lookups.push_back(wholeScene);
      continue;
    }
    glm::vec3 low, high;
    lightSpaceBounds(seen, low, high);
    const float extent = std::max(0.5f * std::max(high.x - low.x, high.y - low.y), 1e-4f);
    const float rounded = std::exp2(std::ceil(8.0f * std::log2(extent)) / 8.0f);
    const float texel = 2.0f * rounded / static_cast<float>(kShadowMapSize - 2 * (kCascadeMarginTexels + 1));
    const float half = 0.5f * texel * static_cast<float>(kShadowMapSize);
    if (half >= sceneHalf) {
      lookups.push_back(wholeScene);
      continue;
    }
    const glm::vec2 middle = texel * glm::round(0.5f * (glm::vec2(low) + glm::vec2(high)) / texel);
    lookups.push_back(orthographicLookup(view, middle, half, sceneLow, sceneHigh));
  }
  return lookups;
}

}  // namespace

std::vector<float> cascadeSplits(float nearDepth, float farDepth, int cascades) {
  // Practical split scheme (Zhang et al. 2006): a weighed mean of the logarithmic split, which
  // gives every cascade the same ratio of far to near (so about the same texels per pixel), and
  // the uniform one.
  const float logNear = std::max(nearDepth, 1e-4f * farDepth);
  std::vector<float> splits(static_cast<std::size_t>(cascades) + 1);
  for (int k = 0; k <= cascades; ++k) {
    const float f = static_cast<float>(k) / static_cast<float>(cascades);
    const float logarithmic = logNear * std::pow(farDepth / logNear, f);
    const float uniform = nearDepth + (farDepth - nearDepth) * f;
    splits[static_cast<std::size_t>(k)] = kCascadeSplitLogWeight * logarithmic + (1.0f - kCascadeSplitLogWeight) * uniform;
  }
  splits.front() = nearDepth;
  splits.back() = farDepth;
  return splits;
}

std::vector<ShadowLookup> shadowLookups(const scene::Light& light, glm::vec3 boundsMin, glm::vec3 boundsMax,
                                        const ShadowView& view) {
  if (light.type == scene::Light::Type::Directional) return directionalLookups(light, boundsMin, boundsMax, view);
  ShadowLookup lookup;
  lookup.cube = usesCube(light);
  const float farPlane = farthestCorner(light.position, boundsMin, boundsMax);
  lookup.depthScale = 1.0f / farPlane;
  if (lookup.cube) {
    lookup.texel = 2.0f / static_cast<float>(kShadowCubeSize);  // a 90-degree face
    return {lookup};
  }
  // A spot: a perspective map around its outer cone, a few texels wider for the filter.
  const glm::vec3 axis = light.spotAxis();
  const float halfAngle = std::min(light.outerConeAngle * 1.02f + 4.0f / kShadowMapSize, 1.45f);
  lookup.matrix = glm::perspective(2.0f * halfAngle, 1.0f, kNearFraction * farPlane, farPlane) *
                  glm::lookAt(light.position, light.position + axis, upFor(axis));
  lookup.texel = 2.0f * std::tan(halfAngle) / static_cast<float>(kShadowMapSize);
  return {lookup};
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
  for (std::size_t i = 0; i < lookups_.size(); i += kShadowCascades) {
    mask |= lookups_[i].cube ? 1 << (i / kShadowCascades) : 0;
  }
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
                        const ShadowView& view, const std::vector<float>& key, const DrawOccluders& draw) {
  // The maps depend on the camera only through the cascades' matrices, which move in whole texels.
  std::vector<ShadowLookup> lookups(lights.size() * kShadowCascades);
  std::vector<float> fullKey = key;
  fullKey.push_back(static_cast<float>(view.cascades));
  int planes = 0, cubes = 0;
  for (std::size_t i = 0; i < lights.size(); ++i) {
    const std::vector<ShadowLookup> maps = shadowLookups(lights[i], boundsMin, boundsMax, view);
    for (std::size_t c = 0; c < maps.size(); ++c) {
      ShadowLookup lookup = maps[c];
      lookup.layer = lookup.cube ? cubes++ : planes++;
      if (lights[i].type == scene::Light::Type::Directional) {
        fullKey.insert(fullKey.end(), &lookup.matrix[0][0], &lookup.matrix[0][0] + 16);
      }
      lookups[i * kShadowCascades + c] = lookup;
    }
  }
  if (valid_ && fullKey == key_) return;
  lookups_ = std::move(lookups);
  cascades_ = std::clamp(view.cascades, 1, kShadowCascades);
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
    const scene::Light& light = lights[i];
    const int maps = light.type == scene::Light::Type::Directional ? cascades_ : 1;
    for (int c = 0; c < maps; ++c) {
      const ShadowLookup& lookup = lookups_[i * kShadowCascades + static_cast<std::size_t>(c)];
      if (lookup.cube) {
        for (int face = 0; face < 6; ++face) {
          drawInto(cubes_, 6 * lookup.layer + face, kShadowCubeSize,
                   cubeFaceViewProjection(light.position, face, 1.0f / lookup.depthScale), true, light.position,
                   lookup.depthScale);
        }
      } else {
        drawInto(maps_, lookup.layer, kShadowMapSize, lookup.matrix, light.positional(), light.position,
                 lookup.depthScale);
      }
    }
  }
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  key_ = std::move(fullKey);
  valid_ = true;
}

void ShadowMaps::bind() const {
  glBindTextureUnit(13, maps_);
  glBindTextureUnit(14, cubes_);
}

}  // namespace glint::gl
