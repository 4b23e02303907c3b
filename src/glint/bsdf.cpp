#include "bsdf.h"

#include <cmath>
#include <sstream>
#include <string>

#include "error.h"

namespace glint {

namespace {

void requireRange(const char* field, float value, float low, float high) {
  if (!(value >= low && value <= high)) {
    std::ostringstream message;
    message << field << " must be in [" << low << ", " << high << "], got " << value;
    throw Error(message.str());
  }
}

void requireFinite(const char* field, glm::vec2 value) {
  if (!std::isfinite(value.x) || !std::isfinite(value.y)) {
    std::ostringstream message;
    message << field << " must be finite, got [" << value.x << ", " << value.y << "]";
    throw Error(message.str());
  }
}

}  // namespace

GlintParameters defaultGlintParameters() {
  GlintParameters p;
  p.alpha = glm::vec2(0.5f);
  p.logDensity = 27.0f;
  p.relativeArea = 1.0f;
  p.densityRandomisation = 2.0f;
  p.maxAnisotropy = 8.0f;
  p.patternSeed = 0u;
  p.colouredCells = false;
  return p;
}

void validateRoughness(glm::vec2 alpha) {
  requireRange("alpha_x", alpha.x, 0.005f, 2.0f);
  requireRange("alpha_y", alpha.y, 0.005f, 2.0f);
}

void validateGlintParameters(const GlintParameters& p) {
  validateRoughness(p.alpha);
  requireRange("log_density", p.logDensity, 0.0f, 100.0f);
  if (!(p.relativeArea > 0.0f && p.relativeArea <= 1.0f)) {
    std::ostringstream message;
    message << "relative_area must be in (0, 1], got " << p.relativeArea;
    throw Error(message.str());
  }
  requireRange("density_randomisation", p.densityRandomisation, 0.0f, 10.0f);
  requireRange("max_anisotropy", p.maxAnisotropy, 1.0f, 64.0f);
}

void validateFootprint(const SurfaceFootprint& footprint) {
  requireFinite("uv", footprint.uv);
  requireFinite("duvdx", footprint.duvdx);
  requireFinite("duvdy", footprint.duvdy);
}

Fresnel Fresnel::none() { return Fresnel(); }

Fresnel Fresnel::schlick(Spectrum f0) {
  for (int c = 0; c < 3; ++c) requireRange("Schlick f0", f0[c], 0.0f, 1.0f);
  Fresnel fresnel;
  fresnel.kind_ = Kind::Schlick;
  fresnel.a_ = f0;
  return fresnel;
}

Fresnel Fresnel::conductor(Spectrum eta, Spectrum k) {
  for (int c = 0; c < 3; ++c) {
    requireRange("conductor eta", eta[c], 1e-3f, 100.0f);
    requireRange("conductor k", k[c], 0.0f, 100.0f);
  }
  Fresnel fresnel;
  fresnel.kind_ = Kind::Conductor;
  fresnel.a_ = eta;
  fresnel.b_ = k;
  return fresnel;
}

Spectrum Fresnel::evaluate(float cosThetaI) const {
  switch (kind_) {
    case Kind::None: return Spectrum(1.0f);
    case Kind::Schlick: return kernel::fresnelSchlick(a_, cosThetaI);
    case Kind::Conductor: return kernel::fresnelConductor(a_, b_, cosThetaI);
  }
  return Spectrum(1.0f);
}

CookTorranceBsdf::CookTorranceBsdf(glm::vec2 alpha, Fresnel fresnel, Spectrum reflectance)
    : alpha_(alpha), fresnel_(fresnel), reflectance_(reflectance) {
  validateRoughness(alpha);
}

Spectrum CookTorranceBsdf::f(glm::vec3 wo, glm::vec3 wi) const {
  const float value = kernel::cookTorranceReflectance(alpha_, wo, wi);
  if (value == 0.0f) return Spectrum(0.0f);
  return reflectance_ * fresnel_.evaluate(glm::dot(wo, glm::normalize(wo + wi))) * value;
}

float CookTorranceBsdf::ndf(glm::vec3 m) const {
  return m.z > 0.0f ? kernel::ndfFromP22(p22(kernel::slopeFromNormal(m)), m.z) : 0.0f;
}

float CookTorranceBsdf::p22(glm::vec2 slope) const { return kernel::beckmannP22(slope, alpha_); }

GlintBsdf::GlintBsdf(const Dictionary& dictionary, const GlintParameters& parameters,
                     const SurfaceFootprint& footprint, Fresnel fresnel, Spectrum reflectance)
    : dictionary_(dictionary.view()),
      parameters_(parameters),
      footprint_(footprint),
      fresnel_(fresnel),
      reflectance_(reflectance) {
  validateGlintParameters(parameters);
  validateFootprint(footprint);
}

Spectrum GlintBsdf::f(glm::vec3 wo, glm::vec3 wi) const {
  const float value = kernel::glintReflectance(dictionary_, parameters_, footprint_.uv, footprint_.duvdx,
                                               footprint_.duvdy, wo, wi);
  if (value == 0.0f) return Spectrum(0.0f);
  return reflectance_ * fresnel_.evaluate(glm::dot(wo, glm::normalize(wo + wi))) * value;
}

float GlintBsdf::ndf(glm::vec3 m) const {
  return m.z > 0.0f ? kernel::ndfFromP22(p22(kernel::slopeFromNormal(m)), m.z) : 0.0f;
}

float GlintBsdf::p22(glm::vec2 slope) const {
  return kernel::glintP22(dictionary_, parameters_, footprint_.uv, footprint_.duvdx, footprint_.duvdy, slope);
}

}  // namespace glint
