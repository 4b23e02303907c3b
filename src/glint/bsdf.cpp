#include "glint/bsdf.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "glint/error.h"
#include "glint/glint_fields.h"
#include "glint/kernel/multiple_scattering.h"
#include "glint/microfacet_sampling.h"

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

FootprintPolicy exactFootprintPolicy() {
  FootprintPolicy policy;
  policy.maxAnisotropy = 0.0f;
  policy.maxCells = 0.0f;
  policy.minBlend = 0.0f;
  return policy;
}

FootprintPolicy footprintPolicyFromString(const std::string& text) {
  FootprintPolicy policy = exactFootprintPolicy();
  if (text == "exact") return policy;
  const std::string context = "footprint policy '" + text + "': ";
  if (text.empty()) throw Error(context + "expected exact, or aniso=A, cells=K, drop=W joined by commas");
  bool seen[3] = {false, false, false};
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = std::min(text.find(',', start), text.size());
    const std::string word = text.substr(start, comma - start);
    start = comma + 1;
    const std::size_t equals = word.find('=');
    const std::string name = word.substr(0, equals);
    const int index = name == "aniso" ? 0 : name == "cells" ? 1 : name == "drop" ? 2 : -1;
    if (index < 0 || equals == std::string::npos) {
      throw Error(context + "unknown word '" + word + "' (expected exact, or aniso=A, cells=K, drop=W joined by commas)");
    }
    if (seen[index]) throw Error(context + name + " is given twice");
    seen[index] = true;
    const std::string number = word.substr(equals + 1);
    char* end = nullptr;
    const float value = number.empty() ? std::nanf("") : std::strtof(number.c_str(), &end);
    if (number.empty() || end != number.c_str() + number.size() || !std::isfinite(value)) {
      throw Error(context + name + " must be a number, got '" + number + "'");
    }
    if (index == 0) {
      if (!(value >= 1.0f && value <= 64.0f)) throw Error(context + "aniso must be in [1, 64], got " + number);
      policy.maxAnisotropy = value;
    } else if (index == 1) {
      if (!(value >= kMinFootprintCells && value <= 1e6f && value == std::floor(value))) {
        throw Error(context + "cells must be a whole number in [12, 1000000], got " + number);
      }
      policy.maxCells = value;
    } else {
      if (!(value >= 0.0f && value <= 1.0f)) throw Error(context + "drop must be in [0, 1], got " + number);
      policy.minBlend = value;
    }
  }
  return policy;
}

std::string footprintPolicyName(const FootprintPolicy& policy) {
  std::ostringstream name;
  const char* separator = "";
  if (policy.maxAnisotropy > 0.0f) {
    name << "aniso=" << policy.maxAnisotropy;
    separator = ",";
  }
  if (policy.maxCells > 0.0f) {
    name << separator << "cells=" << policy.maxCells;
    separator = ",";
  }
  if (policy.minBlend > 0.0f) name << separator << "drop=" << policy.minBlend;
  return name.str().empty() ? "exact" : name.str();
}

void validateFootprintPolicy(const FootprintPolicy& policy) {
  if (policy.maxAnisotropy != 0.0f) requireRange("footprint policy aniso", policy.maxAnisotropy, 1.0f, 64.0f);
  if (policy.maxCells != 0.0f) requireRange("footprint policy cells", policy.maxCells, kMinFootprintCells, 1e6f);
  requireRange("footprint policy drop", policy.minBlend, 0.0f, 1.0f);
}

GlintParameters defaultGlintParameters() {
  GlintParameters p = kernel::glintMaterialConstants(glintDefaultMaterial(), exactFootprintPolicy());
  // The 2020 paper's target (glTF's is glint_fields.h's default, scene::kGltfSpecular).
  p.ndf = kernel::GLINT_NDF_BECKMANN;
  p.masking = kernel::GLINT_MASKING_VCAVITY;
  p.multipleScattering = false;
  return p;
}

MicrofacetTarget microfacetTarget(const GlintParameters& parameters) {
  return MicrofacetTarget{parameters.ndf, parameters.masking, parameters.multipleScattering};
}

// "a", "b" or "c", as a message lists a Choice field's names.
std::string glintChoiceList(GlintField field) {
  std::vector<std::string> names;
  for (const char* name : glintField(field).choices) {
    if (name != nullptr) names.push_back("\"" + std::string(name) + "\"");
  }
  std::string list;
  for (std::size_t i = 0; i < names.size(); ++i) {
    list += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + names[i];
  }
  return list;
}

int glintChoiceFromName(GlintField choice, const std::string& field, const std::string& name) {
  const int value = glintChoiceValue(choice, name);
  if (value < 0) throw Error(field + " must be " + glintChoiceList(choice) + ", got \"" + name + "\"");
  return value;
}

int ndfFromName(const std::string& field, const std::string& name) { return glintChoiceFromName(GlintField::Ndf, field, name); }
int maskingFromName(const std::string& field, const std::string& name) {
  return glintChoiceFromName(GlintField::Masking, field, name);
}
int lodFromName(const std::string& field, const std::string& name) { return glintChoiceFromName(GlintField::Lod, field, name); }
const char* lodName(int lod) { return glintChoiceName(GlintField::Lod, lod); }
const char* ndfName(int ndf) { return glintChoiceName(GlintField::Ndf, ndf); }
const char* maskingName(int masking) { return glintChoiceName(GlintField::Masking, masking); }

namespace {

void validateTarget(const MicrofacetTarget& target) {
  if (target.ndf != kernel::GLINT_NDF_BECKMANN && target.ndf != kernel::GLINT_NDF_GGX) {
    throw Error("ndf must be beckmann (0) or ggx (1), got " + std::to_string(target.ndf));
  }
  if (target.masking != kernel::GLINT_MASKING_VCAVITY && target.masking != kernel::GLINT_MASKING_SMITH) {
    throw Error("masking must be v-cavity (0) or smith (1), got " + std::to_string(target.masking));
  }
}

}  // namespace

namespace {

// `value` within the field's range (glint_fields.h), the message naming it as `name`.
void requireFieldRange(const char* name, GlintField field, float value) {
  const GlintFieldSpec& spec = glintField(field);
  const auto low = static_cast<float>(spec.minimum);
  const auto high = static_cast<float>(spec.maximum);
  if (!spec.exclusiveMinimum) {
    requireRange(name, value, low, high);
  } else if (!(value > low && value <= high)) {
    std::ostringstream message;
    message << name << " must be in (" << low << ", " << high << "], got " << value;
    throw Error(message.str());
  }
}

}  // namespace

void validateRoughness(glm::vec2 alpha) {
  requireFieldRange("alpha_x", GlintField::Alpha, alpha.x);
  requireFieldRange("alpha_y", GlintField::Alpha, alpha.y);
}

void validateSlopeCorrelation(float rho) {
  // |rho| = 1 is a degenerate Gaussian; the clamp keeps M^-1's 1 / sqrt(1 - rho^2) below 7.1.
  requireFieldRange("rho", GlintField::Rho, rho);
}

void validateGlintParameters(const GlintParameters& p) {
  validateRoughness(p.alpha);
  // The numbers the model takes as they are, each through its row (glint_fields.h), named as
  // extras.glint and `glint eval` spell them; the glTF reader renames them as its file does.
  for (const GlintFieldSpec& spec : kGlintFields) {
    if (spec.parameter != nullptr) requireFieldRange(spec.extras, spec.field, p.*spec.parameter);
  }
  validateTarget(microfacetTarget(p));
  if (glintChoiceName(GlintField::Lod, p.lod)[0] == '\0') {
    throw Error("lod must be paper (0), consistent (1) or tree (2), got " + std::to_string(p.lod));
  }
  validateFootprintPolicy(p.footprintPolicy);
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
    case Kind::Schlick: return kernel::glintFresnelSchlick(a_, cosThetaI);
    case Kind::Conductor: return kernel::glintFresnelConductor(a_, b_, cosThetaI);
  }
  return Spectrum(1.0f);
}

Spectrum Fresnel::average() const {
  switch (kind_) {
    case Kind::None: return Spectrum(1.0f);
    case Kind::Schlick: return kernel::glintSchlickAverageFresnel(a_);
    case Kind::Conductor: {
      // 2 integral of F(mu) mu dmu by 256 midpoints: F is smooth, the sum is exact to 1e-5.
      constexpr int kPoints = 256;
      Spectrum sum(0.0f);
      for (int k = 0; k < kPoints; ++k) {
        const float mu = (static_cast<float>(k) + 0.5f) / kPoints;
        sum += kernel::glintFresnelConductor(a_, b_, mu) * mu;
      }
      return sum * (2.0f / kPoints);
    }
  }
  return Spectrum(1.0f);
}

namespace {

// The multiple-scattering compensation lobe (kernel/multiple_scattering.h) of a target at roughness
// alpha: its Fresnel factor F_avg^2 E_avg / (1 - F_avg (1 - E_avg)) (0 without compensation) ...
Spectrum compensationFresnel(const MicrofacetTarget& target, glm::vec2 alpha, const Fresnel& fresnel) {
  if (!target.multipleScattering) return Spectrum(0.0f);
  const float averageAlbedo = kernel::glintAverageAlbedo(target.ndf, target.masking, kernel::glintCompensationAlpha(alpha));
  return kernel::glintMultipleScatteringFresnel(fresnel.average(), averageAlbedo);
}

// ... its value, with that factor and the colour ...
Spectrum compensation(const MicrofacetTarget& target, glm::vec2 alpha, Spectrum fresnelFactor, Spectrum reflectance,
                      glm::vec3 wo, glm::vec3 wi) {
  if (!target.multipleScattering) return Spectrum(0.0f);
  return reflectance * fresnelFactor *
         kernel::glintMultipleScatteringReflectance(target.ndf, target.masking, alpha, wo, wi);
}

// ... and the probability that sample() draws it (cosine-weighted) rather than the microfacets:
// the share of the energy it carries with F = 1, 1 - E(mu_o).
float compensationProbability(const MicrofacetTarget& target, glm::vec2 alpha, glm::vec3 wo) {
  if (!target.multipleScattering || wo.z <= 0.0f) return 0.0f;
  return std::clamp(
      1.0f - kernel::glintDirectionalAlbedo(target.ndf, target.masking, kernel::glintCompensationAlpha(alpha), wo.z), 0.0f,
      1.0f);
}

}  // namespace

CookTorranceBsdf::CookTorranceBsdf(glm::vec2 alpha, float rho, Fresnel fresnel, Spectrum reflectance,
                                   MicrofacetTarget target)
    : alpha_(alpha), rho_(rho), fresnel_(fresnel), reflectance_(reflectance), target_(target) {
  validateRoughness(alpha);
  validateSlopeCorrelation(rho);
  validateTarget(target);
  compensationFresnel_ = compensationFresnel(target, alpha, fresnel);
}

Spectrum CookTorranceBsdf::f(glm::vec3 wo, glm::vec3 wi) const {
  const Spectrum multiple = compensation(target_, alpha_, compensationFresnel_, reflectance_, wo, wi);
  const float value = kernel::glintTargetCookTorranceReflectance(target_.ndf, target_.masking, alpha_, rho_, wo, wi);
  if (value == 0.0f) return multiple;
  return reflectance_ * fresnel_.evaluate(glm::dot(wo, glm::normalize(wo + wi))) * value + multiple;
}

float CookTorranceBsdf::ndf(glm::vec3 m) const {
  return m.z > 0.0f ? kernel::glintNdfFromP22(p22(kernel::glintSlopeFromNormal(m)), m.z) : 0.0f;
}

float CookTorranceBsdf::p22(glm::vec2 slope) const { return kernel::glintTargetP22(target_.ndf, slope, alpha_, rho_); }

GlintBsdf::GlintBsdf(const Dictionary& dictionary, const GlintParameters& parameters,
                     const SurfaceFootprint& footprint, Fresnel fresnel, Spectrum reflectance, GlintSampler sampler)
    : dictionary_(dictionary.view()),
      parameters_(parameters),
      footprint_(footprint),
      fresnel_(fresnel),
      reflectance_(reflectance),
      sampler_(sampler) {
  validateGlintParameters(parameters);
  validateFootprint(footprint);
  compensationFresnel_ = compensationFresnel(microfacetTarget(parameters), parameters.alpha, fresnel);
}

namespace {

// The Cook-Torrance frame around a value of the P-NDF at wh = normalize(wo + wi), with the material's
// masking, Fresnel and colour: what kernel::glintReflectance computes, given the NDF value, so that
// sample() evaluates the P-NDF once for both f and pdf.
Spectrum glintReflection(const GlintParameters& parameters, const Fresnel& fresnel, Spectrum reflectance,
                         glm::vec3 wo, glm::vec3 wi, glm::vec3 wh, float ndf) {
  const float value = kernel::glintMaskedReflectance(parameters, wo, wi, wh, ndf);
  if (value == 0.0f) return Spectrum(0.0f);
  return reflectance * fresnel.evaluate(glm::dot(wo, wh)) * value;
}

// The colour of coloured cells (the shader's tint): the P22-weighted mean cell colour, from the
// (colour * P22, P22) pair of kernel::glintP22Coloured; white for uncoloured glints.
Spectrum cellTint(glm::vec4 colouredP22) {
  return colouredP22.w > 0.0f ? Spectrum(colouredP22) / colouredP22.w : Spectrum(1.0f);
}

}  // namespace

glm::vec4 GlintBsdf::colouredNdf(glm::vec3 m) const {
  if (m.z <= 0.0f) return glm::vec4(0.0f);
  const glm::vec4 p = kernel::glintP22Coloured(dictionary_, parameters_, footprint_.uv, footprint_.duvdx,
                                               footprint_.duvdy, kernel::glintSlopeFromNormal(m));
  const float toNdf = kernel::glintNdfFromP22(1.0f, m.z);
  return p * toNdf;
}

Spectrum GlintBsdf::f(glm::vec3 wo, glm::vec3 wi) const {
  if (wo.z <= 0.0f || wi.z <= 0.0f) return Spectrum(0.0f);
  const glm::vec3 wh = glm::normalize(wo + wi);
  const glm::vec4 d = colouredNdf(wh);
  return glintReflection(parameters_, fresnel_, reflectance_, wo, wi, wh, d.w) * cellTint(d) +
         compensation(microfacetTarget(parameters_), parameters_.alpha, compensationFresnel_, reflectance_, wo, wi);
}

float GlintBsdf::ndf(glm::vec3 m) const {
  return m.z > 0.0f ? kernel::glintNdfFromP22(p22(kernel::glintSlopeFromNormal(m)), m.z) : 0.0f;
}

float GlintBsdf::p22(glm::vec2 slope) const {
  return kernel::glintP22(dictionary_, parameters_, footprint_.uv, footprint_.duvdx, footprint_.duvdy, slope);
}

// ---------------------------------------------------------------------------------------------
// Importance sampling (docs/sampling.md): CookTorranceBsdf, GlintBsdf, GlintDielectricBsdf.

namespace {

// Mirror reflection of wo about a microfacet normal m: wi = 2 (wo.m) m - wo.
glm::vec3 reflectAbout(glm::vec3 wo, glm::vec3 m) { return glm::normalize(2.0f * glm::dot(wo, m) * m - wo); }

// A visible normal of the smooth target's lobe: a slope of its P22 (that is, m from D(m) m.z), then
// the V-cavity's choice between m and its mirror (Heitz & d'Eon 2014, section 5).
glm::vec3 sampleTargetVisibleNormal(int ndf, glm::vec2 alpha, float rho, glm::vec3 wo, float& uChoice, glm::vec2 u) {
  const glm::vec3 m = sampling::normalFromSlope(sampling::sampleTargetSlope(ndf, alpha, rho, u));
  return sampling::sampleVCavityVisibleNormal(wo, m, uChoice);
}

float targetNdf(int ndf, glm::vec2 alpha, float rho, glm::vec3 m) {
  return m.z > 0.0f ? kernel::glintNdfFromP22(kernel::glintTargetP22(ndf, kernel::glintSlopeFromNormal(m), alpha, rho), m.z) : 0.0f;
}

// Density of a direction reflected about visible normals: D_wo(wh) / (4 wo.wh), the Jacobian of
// the reflection dwh / dwi = 1 / (4 wi.wh) (Walter et al. 2007, Eq. 14; Heitz 2014, Eq. 17).
float reflectionPdf(glm::vec3 wo, glm::vec3 wh, float visibleNdf) {
  const float cosine = glm::dot(wo, wh);
  return cosine > 0.0f ? visibleNdf / (4.0f * cosine) : 0.0f;
}

std::optional<BsdfSample> makeSample(Spectrum f, glm::vec3 wi, float pdf, bool transmission) {
  if (!(pdf > 0.0f)) return std::nullopt;
  return BsdfSample{f, wi, pdf, f * (std::abs(wi.z) / pdf), transmission};
}

}  // namespace

// With multiple scattering, sample() draws the compensation lobe with probability p
// (compensationProbability), by the cosine, else the microfacets with uChoice rescaled; the pdf is
// the mixture's, (1 - p) pdf_microfacets + p wi.z / pi. Without it p = 0 and nothing changes.
std::optional<BsdfSample> CookTorranceBsdf::sample(glm::vec3 wo, float uChoice, glm::vec2 u) const {
  if (wo.z <= 0.0f) return std::nullopt;
  const float p = compensationProbability(target_, alpha_, wo);
  glm::vec3 wi;
  if (uChoice < p) {
    wi = sampling::sampleCosineHemisphere(u);
  } else {
    if (p > 0.0f) uChoice = sampling::remapUniform(uChoice, p, 1.0f - p);
    wi = reflectAbout(wo, sampleTargetVisibleNormal(target_.ndf, alpha_, rho_, wo, uChoice, u));
  }
  if (wi.z <= 0.0f) return std::nullopt;
  return makeSample(f(wo, wi), wi, pdf(wo, wi), false);
}

float CookTorranceBsdf::pdf(glm::vec3 wo, glm::vec3 wi) const {
  if (wo.z <= 0.0f || wi.z <= 0.0f) return 0.0f;
  const glm::vec3 wh = glm::normalize(wo + wi);
  const float microfacets =
      reflectionPdf(wo, wh, sampling::visibleNdf(wo, wh, targetNdf(target_.ndf, alpha_, rho_, wh)));
  const float p = compensationProbability(target_, alpha_, wo);
  return p > 0.0f ? (1.0f - p) * microfacets + p * sampling::cosineHemispherePdf(wi.z) : microfacets;
}

std::optional<glm::vec3> GlintBsdf::sampleVisibleNormal(glm::vec3 wo, float& uChoice, glm::vec2 u) const {
  if (sampler_ == GlintSampler::Gaussian) {
    return sampleTargetVisibleNormal(parameters_.ndf, parameters_.alpha, parameters_.rho, wo, uChoice, u);
  }
  const std::optional<glm::vec2> slope = sampling::sampleGlintSlope(
      dictionary_, parameters_, footprint_.uv, footprint_.duvdx, footprint_.duvdy, uChoice, u);
  if (!slope) return std::nullopt;  // a cell without microfacets
  return sampling::sampleVCavityVisibleNormal(wo, sampling::normalFromSlope(*slope), uChoice);
}

float GlintBsdf::visibleNormalPdf(glm::vec3 wo, glm::vec3 m) const {
  if (m.z <= 0.0f) return 0.0f;
  const float d =
      sampler_ == GlintSampler::Gaussian ? targetNdf(parameters_.ndf, parameters_.alpha, parameters_.rho, m) : ndf(m);
  return sampling::visibleNdf(wo, m, d);
}

std::optional<BsdfSample> GlintBsdf::sample(glm::vec3 wo, float uChoice, glm::vec2 u) const {
  if (wo.z <= 0.0f) return std::nullopt;
  // The compensation lobe, as CookTorranceBsdf::sample.
  const MicrofacetTarget target = microfacetTarget(parameters_);
  const float p = compensationProbability(target, parameters_.alpha, wo);
  if (uChoice < p) {
    const glm::vec3 wi = sampling::sampleCosineHemisphere(u);
    if (wi.z <= 0.0f) return std::nullopt;
    return makeSample(f(wo, wi), wi, pdf(wo, wi), false);
  }
  if (p > 0.0f) uChoice = sampling::remapUniform(uChoice, p, 1.0f - p);
  const std::optional<glm::vec3> m = sampleVisibleNormal(wo, uChoice, u);
  if (!m) return std::nullopt;
  const glm::vec3 wi = reflectAbout(wo, *m);
  if (wi.z <= 0.0f) return std::nullopt;
  // f and pdf at the half vector of (wo, wi), as f() and pdf() compute them, with the P-NDF
  // evaluated once.
  const glm::vec3 wh = glm::normalize(wo + wi);
  const glm::vec4 d = colouredNdf(wh);
  const float visible =
      sampler_ == GlintSampler::Mixture ? sampling::visibleNdf(wo, wh, d.w) : visibleNormalPdf(wo, wh);
  const Spectrum value = glintReflection(parameters_, fresnel_, reflectance_, wo, wi, wh, d.w) * cellTint(d);
  const float microfacets = reflectionPdf(wo, wh, visible);
  if (!(p > 0.0f)) return makeSample(value, wi, microfacets, false);
  return makeSample(value + compensation(target, parameters_.alpha, compensationFresnel_, reflectance_, wo, wi), wi,
                    (1.0f - p) * microfacets + p * sampling::cosineHemispherePdf(wi.z), false);
}

float GlintBsdf::pdf(glm::vec3 wo, glm::vec3 wi) const {
  if (wo.z <= 0.0f || wi.z <= 0.0f) return 0.0f;
  const glm::vec3 wh = glm::normalize(wo + wi);
  const float microfacets = reflectionPdf(wo, wh, visibleNormalPdf(wo, wh));
  const float p = compensationProbability(microfacetTarget(parameters_), parameters_.alpha, wo);
  return p > 0.0f ? (1.0f - p) * microfacets + p * sampling::cosineHemispherePdf(wi.z) : microfacets;
}

GlintDielectricBsdf::GlintDielectricBsdf(const Dictionary& dictionary, const GlintParameters& parameters,
                                         const SurfaceFootprint& footprint, float eta, GlintSampler sampler)
    : microfacets_(dictionary, parameters, footprint, Fresnel::none(), Spectrum(1.0f), sampler), eta_(eta) {
  requireRange("eta", eta, 0.2f, 5.0f);
  if (std::abs(eta - 1.0f) < 1e-3f) {
    // Index matched: every microfacet transmits wo straight through, a Dirac the model cannot hold.
    std::ostringstream message;
    message << "eta must differ from 1 by at least 1e-3, got " << eta;
    throw Error(message.str());
  }
}

GlintDielectricBsdf::Evaluation GlintDielectricBsdf::evaluate(glm::vec3 wo, glm::vec3 wi) const {
  const float cosO = wo.z;
  const float cosI = wi.z;
  if (cosO == 0.0f || cosI == 0.0f) return {};
  const bool reflection = cosO * cosI > 0.0f;
  // etap = n_wi / n_wo, the relative index across the interface (1 for reflection).
  const float etap = reflection ? 1.0f : (cosO > 0.0f ? eta_ : 1.0f / eta_);
  // Generalised half vector (Walter et al. 2007, Eq. 16), turned to the outside.
  glm::vec3 wm = wo + etap * wi;
  if (glm::dot(wm, wm) == 0.0f) return {};
  wm = glm::normalize(wm);
  if (wm.z < 0.0f) wm = -wm;
  // Both directions must see the front of the microfacet from their own side.
  if (wm.z <= 0.0f || glm::dot(wm, wo) * cosO <= 0.0f || glm::dot(wm, wi) * cosI <= 0.0f) return {};

  const float d = microfacets_.ndf(wm);
  const float g = sampling::vcavityG1TwoSided(wo, wm) * sampling::vcavityG1TwoSided(wi, wm);
  const float fresnel = sampling::fresnelDielectric(glm::dot(wo, wm), eta_);
  // Visible normals are drawn for the viewer's side turned up: D_wo(m) with |wo|.
  const float visible = microfacets_.visibleNormalPdf(cosO > 0.0f ? wo : -wo, wm);
  const float cosOM = glm::dot(wo, wm);
  const float cosIM = glm::dot(wi, wm);
  Evaluation result;
  if (reflection) {
    // Walter et al. 2007, Eq. 20; pdf: Eq. 14 times the probability F of choosing reflection.
    result.f = fresnel * g * d / (4.0f * std::abs(cosI * cosO));
    result.pdf = visible / (4.0f * std::abs(cosOM)) * fresnel;
  } else {
    // Walter et al. 2007, Eq. 21 (radiance), written with etap = n_wi / n_wo:
    // f = (1 - F) G D |wi.m| |wo.m| / (|wi.z| |wo.z| (wi.m + wo.m / etap)^2) / etap^2;
    // pdf: dwm / dwi = |wi.m| / (wi.m + wo.m / etap)^2 (Eq. 17), times the probability 1 - F.
    const float sqrtDenominator = cosIM + cosOM / etap;
    const float denominator = sqrtDenominator * sqrtDenominator;
    if (!(denominator > 0.0f)) return {};
    result.f = (1.0f - fresnel) * g * d * std::abs(cosIM * cosOM) / (std::abs(cosI * cosO) * denominator) /
               (etap * etap);
    result.pdf = visible * std::abs(cosIM) / denominator * (1.0f - fresnel);
  }
  return result;
}

Spectrum GlintDielectricBsdf::f(glm::vec3 wo, glm::vec3 wi) const { return Spectrum(evaluate(wo, wi).f); }

float GlintDielectricBsdf::pdf(glm::vec3 wo, glm::vec3 wi) const { return evaluate(wo, wi).pdf; }

std::optional<BsdfSample> GlintDielectricBsdf::sample(glm::vec3 wo, float uChoice, glm::vec2 u) const {
  if (wo.z == 0.0f) return std::nullopt;
  const std::optional<glm::vec3> m = microfacets_.sampleVisibleNormal(wo.z > 0.0f ? wo : -wo, uChoice, u);
  if (!m) return std::nullopt;  // a cell without microfacets: neither reflects nor transmits
  const float fresnel = sampling::fresnelDielectric(glm::dot(wo, *m), eta_);
  glm::vec3 wi;
  bool transmission = false;
  if (uChoice < fresnel) {
    wi = reflectAbout(wo, *m);
    if (wi.z * wo.z <= 0.0f) return std::nullopt;
  } else {
    const std::optional<glm::vec3> refracted = sampling::refractDirection(wo, *m, eta_);
    if (!refracted || refracted->z * wo.z >= 0.0f) return std::nullopt;
    wi = *refracted;
    transmission = true;
  }
  const Evaluation e = evaluate(wo, wi);
  return makeSample(Spectrum(e.f), wi, e.pdf, transmission);
}

ZirrKaplanyanParameters defaultZirrKaplanyanParameters() {
  ZirrKaplanyanParameters p;
  p.roughness = glm::vec2(0.6f);
  p.microRoughness = 0.024f * p.roughness;
  p.searchConeAngle = 0.01f;
  p.variation = 100.0f;
  p.dynamicRange = 50000.0f;
  p.logDensity = std::log(5e8f);
  p.maxAnisotropy = kernel::GLINT_ZIRR_KAPLANYAN_REFERENCE_MAX_ANISOTROPY;
  p.patternSeed = 0u;
  return p;
}

void validateZirrKaplanyanParameters(const ZirrKaplanyanParameters& p) {
  // The glint layer's alpha range (glint_fields.h), whose roughness it takes.
  requireRange("roughness_x", p.roughness.x, kMinRoughnessAlpha, kMaxRoughnessAlpha);
  requireRange("roughness_y", p.roughness.y, kMinRoughnessAlpha, kMaxRoughnessAlpha);
  // The bin index q / (mu + c) stays below 1e4 in magnitude (an int), and rho = sqrt(r^2 - mu^2).
  requireRange("micro_roughness_x", p.microRoughness.x, 1e-4f, p.roughness.x);
  requireRange("micro_roughness_y", p.microRoughness.y, 1e-4f, p.roughness.y);
  requireRange("search_cone_angle", p.searchConeAngle, 0.0f, 1.0f);
  requireRange("variation", p.variation, 0.0f, 1e6f);
  // R p K stays finite: p K is at most about 1e10 for accepted roughnesses.
  requireRange("dynamic_range", p.dynamicRange, 1e-6f, 1e10f);
  requireRange("log_density", p.logDensity, -100.0f, 100.0f);
  requireRange("max_anisotropy", p.maxAnisotropy, 1.0f, 64.0f);
}

namespace {

// The Beckmann lobe of the model's macro roughness, within the roughness the CPU BSDFs accept.
CookTorranceBsdf zirrKaplanyanProposal(const ZirrKaplanyanParameters& parameters) {
  return CookTorranceBsdf(glm::clamp(parameters.roughness, glm::vec2(kMinRoughnessAlpha), glm::vec2(kMaxRoughnessAlpha)));
}

ZirrKaplanyanParameters validatedMapping(const GlintParameters& parameters) {
  validateGlintParameters(parameters);
  return kernel::glintZirrKaplanyanFromGlint(parameters);
}

}  // namespace

ZirrKaplanyanBsdf::ZirrKaplanyanBsdf(const GlintParameters& parameters, const SurfaceFootprint& footprint,
                                     Fresnel fresnel, Spectrum reflectance)
    : ZirrKaplanyanBsdf(validatedMapping(parameters), footprint, fresnel, reflectance) {
  target_ = microfacetTarget(parameters);
  alpha_ = parameters.alpha;
  compensationFresnel_ = compensationFresnel(target_, alpha_, fresnel);
}

ZirrKaplanyanBsdf::ZirrKaplanyanBsdf(const ZirrKaplanyanParameters& parameters, const SurfaceFootprint& footprint,
                                     Fresnel fresnel, Spectrum reflectance)
    : parameters_(parameters),
      footprint_(footprint),
      fresnel_(fresnel),
      reflectance_(reflectance),
      proposal_(zirrKaplanyanProposal(parameters)) {
  validateZirrKaplanyanParameters(parameters);
  validateFootprint(footprint);
}

Spectrum ZirrKaplanyanBsdf::f(glm::vec3 wo, glm::vec3 wi) const {
  const float value = kernel::glintZirrKaplanyanReflectance(footprint_.uv, footprint_.duvdx, footprint_.duvdy, wo, wi,
                                                       parameters_);
  const Spectrum multiple = compensation(target_, alpha_, compensationFresnel_, Spectrum(1.0f), wo, wi);
  if (value == 0.0f) return multiple;
  return reflectance_ * fresnel_.evaluate(glm::dot(wo, glm::normalize(wo + wi))) * value + multiple;
}

std::optional<BsdfSample> ZirrKaplanyanBsdf::sample(glm::vec3 wo, float uChoice, glm::vec2 u) const {
  std::optional<BsdfSample> drawn = proposal_.sample(wo, uChoice, u);
  if (!drawn) return std::nullopt;
  drawn->f = f(wo, drawn->wi);
  drawn->weight = drawn->f * (std::abs(drawn->wi.z) / drawn->pdf);
  return drawn;
}

float ZirrKaplanyanBsdf::pdf(glm::vec3 wo, glm::vec3 wi) const { return proposal_.pdf(wo, wi); }

}  // namespace glint
