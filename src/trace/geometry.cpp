#include "trace/geometry.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <memory>
#include <string>

#include <embree3/rtcore.h>

#include "glint/error.h"
#include "trace/texture.h"

namespace glint::trace {

namespace {

const char* errorName(RTCError code) {
  switch (code) {
    case RTC_ERROR_NONE: return "no error";
    case RTC_ERROR_UNKNOWN: return "unknown error";
    case RTC_ERROR_INVALID_ARGUMENT: return "invalid argument";
    case RTC_ERROR_INVALID_OPERATION: return "invalid operation";
    case RTC_ERROR_OUT_OF_MEMORY: return "out of memory";
    case RTC_ERROR_UNSUPPORTED_CPU: return "unsupported CPU";
    case RTC_ERROR_CANCELLED: return "cancelled";
  }
  return "unknown error";
}

void check(RTCDevice device, const char* what) {
  const RTCError code = rtcGetDeviceError(device);
  if (code != RTC_ERROR_NONE) throw Error(std::string("Embree: ") + what + ": " + errorName(code));
}

}  // namespace

// glTF alphaMode MASK: a hit counts where the base colour's alpha, factor times texture times
// vertex colour (COLOR_0), is at least the cutoff. The texture's alpha is filtered bilinearly at
// its finest level: a filter has no ray footprint, where the rasteriser's pre-pass samples the mip
// level of its pixel.
struct SceneGeometry::AlphaMask {
  // A texture's alpha channel, shared by every mesh whose material uses it (a glTF node instance
  // is a mesh of its own).
  struct Alpha {
    int width = 0;
    int height = 0;
    std::vector<float> texels;  // rows from the top, as scene::Texture
  };

  std::vector<glm::vec2> uvs;     // three per triangle (copied: the geometry may outlive the scene)
  std::vector<float> vertexAlpha;  // three per triangle, COLOR_0's alpha
  float factor = 1.0f;
  float cutoff = 0.5f;
  std::shared_ptr<const Alpha> texture;  // null: no texture

  bool keeps(unsigned triangle, float u, float v) const {
    const float* cornerAlpha = &vertexAlpha[3 * static_cast<std::size_t>(triangle)];
    float a = factor * ((1.0f - u - v) * cornerAlpha[0] + u * cornerAlpha[1] + v * cornerAlpha[2]);
    if (texture) {
      const glm::vec2* corner = &uvs[3 * static_cast<std::size_t>(triangle)];
      const glm::vec2 uv = (1.0f - u - v) * corner[0] + u * corner[1] + v * corner[2];
      a *= bilinearRepeat(texture->texels, texture->width, texture->height, uv);
    }
    return a >= cutoff;
  }

};

// What a mesh's hits go through before they count: glTF alphaMode MASK (AlphaMask), and glTF's
// back-face culling of single-sided materials. A ray that finds a surface (from the camera, or
// scattered) goes through the back of a single-sided triangle, as the rasteriser culls it; a
// shadow ray is stopped by both sides, as the rasteriser's shadow maps draw both.
struct SceneGeometry::HitFilter {
  const AlphaMask* mask = nullptr;  // null: no alpha mask
  bool cullBackFaces = false;       // a single-sided material

  // Embree's filters: clearing valid[i] makes the ray go on.
  static void intersection(const RTCFilterFunctionNArguments* args) {
    const auto* filter = static_cast<const HitFilter*>(args->geometryUserPtr);
    for (unsigned i = 0; i < args->N; ++i) {
      if (args->valid[i] == 0) continue;
      if (filter->cullBackFaces) {
        // Embree's Ng points out of the counter-clockwise front side (unnormalised): a ray meets
        // the front when it runs against Ng.
        const float along = RTCRayN_dir_x(args->ray, args->N, i) * RTCHitN_Ng_x(args->hit, args->N, i) +
                            RTCRayN_dir_y(args->ray, args->N, i) * RTCHitN_Ng_y(args->hit, args->N, i) +
                            RTCRayN_dir_z(args->ray, args->N, i) * RTCHitN_Ng_z(args->hit, args->N, i);
        if (!(along < 0.0f)) {
          args->valid[i] = 0;
          continue;
        }
      }
      if (filter->mask && !keptByMask(*filter->mask, args, i)) args->valid[i] = 0;
    }
  }
  static void occlusion(const RTCFilterFunctionNArguments* args) {
    const auto* filter = static_cast<const HitFilter*>(args->geometryUserPtr);
    for (unsigned i = 0; i < args->N; ++i) {
      if (args->valid[i] != 0 && filter->mask && !keptByMask(*filter->mask, args, i)) args->valid[i] = 0;
    }
  }

 private:
  static bool keptByMask(const AlphaMask& mask, const RTCFilterFunctionNArguments* args, unsigned i) {
    return mask.keeps(RTCHitN_primID(args->hit, args->N, i), RTCHitN_u(args->hit, args->N, i),
                      RTCHitN_v(args->hit, args->N, i));
  }
};

SceneGeometry::SceneGeometry(const scene::Scene& scene) {
  device_ = rtcNewDevice(nullptr);
  if (!device_) throw Error(std::string("Embree: cannot create a device: ") + errorName(rtcGetDeviceError(nullptr)));
  try {
    scene_ = rtcNewScene(device_);
    check(device_, "new scene");
    // Robust traversal: no rays slip between neighbouring triangles (no light leaks).
    rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);
    std::map<int, std::shared_ptr<const AlphaMask::Alpha>> alphas;  // by scene texture
    auto alphaOf = [&](int index) {
      std::shared_ptr<const AlphaMask::Alpha>& shared = alphas[index];
      if (shared) return shared;
      const scene::Texture& texture = scene.textures[static_cast<std::size_t>(index)];
      requireTexelData(texture);
      auto alpha = std::make_shared<AlphaMask::Alpha>();
      alpha->width = texture.width;
      alpha->height = texture.height;
      alpha->texels.resize(texture.rgba.size() / 4);
      for (std::size_t i = 0; i < alpha->texels.size(); ++i) alpha->texels[i] = texture.rgba[4 * i + 3] / 255.0f;
      shared = std::move(alpha);
      return shared;
    };
    maskOfMesh_.assign(scene.meshes.size(), nullptr);
    for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
      const scene::Mesh& mesh = scene.meshes[m];
      if (mesh.indices.size() < 3) continue;
      // The mask first: what it may throw then leaves no Embree geometry behind.
      AlphaMask* mask = nullptr;
      const scene::Material& material = scene.materials[static_cast<std::size_t>(mesh.material)];
      if (material.alphaMode == scene::Material::AlphaMode::Mask) {
        mask = masks_.emplace_back(std::make_unique<AlphaMask>()).get();
        maskOfMesh_[m] = mask;
        mask->uvs.reserve(mesh.indices.size() / 3 * 3);
        mask->vertexAlpha.reserve(mesh.indices.size() / 3 * 3);
        for (std::size_t i = 0; i < mesh.indices.size() / 3 * 3; ++i) {
          // The base colour texture's KHR_texture_transform is affine, so it can be applied to the
          // corners before they are interpolated.
          mask->uvs.push_back(material.baseColourUv.apply(mesh.vertices[mesh.indices[i]].uv));
          mask->vertexAlpha.push_back(mesh.vertices[mesh.indices[i]].colour.a);
        }
        mask->factor = material.baseColour.a;
        mask->cutoff = material.alphaCutoff;
        if (material.baseColourTexture >= 0) mask->texture = alphaOf(material.baseColourTexture);
      }
      RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
      auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
          geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), mesh.vertices.size()));
      auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
          geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), mesh.indices.size() / 3));
      check(device_, "geometry buffers");
      for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
        std::memcpy(vertices + 3 * i, &mesh.vertices[i].position.x, 3 * sizeof(float));
      }
      std::copy(mesh.indices.begin(), mesh.indices.begin() + static_cast<std::ptrdiff_t>(mesh.indices.size() / 3 * 3),
                indices);
      if (mask || !material.doubleSided) {
        HitFilter* filter = filters_.emplace_back(std::make_unique<HitFilter>()).get();
        filter->mask = mask;
        filter->cullBackFaces = !material.doubleSided;
        rtcSetGeometryUserData(geometry, filter);
        rtcSetGeometryIntersectFilterFunction(geometry, &HitFilter::intersection);
        if (mask) rtcSetGeometryOccludedFilterFunction(geometry, &HitFilter::occlusion);
      }
      rtcCommitGeometry(geometry);
      rtcAttachGeometryByID(scene_, geometry, static_cast<unsigned>(m));
      rtcReleaseGeometry(geometry);
      check(device_, "attach geometry");
    }
    rtcCommitScene(scene_);
    check(device_, "build scene");
  } catch (...) {
    if (scene_) rtcReleaseScene(scene_);
    rtcReleaseDevice(device_);
    throw;
  }
}

SceneGeometry::~SceneGeometry() {
  rtcReleaseScene(scene_);
  rtcReleaseDevice(device_);
}

std::optional<Hit> SceneGeometry::intersect(const Ray& ray, float tMax) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rayHit{};
  rayHit.ray.org_x = ray.origin.x;
  rayHit.ray.org_y = ray.origin.y;
  rayHit.ray.org_z = ray.origin.z;
  rayHit.ray.dir_x = ray.direction.x;
  rayHit.ray.dir_y = ray.direction.y;
  rayHit.ray.dir_z = ray.direction.z;
  rayHit.ray.tnear = 0.0f;
  rayHit.ray.tfar = tMax;
  rayHit.ray.mask = 0xFFFFFFFFu;
  rayHit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(scene_, &context, &rayHit);
  if (rayHit.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
  return Hit{rayHit.ray.tfar, rayHit.hit.geomID, rayHit.hit.primID, {rayHit.hit.u, rayHit.hit.v}};
}

bool SceneGeometry::occluded(const Ray& ray, float tMax) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay r{};
  r.org_x = ray.origin.x;
  r.org_y = ray.origin.y;
  r.org_z = ray.origin.z;
  r.dir_x = ray.direction.x;
  r.dir_y = ray.direction.y;
  r.dir_z = ray.direction.z;
  r.tnear = 0.0f;
  r.tfar = tMax;
  r.mask = 0xFFFFFFFFu;
  rtcOccluded1(scene_, &context, &r);
  // Embree sets tfar to -inf when the ray is blocked.
  return r.tfar < 0.0f;
}

bool SceneGeometry::maskedOut(const Hit& at) const {
  const AlphaMask* mask = at.mesh < maskOfMesh_.size() ? maskOfMesh_[at.mesh] : nullptr;
  return mask && !mask->keeps(at.triangle, at.barycentric.x, at.barycentric.y);
}

SurfacePoint surfacePoint(const scene::Scene& scene, const Hit& hit) {
  const scene::Mesh& mesh = scene.meshes[hit.mesh];
  const scene::Vertex& a = mesh.vertices[mesh.indices[3 * hit.triangle + 0]];
  const scene::Vertex& b = mesh.vertices[mesh.indices[3 * hit.triangle + 1]];
  const scene::Vertex& c = mesh.vertices[mesh.indices[3 * hit.triangle + 2]];
  const float wb = hit.barycentric.x;
  const float wc = hit.barycentric.y;
  const float wa = 1.0f - wb - wc;

  SurfacePoint p;
  p.material = mesh.material;
  p.position = wa * a.position + wb * b.position + wc * c.position;
  const glm::vec3 faceNormal = glm::cross(b.position - a.position, c.position - a.position);
  const float faceLength = glm::length(faceNormal);
  p.normal = wa * a.normal + wb * b.normal + wc * c.normal;
  const float normalLength = glm::length(p.normal);
  p.geometricNormal = faceLength > 0.0f ? faceNormal / faceLength : (normalLength > 0.0f ? p.normal / normalLength : glm::vec3(0, 0, 1));
  p.normal = normalLength > 0.0f ? p.normal / normalLength : p.geometricNormal;
  p.tangent = wa * a.tangent + wb * b.tangent + wc * c.tangent;
  p.uv = wa * a.uv + wb * b.uv + wc * c.uv;
  p.colour = wa * a.colour + wb * b.colour + wc * c.colour;

  // The triangle's dp/du and dp/dv (pbrt-v3, Triangle::Intersect) from two edges and their uvs.
  const glm::vec2 duv02 = a.uv - c.uv;
  const glm::vec2 duv12 = b.uv - c.uv;
  const glm::vec3 dp02 = a.position - c.position;
  const glm::vec3 dp12 = b.position - c.position;
  const float determinant = duv02.x * duv12.y - duv02.y * duv12.x;
  const float scale = std::max({std::abs(duv02.x), std::abs(duv02.y), std::abs(duv12.x), std::abs(duv12.y)});
  p.uvDegenerate = !(std::abs(determinant) > 1e-9f * scale * scale) || !std::isfinite(determinant);
  if (!p.uvDegenerate) {
    const float inverse = 1.0f / determinant;
    p.dpdu = (duv12.y * dp02 - duv02.y * dp12) * inverse;
    p.dpdv = (duv02.x * dp12 - duv12.x * dp02) * inverse;
  }
  return p;
}

UvDerivatives uvDerivatives(const SurfacePoint& point, const RayDifferential& rays) {
  UvDerivatives result;
  if (point.uvDegenerate) return result;
  const glm::vec3 n = point.geometricNormal;
  const float planeOffset = glm::dot(n, point.position);
  // Where an offset ray meets the triangle's plane, minus p; nothing when it runs parallel to it.
  auto offsetOnPlane = [&](const Ray& r, glm::vec3& dp) {
    const float denominator = glm::dot(n, r.direction);
    if (std::abs(denominator) < 1e-8f) return false;
    const float t = (planeOffset - glm::dot(n, r.origin)) / denominator;
    dp = r.origin + t * r.direction - point.position;
    return std::isfinite(dp.x) && std::isfinite(dp.y) && std::isfinite(dp.z);
  };
  glm::vec3 dpdx;
  glm::vec3 dpdy;
  if (!offsetOnPlane(rays.rx, dpdx) || !offsetOnPlane(rays.ry, dpdy)) return result;
  // Normal equations of [dpdu dpdv] (duv) = dp: a 2x2 system.
  const float a00 = glm::dot(point.dpdu, point.dpdu);
  const float a01 = glm::dot(point.dpdu, point.dpdv);
  const float a11 = glm::dot(point.dpdv, point.dpdv);
  const float determinant = a00 * a11 - a01 * a01;
  if (!(std::abs(determinant) > 1e-20f)) return result;
  auto solve = [&](glm::vec3 dp) {
    const float b0 = glm::dot(point.dpdu, dp);
    const float b1 = glm::dot(point.dpdv, dp);
    return glm::vec2(a11 * b0 - a01 * b1, a00 * b1 - a01 * b0) / determinant;
  };
  result.duvdx = solve(dpdx);
  result.duvdy = solve(dpdy);
  if (!std::isfinite(result.duvdx.x + result.duvdx.y + result.duvdy.x + result.duvdy.y)) return UvDerivatives{};
  return result;
}

Ray spawnRay(const SurfacePoint& point, glm::vec3 w) {
  // Float error of a hit point grows with its magnitude; 1e-4 m is far below the scenes' detail.
  const float maxCoordinate = std::max({std::abs(point.position.x), std::abs(point.position.y),
                                        std::abs(point.position.z)});
  const float epsilon = 1e-4f * (1.0f + maxCoordinate);
  const float side = glm::dot(point.geometricNormal, w) >= 0.0f ? 1.0f : -1.0f;
  return {point.position + side * epsilon * point.geometricNormal, w};
}

}  // namespace glint::trace
