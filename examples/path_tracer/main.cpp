// A small CPU path tracer that shades with glint's BSDF from an installed glint (find_package(glint)):
// a glinty sphere lit by a small spherical light under a dim sky, with next-event estimation and BSDF
// sampling combined by multiple importance sampling, as pbrt or Mitsuba would.
//
//   glint_path_tracer OUTPUT.{png,exr} [--smooth] [--dictionary FILE] [--size N] [--spp N]
//
// --smooth shades with the smooth Cook-Torrance lobe that the glint BRDF converges to (the same
// roughness, NDF, masking and Fresnel), for comparison. --dictionary reads a file written by
// `glint dict`; without it the dictionary is generated at start (the same default parameters).
//
// How a host renderer uses glint's BSDF (glint/bsdf.h):
//   - Frame: glint's BSDFs work in a local shading frame, z the normal, x the tangent (dp/du, the
//     direction of alpha_x and of increasing u), y = cross(z, x). wo and wi both point away from the
//     surface. f(wo, wi) has no cosine: the renderer multiplies by wi.z.
//   - Footprint: the glint BRDF is the reflectance of the microfacets inside the pixel's footprint on
//     the surface, in uv. The renderer gives it the hit's uv and the uv derivatives across one pixel,
//     from ray differentials (pbrt-v3 10.1.1): the offset rays through the next pixel right and down
//     meet the tangent plane at p + dp/dx and p + dp/dy, and dp = dp/du du + dp/dv dv is solved for
//     du, dv. Each sample gets the whole pixel's footprint: the BRDF already averages over it.
//   - A BSDF is a small value built per shading point (it holds the footprint and a reference to the
//     dictionary, which must outlive it); sample(wo, uChoice, u) returns wi, f, the solid-angle pdf
//     and weight = f |wi.z| / pdf, or nothing; pdf(wo, wi) is the density sample() draws wi with, for
//     the MIS weight of a light sample.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>
#include <variant>

#include <glm/glm.hpp>
#include <tbb/parallel_for.h>

#include <glint/bsdf.h>
#include <glint/dictionary.h>
#include <glint/error.h>
#include <glint/image_io.h>
#include <glint/pcg.h>

namespace {

using glm::vec2;
using glm::vec3;
constexpr float kPi = 3.14159265358979f;

// The scene: a unit sphere at the origin seen from +z (it spans 70% of the frame's height), a light
// sphere up and to the right of the camera, so that the highlight sits on the sphere's upper right.
constexpr vec3 kCameraPosition{0.0f, 0.0f, 3.6f};
constexpr float kVerticalFovDegrees = 45.0f;
constexpr vec3 kLightCentre{3.0f, 3.0f, 5.0f};
constexpr float kLightRadius = 0.1f;
constexpr vec3 kLightRadiance{1900.0f};  // about 60 W/sr: radiance * pi * radius^2
// The glint uv is the sphere's uv (u around, v from the north pole) times this, so that the pattern's
// cells are small enough on screen.
constexpr float kUvScale = 4.0f;

vec3 skyRadiance(vec3 direction) { return glm::mix(vec3(0.01f), vec3(0.03f, 0.035f, 0.05f), 0.5f + 0.5f * direction.y); }

struct Ray {
  vec3 origin;
  vec3 direction;  // unit length
};

// A camera ray with its offset rays through the film points one pixel right and one pixel down.
struct RayDifferential {
  Ray ray, offsetX, offsetY;
};

// The nearest t > 0 where the ray meets a sphere, if any.
std::optional<float> intersectSphere(const Ray& ray, vec3 centre, float radius) {
  const vec3 oc = ray.origin - centre;
  const float b = glm::dot(oc, ray.direction);
  const float c = glm::dot(oc, oc) - radius * radius;
  const float discriminant = b * b - c;
  if (discriminant < 0.0f) return std::nullopt;
  const float root = std::sqrt(discriminant);
  const float t = -b - root > 1e-4f ? -b - root : -b + root;
  if (t <= 1e-4f) return std::nullopt;
  return t;
}

// t where the ray meets the plane through p with normal n.
float intersectPlane(const Ray& ray, vec3 p, vec3 n) { return glm::dot(n, p - ray.origin) / glm::dot(n, ray.direction); }

// The shading point on the unit sphere with its frame and uv footprint (the glint BSDF's inputs).
struct ShadingPoint {
  vec3 position, tangent, bitangent, normal;
  glint::SurfaceFootprint footprint;
  vec3 toLocal(vec3 v) const { return {glm::dot(v, tangent), glm::dot(v, bitangent), glm::dot(v, normal)}; }
  vec3 toWorld(vec3 v) const { return v.x * tangent + v.y * bitangent + v.z * normal; }
};

// u = phi / 2 pi with phi = atan2(z, x), v = theta / pi with theta from +y: p = (sin theta cos phi,
// cos theta, sin theta sin phi), dp/du = 2 pi sin theta (-sin phi, 0, cos phi), dp/dv = pi (cos theta
// cos phi, -sin theta, cos theta sin phi); the two are perpendicular, so dp projects on each alone.
ShadingPoint shadeSphere(vec3 p, const Ray& offsetX, const Ray& offsetY) {
  ShadingPoint s;
  s.position = p;
  s.normal = glm::normalize(p);
  const float phi = std::atan2(p.z, p.x);
  const float theta = std::acos(std::clamp(p.y, -1.0f, 1.0f));
  s.tangent = vec3(-std::sin(phi), 0.0f, std::cos(phi));
  s.bitangent = glm::cross(s.normal, s.tangent);
  const vec3 dpdvUnit(std::cos(theta) * std::cos(phi), -std::sin(theta), std::cos(theta) * std::sin(phi));
  const float dpduLength = 2.0f * kPi * std::max(std::sin(theta), 1e-3f);  // the poles: a long, thin footprint
  const float dpdvLength = kPi;
  auto duv = [&](const Ray& offset) {
    const vec3 dp = offset.origin + intersectPlane(offset, p, s.normal) * offset.direction - p;
    return vec2(glm::dot(dp, s.tangent) / dpduLength, glm::dot(dp, dpdvUnit) / dpdvLength);
  };
  const vec2 uv((phi < 0.0f ? phi + 2.0f * kPi : phi) / (2.0f * kPi), theta / kPi);
  s.footprint.uv = kUvScale * uv;
  s.footprint.duvdx = kUvScale * duv(offsetX);
  s.footprint.duvdy = kUvScale * duv(offsetY);
  if (!std::isfinite(s.footprint.duvdx.x + s.footprint.duvdx.y + s.footprint.duvdy.x + s.footprint.duvdy.y)) {
    s.footprint.duvdx = s.footprint.duvdy = vec2(0.0f);  // a grazing offset ray: no area, the smooth limit
  }
  return s;
}

// The sphere's material: glint's BSDF, or the smooth lobe it converges to. Both have f, sample, pdf.
struct Material {
  std::variant<glint::GlintBsdf, glint::CookTorranceBsdf> bsdf;
  glint::Spectrum f(vec3 wo, vec3 wi) const { return std::visit([&](const auto& b) { return b.f(wo, wi); }, bsdf); }
  float pdf(vec3 wo, vec3 wi) const { return std::visit([&](const auto& b) { return b.pdf(wo, wi); }, bsdf); }
  std::optional<glint::BsdfSample> sample(vec3 wo, float uChoice, vec2 u) const {
    return std::visit([&](const auto& b) { return b.sample(wo, uChoice, u); }, bsdf);
  }
};

float powerHeuristic(float pdfA, float pdfB) { return pdfA * pdfA / (pdfA * pdfA + pdfB * pdfB); }

// Directions towards the light sphere from p: uniform in the cone it subtends (pbrt-v4, Sphere::Sample).
struct LightCone {
  vec3 axis;
  float cosMax;
  float oneMinusCosMax;  // sin^2 / (1 + cos): exact where the cone is narrow
  explicit LightCone(vec3 p) {
    const vec3 toCentre = kLightCentre - p;
    const float distance2 = glm::dot(toCentre, toCentre);
    axis = toCentre / std::sqrt(distance2);
    const float sin2 = kLightRadius * kLightRadius / distance2;
    cosMax = std::sqrt(1.0f - sin2);
    oneMinusCosMax = sin2 / (1.0f + cosMax);
  }
  float pdf() const { return 1.0f / (2.0f * kPi * oneMinusCosMax); }
  vec3 sample(vec2 u) const {
    const float cosTheta = 1.0f - u.x * oneMinusCosMax;
    const float sinTheta = std::sqrt(std::max(0.0f, 1.0f - cosTheta * cosTheta));
    const vec3 a = std::abs(axis.x) > 0.9f ? vec3(0, 1, 0) : vec3(1, 0, 0);
    const vec3 x = glm::normalize(glm::cross(a, axis)), y = glm::cross(axis, x);
    const float phi = 2.0f * kPi * u.y;
    return sinTheta * std::cos(phi) * x + sinTheta * std::sin(phi) * y + cosTheta * axis;
  }
};

float uniform(glint::Pcg32& rng) { return static_cast<float>(rng.nextOpenUnit()); }

struct Options {
  std::string output;
  std::string dictionary;
  bool smooth = false;
  int size = 128;
  int spp = 16;
};

// One camera path: the sphere (convex, so a direction above its tangent plane leaves it, and no
// shadow ray is needed), then the light or the sky. A renderer with more geometry repeats the vertex
// part below at each bounce, with a shadow ray for the light sample.
vec3 radiance(const Options& options, const glint::Dictionary& dictionary, const glint::GlintParameters& parameters,
              const glint::Fresnel& fresnel, const RayDifferential& camera, glint::Pcg32& rng) {
  const Ray& ray = camera.ray;
  const std::optional<float> tSphere = intersectSphere(ray, vec3(0.0f), 1.0f);
  const std::optional<float> tLight = intersectSphere(ray, kLightCentre, kLightRadius);
  if (tLight && (!tSphere || *tLight < *tSphere)) return kLightRadiance;
  if (!tSphere) return skyRadiance(ray.direction);

  const ShadingPoint s = shadeSphere(ray.origin + *tSphere * ray.direction, camera.offsetX, camera.offsetY);
  const Material material =
      options.smooth
          ? Material{glint::CookTorranceBsdf(parameters.alpha, parameters.rho, fresnel, glint::Spectrum(1.0f),
                                             glint::microfacetTarget(parameters))}
          : Material{glint::GlintBsdf(dictionary, parameters, s.footprint, fresnel)};
  const vec3 wo = s.toLocal(-ray.direction);
  const LightCone cone(s.position);
  vec3 result(0.0f);

  // Next-event estimation: a direction towards the light, weighed against BSDF sampling.
  const vec3 wiLight = s.toLocal(cone.sample(vec2(uniform(rng), uniform(rng))));
  if (wiLight.z > 0.0f) {
    const vec3 f = material.f(wo, wiLight);
    result += f * kLightRadiance * (wiLight.z / cone.pdf()) * powerHeuristic(cone.pdf(), material.pdf(wo, wiLight));
  }

  // BSDF sampling: a direction by the BSDF, weighed against the light sample where it meets the light.
  const float uChoice = uniform(rng);
  const std::optional<glint::BsdfSample> bounce = material.sample(wo, uChoice, vec2(uniform(rng), uniform(rng)));
  if (bounce && bounce->wi.z > 0.0f) {
    const vec3 direction = s.toWorld(bounce->wi);
    if (intersectSphere({s.position, direction}, kLightCentre, kLightRadius)) {
      result += bounce->weight * kLightRadiance * powerHeuristic(bounce->pdf, cone.pdf());
    } else {
      result += bounce->weight * skyRadiance(direction);  // the sky is found by BSDF sampling alone
    }
  }
  return result;
}

int run(const Options& options) {
  const glint::Dictionary dictionary = options.dictionary.empty()
                                           ? glint::generateDictionary(glint::DictionaryParameters{})
                                           : glint::Dictionary::load(options.dictionary);
  glint::GlintParameters parameters = glint::defaultGlintParameters();  // alpha 0.5, Beckmann, V-cavity
  parameters.logDensity = 11.0f;  // e^11 microfacets per unit glint uv: sparse enough to sparkle at 128 px
  glint::validateGlintParameters(parameters);
  const glint::Fresnel fresnel = glint::Fresnel::schlick(vec3(0.95f, 0.64f, 0.54f));  // copper-like

  const int size = options.size;
  const float tanHalf = std::tan(0.5f * kVerticalFovDegrees * kPi / 180.0f);
  // The ray through film point (x, y) in pixels, y down; the camera looks along -z with y up.
  auto cameraRay = [&](vec2 film) {
    const vec2 ndc = 2.0f * film / float(size) - 1.0f;
    return Ray{kCameraPosition, glm::normalize(vec3(ndc.x * tanHalf, -ndc.y * tanHalf, -1.0f))};
  };
  glint::ImageRgbF image = glint::ImageRgbF::filled(size, size);
  tbb::parallel_for(0, size, [&](int y) {
    for (int x = 0; x < size; ++x) {
      glint::Pcg32 rng(1, static_cast<std::uint64_t>(y) * size + x);  // one stream a pixel: any thread count
      vec3 sum(0.0f);
      for (int i = 0; i < options.spp; ++i) {
        const vec2 film = vec2(x, y) + vec2(uniform(rng), uniform(rng));
        const RayDifferential rays{cameraRay(film), cameraRay(film + vec2(1, 0)), cameraRay(film + vec2(0, 1))};
        sum += radiance(options, dictionary, parameters, fresnel, rays, rng);
      }
      image.at(x, y) = sum / float(options.spp);
    }
  });
  glint::writeImage(options.output, image);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const char* usage = "usage: glint_path_tracer OUTPUT.{png,exr} [--smooth] [--dictionary FILE] [--size N] [--spp N]";
  Options options;
  try {
    for (int i = 1; i < argc; ++i) {
      const std::string argument = argv[i];
      auto value = [&]() -> std::string {
        if (i + 1 >= argc) throw glint::Error(argument + " needs a value");
        return argv[++i];
      };
      auto count = [&](int low, int high) {
        const std::string text = value();
        char* end = nullptr;
        const long n = std::strtol(text.c_str(), &end, 10);
        if (text.empty() || *end != '\0' || n < low || n > high) {
          throw glint::Error(argument + " must be a whole number in [" + std::to_string(low) + ", " +
                             std::to_string(high) + "], got '" + text + "'");
        }
        return static_cast<int>(n);
      };
      if (argument == "-h" || argument == "--help") {
        std::printf("%s\n", usage);
        return 0;
      }
      if (argument == "--smooth") options.smooth = true;
      else if (argument == "--dictionary") options.dictionary = value();
      else if (argument == "--size") options.size = count(8, 4096);
      else if (argument == "--spp") options.spp = count(1, 65536);
      else if (argument[0] != '-' && options.output.empty()) options.output = argument;
      else throw glint::Error("unknown argument '" + argument + "'");
    }
    if (options.output.empty()) throw glint::Error(usage);
    glint::requireImageExtension(options.output);  // before the work, not after it
    return run(options);
  } catch (const glint::Error& e) {
    std::fprintf(stderr, "glint_path_tracer: error: %s\n", e.what());
    return 1;
  }
}
