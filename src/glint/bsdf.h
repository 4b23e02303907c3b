// BSDF value types in the spirit of pbrt-v4 (docs/conventions.md):
//   - directions in the local shading frame, z = normal, both pointing away from the surface;
//   - f(wo, wi) is the BRDF value WITHOUT the cosine factor;
//   - a BSDF is a small value type built per shading point; its parameters are validated when it
//     is built (glint::Error naming the field), never on the evaluation path.
// Sampling (sample / pdf) arrives with the path tracer; the types leave room for it.
#pragma once

#include <glm/glm.hpp>

#include "dictionary.h"
#include "kernel/glint_brdf.h"

namespace glint {

using Spectrum = glm::vec3;
using GlintParameters = kernel::GlintParameters;

// The reference defaults of model.md section 2.
GlintParameters defaultGlintParameters();
// Throws Error naming the first parameter out of range (ranges in docs/conventions.md).
void validateGlintParameters(const GlintParameters& parameters);
void validateRoughness(glm::vec2 alpha);

// Fresnel reflectance at the microfacet: none (F = 1), Schlick, or an exact conductor.
class Fresnel {
 public:
  static Fresnel none();
  static Fresnel schlick(Spectrum f0);
  static Fresnel conductor(Spectrum eta, Spectrum k);
  Spectrum evaluate(float cosThetaI) const;

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

// Cook-Torrance with a Beckmann NDF and V-cavity masking: the baseline, and the glint BRDF's limit.
class CookTorranceBsdf {
 public:
  CookTorranceBsdf(glm::vec2 alpha, Fresnel fresnel = Fresnel::none(), Spectrum reflectance = Spectrum(1.0f));
  Spectrum f(glm::vec3 wo, glm::vec3 wi) const;
  float ndf(glm::vec3 m) const;    // Beckmann D(m)
  float p22(glm::vec2 slope) const;

 private:
  glm::vec2 alpha_;
  Fresnel fresnel_;
  Spectrum reflectance_;
};

// The glint BRDF (model.md sections 2-3) at one shading point. Holds a reference to the
// dictionary, which must outlive it.
class GlintBsdf {
 public:
  GlintBsdf(const Dictionary& dictionary, const GlintParameters& parameters, const SurfaceFootprint& footprint,
            Fresnel fresnel = Fresnel::none(), Spectrum reflectance = Spectrum(1.0f));
  Spectrum f(glm::vec3 wo, glm::vec3 wi) const;
  float ndf(glm::vec3 m) const;     // D_P(m), the P-NDF
  float p22(glm::vec2 slope) const; // P22_P, the P-SDF

 private:
  kernel::DictionaryView dictionary_;
  GlintParameters parameters_;
  SurfaceFootprint footprint_;
  Fresnel fresnel_;
  Spectrum reflectance_;
};

}  // namespace glint
