// Per-hit material evaluation of the path tracer: the surface the kernel assembles from the
// textures' samples (kernel/surface.h, the rasteriser's too) turned into a BSDF that can be sampled:
//   - Lambertian diffuse baseColour (1 - metallic) / pi;
//   - plus a specular lobe times Schlick's Fresnel with F0 = mix(0.04, baseColour, metallic): the
//     glint BRDF when the material has a glint layer and the glint model is selected (coloured
//     cells tint it, inside GlintBsdf), Zirr & Kaplanyan 2016 when that model is, else Cook-Torrance
//     with the layer's alpha, or alpha = roughness^2 without one;
//   - under a KHR_materials_clearcoat coat (kernel/clearcoat.h): both dimmed by the coat's share of
//     the light, plus the coat's lobe.
// SceneMaterials::shade looks the textures up and builds the BSDF once per hit; what the integrator
// asks of a material (f, sample, pdf over its lobes) is in SurfaceMaterial.
#pragma once

#include <optional>
#include <variant>
#include <vector>

#include <glm/glm.hpp>

#include "glint/bsdf.h"
#include "glint/kernel/clearcoat.h"
#include "glint/specular_model.h"
#include "scene/scene.h"
#include "trace/geometry.h"
#include "trace/texture.h"

namespace glint::trace {

using scene::luminance;

// Shading frame: n the shading normal, t the tangent (alpha_x), b = cross(n, t) times the
// tangent's handedness (kernel/surface.h; so the frame may be left-handed).
struct ShadingFrame {
  glm::vec3 t{1, 0, 0};
  glm::vec3 b{0, 1, 0};
  glm::vec3 n{0, 0, 1};
  glm::vec3 toLocal(glm::vec3 v) const { return {glm::dot(v, t), glm::dot(v, b), glm::dot(v, n)}; }
  glm::vec3 toWorld(glm::vec3 v) const { return t * v.x + b * v.y + n * v.z; }
};

struct MaterialSample {
  Spectrum f;        // the whole material's f(wo, wi), without the cosine
  glm::vec3 wi;      // local frame
  float pdf;         // of the lobe mixture, solid angle
  Spectrum weight;   // f wi.z / pdf
};

// Lambertian diffuse plus one specular lobe, in the local shading frame (docs/conventions.md:
// directions away from the surface, f without the cosine), under an optional clear coat. Lobes are
// chosen for sampling in proportion to estimates of their albedos, and pdf() is the mixture's
// (one-sample MIS over lobes).
class SurfaceMaterial {
 public:
  using Specular = std::variant<CookTorranceBsdf, GlintBsdf, ZirrKaplanyanBsdf>;
  // `specularAlbedo`: an estimate of the specular lobe's reflectance (Fresnel at wo), to split
  // samples between the lobes. `coat` (weight 0: none) in the local frame, for the view wo the
  // material is made for: its weight is the extension's Fresnel at that view.
  SurfaceMaterial(Spectrum diffuse, Specular specular, Spectrum specularAlbedo, kernel::GlintCoat coat = noCoat());
  static kernel::GlintCoat noCoat();

  Spectrum f(glm::vec3 wo, glm::vec3 wi) const;
  float pdf(glm::vec3 wo, glm::vec3 wi) const;
  // uChoice picks the lobe (and is rescaled for the lobe's own choices), u the direction.
  std::optional<MaterialSample> sample(glm::vec3 wo, float uChoice, glm::vec2 u) const;

  Spectrum diffuse() const { return diffuse_; }  // baseColour (1 - metallic) / pi
  float specularProbability() const { return specularProbability_; }
  const Specular& specular() const { return specular_; }
  float coatWeight() const { return coat_.weight; }

 private:
  Spectrum specularF(glm::vec3 wo, glm::vec3 wi) const;
  float specularPdf(glm::vec3 wo, glm::vec3 wi) const;
  // The base (diffuse and specular) and the coat's lobe, each without the other.
  Spectrum baseF(glm::vec3 wo, glm::vec3 wi) const;
  float basePdf(glm::vec3 wo, glm::vec3 wi) const;
  float coatF(glm::vec3 wo, glm::vec3 wi) const;
  float coatPdf(glm::vec3 wo, glm::vec3 wi) const;
  std::optional<MaterialSample> sampleBase(glm::vec3 wo, float uChoice, glm::vec2 u) const;

  Spectrum diffuse_;
  Specular specular_;
  float specularProbability_;
  kernel::GlintCoat coat_;
  // The coat's lobe for sampling: GGX with Smith and its compensation, F = 1, in the coat's frame.
  std::optional<CookTorranceBsdf> coatLobe_;
  float coatProbability_ = 0.0f;
};

// What the shader knows at a fragment, for one path vertex.
struct ShadedPoint {
  ShadingFrame frame;
  glm::vec3 wo;       // towards the viewer, local; wo.z at least 1e-4 as in the shader
  Spectrum emitted;   // towards the viewer: SceneMaterials::emission
  SurfaceMaterial material;
};

class SceneMaterials {
 public:
  // Decodes the scene's textures into mip chains. The scene and the dictionary must outlive it.
  // With normalMapFiltering, glint layers on normal-mapped materials read the normal map's slope
  // moments (TraceSettings::normalMapFiltering).
  // The glint layers' footprints follow footprintPolicy (TraceSettings::footprintPolicy).
  SceneMaterials(const scene::Scene& scene, const Dictionary& dictionary, SpecularModel model,
                 GlintSampler sampler = GlintSampler::Mixture, bool normalMapFiltering = false,
                 FootprintPolicy footprintPolicy = exactFootprintPolicy());

  // The material at a surface point seen from direction `towardsViewer` (world, unit), with the
  // mesh-uv derivatives of the footprint (textures' level of detail; times the layer's uv_scale,
  // the glint footprint).
  ShadedPoint shade(const SurfacePoint& point, const UvDerivatives& footprint, glm::vec3 towardsViewer) const;

  // Radiance emitted at a surface point towards `towardsViewer` (world): the emissive factor
  // (times KHR_materials_emissive_strength) times the emissive texture at the footprint, as the
  // shader adds it. From the front face (counter-clockwise) only, unless the material is
  // doubleSided: glTF culls the back of a single-sided surface, so nothing sees it glow, and
  // draws a double-sided one's back with the same emission.
  Spectrum emission(const SurfacePoint& point, const UvDerivatives& footprint, glm::vec3 towardsViewer) const;

 private:
  glm::vec3 texture(int index, glm::vec2 uv, const UvDerivatives& footprint) const;
  // The same through a glTF KHR_texture_transform: the uv and its footprint are transformed.
  glm::vec3 texture(int index, const scene::UvTransform& transform, glm::vec2 uv, const UvDerivatives& footprint) const;

  const scene::Scene& scene_;
  const Dictionary& dictionary_;
  SpecularModel model_;
  GlintSampler sampler_;
  FootprintPolicy footprintPolicy_;
  std::vector<MipTexture> textures_;
  // Per material, the slope moments of its normal map when it has one and a glint layer, and
  // normal-map filtering is on: first (E[sx], E[sy], E[sx^2]) and second (E[sy^2], E[sx sy], 0).
  struct NormalMapMoments {
    MipTexture first;
    MipTexture second;
  };
  std::vector<std::optional<NormalMapMoments>> normalMapMoments_;
};

}  // namespace glint::trace
