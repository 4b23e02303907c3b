// BSDF value types in the spirit of pbrt-v4 (docs/conventions.md):
//   - directions in the local shading frame, z = normal, both pointing away from the surface;
//   - f(wo, wi) is the BRDF value WITHOUT the cosine factor;
//   - a BSDF is a small value type built per shading point; its parameters are validated when it
//     is built (glint::Error naming the field), never on the evaluation path.
//   - sample(wo, uChoice, u) draws wi by importance and returns f, pdf and the weight f |cos| / pdf;
//     pdf(wo, wi) is the solid-angle density of sample(), the same value for the same pair
//     (docs/sampling.md). sample() returns nullopt where it draws no direction (below the horizon,
//     or on a glint cell without microfacets): the pdf then integrates to less than 1.
#pragma once

#include <optional>
#include <string>

#include <glm/glm.hpp>

#include "glint/dictionary.h"
#include "glint/glint_fields.h"
#include "glint/kernel/glint_brdf.h"
#include "glint/kernel/zirr_kaplanyan.h"

namespace glint {

using Spectrum = glm::vec3;
using GlintParameters = kernel::GlintParameters;
using ZirrKaplanyanParameters = kernel::GlintZirrKaplanyanParameters;

// The renderer's footprint policy (kernel::GlintFootprintPolicy; docs/antialiasing.md, "Footprint
// policies"), `--footprint` on the command line: "exact" (the paper's footprint, the default), or
// any of aniso=A, cells=K, drop=W joined by commas.
using FootprintPolicy = kernel::GlintFootprintPolicy;
FootprintPolicy exactFootprintPolicy();
// Throws Error with one line naming the word that is wrong: an unknown word, a repeated one, a value
// that is not a number or out of range (validateFootprintPolicy).
FootprintPolicy footprintPolicyFromString(const std::string& text);
// The policy as footprintPolicyFromString reads it: "exact", or its words in the order aniso, cells,
// drop.
std::string footprintPolicyName(const FootprintPolicy& policy);
// aniso in [1, 64] (0: none), cells in [kMinFootprintCells, 1e6] (0: none), drop in [0, 1].
void validateFootprintPolicy(const FootprintPolicy& policy);
// The fewest cells a walk can be bounded by: however large its cells, a footprint's walk may take
// up to 8.6 steps (kernel::glintWalkBound; glintBoundedFootprint).
inline constexpr float kMinFootprintCells = 12.0f;

// The reference defaults of method.md section 2.
GlintParameters defaultGlintParameters();
// Throws Error naming the first parameter out of range (ranges in docs/conventions.md).
void validateGlintParameters(const GlintParameters& parameters);
// The ranges are glint_fields.h's (kGlintFields), for alpha on each axis and for rho.
void validateRoughness(glm::vec2 alpha);
void validateSlopeCorrelation(float rho);
// The same ranges as constants, for sliders and clamps.
inline constexpr float kMinRoughnessAlpha = static_cast<float>(glintField(GlintField::Alpha).minimum);
inline constexpr float kMaxRoughnessAlpha = static_cast<float>(glintField(GlintField::Alpha).maximum);
inline constexpr float kMaxSlopeCorrelation = static_cast<float>(glintField(GlintField::Rho).maximum);
inline constexpr float kMinLogDensity = static_cast<float>(glintField(GlintField::LogDensity).minimum);
inline constexpr float kMaxLogDensity = static_cast<float>(glintField(GlintField::LogDensity).maximum);

// Fresnel reflectance at the microfacet: none (F = 1), Schlick, or an exact conductor.
class Fresnel {
 public:
  static Fresnel none();
  static Fresnel schlick(Spectrum f0);
  static Fresnel conductor(Spectrum eta, Spectrum k);
  Spectrum evaluate(float cosThetaI) const;
  // The cosine-weighted hemispherical mean 2 integral of F(mu) mu dmu (the multiple-scattering
  // lobe's F_avg).
  Spectrum average() const;

 private:
  enum class Kind { None, Schlick, Conductor };
  Kind kind_ = Kind::None;
  Spectrum a_{1.0f};  // f0, or eta
  Spectrum b_{0.0f};  // k
};

// Where on the surface a pixel looks: uv and its screen-space derivatives (or ray differentials).
struct SurfaceFootprint {
  glm::vec2 uv{0.5f};
  glm::vec2 duvdx{1e-3f, 0.0f};
  glm::vec2 duvdy{0.0f, 1e-3f};
};
void validateFootprint(const SurfaceFootprint& footprint);

// One importance sample of a BSDF (docs/sampling.md): wi in the local frame, f(wo, wi) without the
// cosine, pdf(wo, wi) in solid angle, and the Monte Carlo weight f |wi.z| / pdf.
struct BsdfSample {
  Spectrum f;
  glm::vec3 wi;
  float pdf;
  Spectrum weight;  // f * |cos wi| / pdf
  bool transmission = false;
};

// How GlintBsdf draws its microfacet normals (docs/sampling.md): Mixture samples the P-NDF itself,
// as the finite mixture it is (Chermain et al. 2021, EGSR); Gaussian samples the single Beckmann
// lobe of the same roughness, the baseline (low cost, high variance for glints).
enum class GlintSampler { Mixture, Gaussian };

// The smooth target and masking of a microfacet BRDF (kernel/microfacet_targets.h): the 2020
// paper's Beckmann with V-cavity by default; glTF's is GGX with Smith.
struct MicrofacetTarget {
  int ndf = kernel::GLINT_NDF_BECKMANN;
  int masking = kernel::GLINT_MASKING_VCAVITY;
  bool multipleScattering = false;  // the compensation lobe of kernel/multiple_scattering.h
};
MicrofacetTarget microfacetTarget(const GlintParameters& parameters);
// The accepted names, as EXT_materials_glint, extras.glint and glint eval spell them: "beckmann" | "ggx",
// "v-cavity" | "smith". Throws Error naming the field and the value otherwise.
int ndfFromName(const std::string& field, const std::string& name);
int maskingFromName(const std::string& field, const std::string& name);
const char* ndfName(int ndf);
const char* maskingName(int masking);
// The glint layer's LOD construction (kernel GlintParameters::lod), as EXT_materials_glint's and
// extras.glint's "lod" and --lod spell it: "paper" | "consistent" (docs/method.md 2.7) | "tree"
// (2.8).
int lodFromName(const std::string& field, const std::string& name);
// A Choice field's names as a message lists them: "paper", "consistent" or "tree" (glint_fields.h).
std::string glintChoiceList(GlintField field);
// The value of a Choice field's name; throws Error naming `field` (as the input spells it) otherwise.
int glintChoiceFromName(GlintField choice, const std::string& field, const std::string& name);
const char* lodName(int lod);

// Cook-Torrance with the target's NDF (roughness alpha, slope correlation rho) and masking:
// the baseline, and the glint BRDF's limit.
class CookTorranceBsdf {
 public:
  CookTorranceBsdf(glm::vec2 alpha, float rho = 0.0f, Fresnel fresnel = Fresnel::none(),
                   Spectrum reflectance = Spectrum(1.0f), MicrofacetTarget target = MicrofacetTarget());
  Spectrum f(glm::vec3 wo, glm::vec3 wi) const;
  float ndf(glm::vec3 m) const;    // the target's D(m)
  float p22(glm::vec2 slope) const;
  // Slopes of the target, then the V-cavity's visible normals (Heitz & d'Eon 2014), whatever the
  // masking of f; uChoice, u in [0, 1).
  std::optional<BsdfSample> sample(glm::vec3 wo, float uChoice, glm::vec2 u) const;
  float pdf(glm::vec3 wo, glm::vec3 wi) const;

 private:
  glm::vec2 alpha_;
  float rho_;
  Fresnel fresnel_;
  Spectrum reflectance_;
  MicrofacetTarget target_;
  Spectrum compensationFresnel_;  // F_avg^2 E_avg / (1 - F_avg (1 - E_avg)), with multiple scattering
};

// The glint BRDF (method.md sections 2-3) at one shading point. Holds a reference to the
// dictionary, which must outlive it.
class GlintBsdf {
 public:
  GlintBsdf(const Dictionary& dictionary, const GlintParameters& parameters, const SurfaceFootprint& footprint,
            Fresnel fresnel = Fresnel::none(), Spectrum reflectance = Spectrum(1.0f),
            GlintSampler sampler = GlintSampler::Mixture);
  Spectrum f(glm::vec3 wo, glm::vec3 wi) const;
  float ndf(glm::vec3 m) const;     // D_P(m), the P-NDF
  float p22(glm::vec2 slope) const; // P22_P, the P-SDF
  // wi by the sampler's visible normals, reflected about them; uChoice, u in [0, 1).
  std::optional<BsdfSample> sample(glm::vec3 wo, float uChoice, glm::vec2 u) const;
  float pdf(glm::vec3 wo, glm::vec3 wi) const;
  GlintSampler sampler() const { return sampler_; }

  // The building blocks of sample() and pdf(), shared with GlintDielectricBsdf: a visible normal
  // for wo.z > 0 (nullopt on a cell without microfacets), uChoice coming back rescaled to [0, 1)
  // for a further choice; and its density D_wo(m) = G1(wo, m) <wo, m>+ D(m) / wo.z, with D the
  // P-NDF (Mixture) or Beckmann (Gaussian).
  std::optional<glm::vec3> sampleVisibleNormal(glm::vec3 wo, float& uChoice, glm::vec2 u) const;
  float visibleNormalPdf(glm::vec3 wo, glm::vec3 m) const;

 private:
  // (colour * D_P, D_P) at m: the P-NDF and its cells' colour weighting (kernel::glintP22Coloured).
  glm::vec4 colouredNdf(glm::vec3 m) const;

  kernel::GlintDictionaryView dictionary_;
  GlintParameters parameters_;
  SurfaceFootprint footprint_;
  Fresnel fresnel_;
  Spectrum reflectance_;
  GlintSampler sampler_;
  Spectrum compensationFresnel_;  // as CookTorranceBsdf's
};

// A glittering dielectric (Chermain et al. 2021, EGSR): the glint microfacets reflect
// and transmit, after Walter, Marschner, Li & Torrance 2007 (generalised half vectors, exact
// dielectric Fresnel), with V-cavity masking G = G1(wo) G1(wi). Conventions (docs/sampling.md):
//   - eta = n_inside / n_outside; the side z > 0 of the shading frame is the outside;
//   - wo and wi may each be on either side: same side is reflection, opposite sides transmission;
//   - f is for radiance (Walter 2007, Eq. 21: the transmitted part carries (n_wo / n_wi)^2), so
//     f(wo, wi) / n_wo^2 = f(wi, wo) / n_wi^2;
//   - sample() picks reflection with probability F(wo.m) at the sampled visible normal m.
class GlintDielectricBsdf {
 public:
  GlintDielectricBsdf(const Dictionary& dictionary, const GlintParameters& parameters,
                      const SurfaceFootprint& footprint, float eta, GlintSampler sampler = GlintSampler::Mixture);
  Spectrum f(glm::vec3 wo, glm::vec3 wi) const;
  std::optional<BsdfSample> sample(glm::vec3 wo, float uChoice, glm::vec2 u) const;
  float pdf(glm::vec3 wo, glm::vec3 wi) const;
  float eta() const { return eta_; }

 private:
  struct Evaluation {
    float f = 0.0f;
    float pdf = 0.0f;
  };
  Evaluation evaluate(glm::vec3 wo, glm::vec3 wi) const;

  GlintBsdf microfacets_;  // F = 1, white: its P-NDF and visible-normal sampler
  float eta_;
};

// The glint BRDF of Zirr & Kaplanyan 2016 (kernel/zirr_kaplanyan.h, docs/zirr-kaplanyan.md), the
// baseline, at one shading point. Built from our parameters through the spec's mapping
// (kernel::glintZirrKaplanyanFromGlint), or from the model's own parameters.
class ZirrKaplanyanBsdf {
 public:
  ZirrKaplanyanBsdf(const GlintParameters& parameters, const SurfaceFootprint& footprint,
                    Fresnel fresnel = Fresnel::none(), Spectrum reflectance = Spectrum(1.0f));
  ZirrKaplanyanBsdf(const ZirrKaplanyanParameters& parameters, const SurfaceFootprint& footprint,
                    Fresnel fresnel = Fresnel::none(), Spectrum reflectance = Spectrum(1.0f));
  Spectrum f(glm::vec3 wo, glm::vec3 wi) const;
  // Directions from the visible normals of the Beckmann lobe of the model's macro roughness, the
  // smooth lobe its microdetails scatter around (spec 1.2): the model itself has no sampler. f is
  // the model's and pdf that lobe's, so sample()'s weight f |cos| / pdf is the model's, unbiased
  // wherever the lobe's density is positive (everywhere above the horizon).
  std::optional<BsdfSample> sample(glm::vec3 wo, float uChoice, glm::vec2 u) const;
  float pdf(glm::vec3 wo, glm::vec3 wi) const;
  const ZirrKaplanyanParameters& parameters() const { return parameters_; }

 private:
  ZirrKaplanyanParameters parameters_;
  SurfaceFootprint footprint_;
  Fresnel fresnel_;
  Spectrum reflectance_;
  CookTorranceBsdf proposal_;  // the sampler's lobe
  // Built from glint parameters: their smooth target's multiple-scattering compensation lobe, added
  // as the rasteriser adds it to every model (not scaled by the relative area); none otherwise.
  MicrofacetTarget target_;
  glm::vec2 alpha_{0.0f};
  Spectrum compensationFresnel_{0.0f};
};

// The Shadertoy's snow material (spec 2.2): r = 0.6, mu = 0.024 r, c = 0.01, v = 100, R = 50000,
// rho_d = 5e8, K_a = 16, in world-scale uv units.
ZirrKaplanyanParameters defaultZirrKaplanyanParameters();
// Throws Error naming the first parameter out of range (docs/zirr-kaplanyan.md).
void validateZirrKaplanyanParameters(const ZirrKaplanyanParameters& parameters);

}  // namespace glint
