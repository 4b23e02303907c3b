#include "trace/material.h"

#include <algorithm>
#include <cmath>

#include "glint/kernel/normal_map_filtering.h"
#include "glint/kernel/surface.h"
#include "scene/normal_map_moments.h"
#include "trace/sampling.h"

namespace glint::trace {

kernel::GlintCoat SurfaceMaterial::noCoat() {
  kernel::GlintCoat coat;
  coat.weight = 0.0f;
  coat.alpha = 1.0f;
  coat.t = glm::vec3(1.0f, 0.0f, 0.0f);
  coat.b = glm::vec3(0.0f, 1.0f, 0.0f);
  coat.n = glm::vec3(0.0f, 0.0f, 1.0f);
  return coat;
}

SurfaceMaterial::SurfaceMaterial(Spectrum diffuse, Specular specular, Spectrum specularAlbedo, kernel::GlintCoat coat)
    : diffuse_(diffuse), specular_(std::move(specular)), coat_(coat) {
  const float d = luminance(diffuse * kPi);
  const float s = luminance(specularAlbedo);
  // Each lobe keeps at least 10% of the samples when it reflects anything, so that neither is
  // left to rare samples where the estimate (Fresnel at normal view) undersells it.
  specularProbability_ = d <= 0.0f ? 1.0f : (s <= 0.0f ? 0.0f : std::clamp(s / (s + d), 0.1f, 0.9f));
  if (coat_.weight > 0.0f) {
    coatLobe_.emplace(glm::vec2(coat_.alpha), 0.0f, Fresnel::none(), Spectrum(1.0f),
                      MicrofacetTarget{kernel::GLINT_NDF_GGX, kernel::GLINT_MASKING_SMITH, true});
    // The coat reflects all of its weight (its lobe and compensation have albedo 1), the base at
    // most the rest times its lobes' estimates; the same 10% floor.
    const float base = (1.0f - coat_.weight) * (d + s);
    coatProbability_ = base <= 0.0f ? 1.0f : std::clamp(coat_.weight / (coat_.weight + base), 0.1f, 0.9f);
  }
}

Spectrum SurfaceMaterial::specularF(glm::vec3 wo, glm::vec3 wi) const {
  return std::visit([&](const auto& bsdf) { return bsdf.f(wo, wi); }, specular_);
}

float SurfaceMaterial::specularPdf(glm::vec3 wo, glm::vec3 wi) const {
  return std::visit([&](const auto& bsdf) { return bsdf.pdf(wo, wi); }, specular_);
}

Spectrum SurfaceMaterial::baseF(glm::vec3 wo, glm::vec3 wi) const { return diffuse_ + specularF(wo, wi); }

float SurfaceMaterial::basePdf(glm::vec3 wo, glm::vec3 wi) const {
  const float diffusePdf = specularProbability_ < 1.0f ? cosineHemispherePdf(wi.z) : 0.0f;
  const float specularPdfValue = specularProbability_ > 0.0f ? specularPdf(wo, wi) : 0.0f;
  return specularProbability_ * specularPdfValue + (1.0f - specularProbability_) * diffusePdf;
}

// The kernel's coat times its cosine, over this frame's cosine (the integrators multiply by wi.z).
float SurfaceMaterial::coatF(glm::vec3 wo, glm::vec3 wi) const {
  return kernel::glintCoatReflectedCosine(coat_, wo, wi) / wi.z;
}

float SurfaceMaterial::coatPdf(glm::vec3 wo, glm::vec3 wi) const {
  return coatLobe_->pdf(kernel::glintCoatLocal(coat_, wo), kernel::glintCoatLocal(coat_, wi));
}

Spectrum SurfaceMaterial::f(glm::vec3 wo, glm::vec3 wi) const {
  if (!(wi.z > 0.0f) || !(wo.z > 0.0f)) return Spectrum(0.0f);
  if (!coatLobe_) return baseF(wo, wi);
  return baseF(wo, wi) * (1.0f - coat_.weight) + coatF(wo, wi);
}

float SurfaceMaterial::pdf(glm::vec3 wo, glm::vec3 wi) const {
  if (!(wi.z > 0.0f) || !(wo.z > 0.0f)) return 0.0f;
  if (!coatLobe_) return basePdf(wo, wi);
  return (1.0f - coatProbability_) * basePdf(wo, wi) + coatProbability_ * coatPdf(wo, wi);
}

std::optional<MaterialSample> SurfaceMaterial::sampleBase(glm::vec3 wo, float uChoice, glm::vec2 u) const {
  const float ps = specularProbability_;
  MaterialSample s;
  if (uChoice < ps) {
    // The specular lobe's own sampler; its value and pdf come with the sample, so the glint
    // P-NDF is not evaluated again.
    const float uLobe = std::min(uChoice / ps, 0x1.fffffep-1f);
    const auto lobe = std::visit([&](const auto& bsdf) { return bsdf.sample(wo, uLobe, u); }, specular_);
    if (!lobe || lobe->transmission || !(lobe->pdf > 0.0f) || !(lobe->wi.z > 0.0f)) return std::nullopt;
    s.wi = lobe->wi;
    s.f = diffuse_ + lobe->f;
    s.pdf = ps * lobe->pdf + (1.0f - ps) * cosineHemispherePdf(s.wi.z);
  } else {
    s.wi = sampleCosineHemisphere(u);
    if (!(s.wi.z > 0.0f)) return std::nullopt;
    s.f = baseF(wo, s.wi);
    s.pdf = basePdf(wo, s.wi);
  }
  return s;
}

std::optional<MaterialSample> SurfaceMaterial::sample(glm::vec3 wo, float uChoice, glm::vec2 u) const {
  if (!(wo.z > 0.0f)) return std::nullopt;
  std::optional<MaterialSample> s;
  if (!coatLobe_) {
    s = sampleBase(wo, uChoice, u);
  } else if (uChoice < coatProbability_) {
    // The coat's lobe, in its own frame, then the whole material at that direction.
    const float uLobe = std::min(uChoice / coatProbability_, 0x1.fffffep-1f);
    const auto lobe = coatLobe_->sample(kernel::glintCoatLocal(coat_, wo), uLobe, u);
    if (!lobe || !(lobe->pdf > 0.0f)) return std::nullopt;
    const glm::vec3 wi = coat_.t * lobe->wi.x + coat_.b * lobe->wi.y + coat_.n * lobe->wi.z;
    if (!(wi.z > 0.0f)) return std::nullopt;  // below the base's horizon, where f is 0
    s = MaterialSample{f(wo, wi), wi, pdf(wo, wi), Spectrum(0.0f)};
  } else {
    const float uBase = std::min((uChoice - coatProbability_) / (1.0f - coatProbability_), 0x1.fffffep-1f);
    s = sampleBase(wo, uBase, u);
    if (s) {
      s->f = s->f * (1.0f - coat_.weight) + coatF(wo, s->wi);
      s->pdf = (1.0f - coatProbability_) * s->pdf + coatProbability_ * coatPdf(wo, s->wi);
    }
  }
  if (!s || !(s->pdf > 0.0f) || !std::isfinite(s->pdf)) return std::nullopt;
  s->weight = s->f * (s->wi.z / s->pdf);
  return s;
}

SceneMaterials::SceneMaterials(const scene::Scene& scene, const Dictionary& dictionary, SpecularModel model,
                               GlintSampler sampler, bool normalMapFiltering, FootprintPolicy footprintPolicy)
    : scene_(scene), dictionary_(dictionary), model_(model), sampler_(sampler), footprintPolicy_(footprintPolicy) {
  validateFootprintPolicy(footprintPolicy);
  textures_.reserve(scene.textures.size());
  for (const scene::Texture& t : scene.textures) textures_.emplace_back(t);
  normalMapMoments_.resize(scene.materials.size());
  for (std::size_t i = 0; i < scene.materials.size() && normalMapFiltering; ++i) {
    const scene::Material& m = scene.materials[i];
    // Only the glint model filters normal maps, in both renderers.
    if (m.normalTexture < 0 || !m.glint.enabled || model != SpecularModel::Glint) continue;
    scene::NormalMapMoments moments =
        scene::normalMapMoments(scene.textures[static_cast<std::size_t>(m.normalTexture)], m.normalScale);
    normalMapMoments_[i] = NormalMapMoments{MipTexture(moments.width, moments.height, std::move(moments.first)),
                                            MipTexture(moments.width, moments.height, std::move(moments.second))};
  }
}

glm::vec3 SceneMaterials::texture(int index, glm::vec2 uv, const UvDerivatives& footprint) const {
  if (index < 0 || index >= static_cast<int>(textures_.size())) return glm::vec3(1.0f);
  return textures_[static_cast<std::size_t>(index)].sample(uv, footprint.duvdx, footprint.duvdy);
}

namespace {

// A lookup through a glTF KHR_texture_transform: the uv and its footprint, transformed.
struct TransformedLookup {
  glm::vec2 uv;
  UvDerivatives footprint;
};

TransformedLookup transformedLookup(const scene::UvTransform& transform, glm::vec2 uv, const UvDerivatives& footprint) {
  // Without a transform the sine and cosine are skipped: every lookup of every hit comes through here.
  if (transform.identity()) return {uv, footprint};
  const glm::mat2 linear = transform.linear();
  return {linear * uv + transform.offset, UvDerivatives{linear * footprint.duvdx, linear * footprint.duvdy}};
}

}  // namespace

glm::vec3 SceneMaterials::texture(int index, const scene::UvTransform& transform, glm::vec2 uv,
                                  const UvDerivatives& footprint) const {
  if (index < 0) return texture(index, uv, footprint);  // no texture: no transform to compute
  const TransformedLookup lookup = transformedLookup(transform, uv, footprint);
  return texture(index, lookup.uv, lookup.footprint);
}

Spectrum SceneMaterials::emission(const SurfacePoint& point, const UvDerivatives& footprint,
                                  glm::vec3 towardsViewer) const {
  const scene::Material& m = scene_.materials[static_cast<std::size_t>(point.material)];
  if (m.emissive == glm::vec3(0.0f)) return Spectrum(0.0f);
  if (!m.doubleSided && !(glm::dot(point.geometricNormal, towardsViewer) > 0.0f)) return Spectrum(0.0f);
  const Spectrum emitted = m.emissive * texture(m.emissiveTexture, m.emissiveUv, point.uv, footprint);
  if (!m.clearcoat.enabled()) return emitted;
  // Under a coat: the share it lets through (kernel/clearcoat.h).
  const float coat = m.clearcoat.factor * texture(m.clearcoat.texture, m.clearcoat.uv, point.uv, footprint).r;
  return emitted * kernel::glintCoatedEmissionWeight(coat, point.normal, towardsViewer);
}

ShadedPoint SceneMaterials::shade(const SurfacePoint& point, const UvDerivatives& footprint,
                                  glm::vec3 towardsViewer) const {
  const scene::Material& m = scene_.materials[static_cast<std::size_t>(point.material)];
  const scene::GlintLayer& layer = m.glint;
  const glm::vec2 uv = point.uv;

  // The surface's inputs as this renderer looks them up (its mip chains at the ray footprint); the
  // surface is assembled from them by the kernel (kernel/surface.h), as the rasteriser assembles its own.
  kernel::GlintSurfaceSamples samples;
  samples.baseColour = m.baseColour * glm::vec4(texture(m.baseColourTexture, m.baseColourUv, uv, footprint), 1.0f) * point.colour;
  const glm::vec3 metallicRoughness = texture(m.metallicRoughnessTexture, m.metallicRoughnessUv, uv, footprint);
  samples.metallicRoughness = {m.metallic * metallicRoughness.b, m.roughness * metallicRoughness.g};
  samples.emission = emission(point, footprint, towardsViewer);
  samples.occlusion = 1.0f;  // ambient occlusion is the rasteriser's stand-in for what a path tracer traces
  samples.normal = point.normal;
  samples.tangent = point.tangent;
  samples.view = towardsViewer;
  samples.mappedNormal = glm::vec3(0.0f, 0.0f, 1.0f);
  samples.normalMapCovariance = glm::vec3(0.0f);
  const std::optional<NormalMapMoments>& moments = normalMapMoments_[static_cast<std::size_t>(point.material)];
  if (moments) {
    // Normal-map filtering: the slope moments at the footprint, through the normal texture's transform.
    const TransformedLookup at = transformedLookup(m.normalUv, uv, footprint);
    const glm::vec2 dx = at.footprint.duvdx;
    const glm::vec2 dy = at.footprint.duvdy;
    const glm::vec3 first = moments->first.sample(at.uv, dx, dy);
    const glm::vec3 second = moments->second.sample(at.uv, dx, dy);
    samples.mappedNormal = kernel::glintLeanMeanNormal(first);
    samples.normalMapCovariance = kernel::glintLeanSlopeCovariance(first, second, moments->first.levelOfDetail(dx, dy));
  } else if (m.normalTexture >= 0) {
    samples.mappedNormal = texture(m.normalTexture, m.normalUv, uv, footprint) * 2.0f - 1.0f;
    samples.mappedNormal.x *= m.normalScale;
    samples.mappedNormal.y *= m.normalScale;
  }
  samples.glintSamples = {texture(layer.roughnessTexture, uv, footprint).r, texture(layer.logDensityTexture, uv, footprint).r,
                          texture(layer.relativeAreaTexture, uv, footprint).r};
  const kernel::GlintMaterial material = scene::glintMaterial(layer, m.specular);
  const kernel::GlintSurface surface = kernel::glintSurface(samples, material, footprintPolicy_);

  const ShadingFrame frame{surface.t, surface.b, surface.n};
  const Fresnel fresnel = Fresnel::schlick(surface.f0);
  const Spectrum specularAlbedo = fresnel.evaluate(surface.wo.z);
  kernel::GlintCoat coat = SurfaceMaterial::noCoat();
  if (m.clearcoat.enabled()) {
    // The coat's inputs as the rasteriser reads them; its lobe at least as rough as the CPU BSDFs accept.
    const scene::Material::Clearcoat& c = m.clearcoat;
    kernel::GlintCoatSamples coatSamples;
    coatSamples.factorRoughness = {c.factor * texture(c.texture, c.uv, uv, footprint).r,
                                   c.roughness * texture(c.roughnessTexture, c.roughnessUv, uv, footprint).g};
    coatSamples.mappedNormal = glm::vec3(0.0f, 0.0f, 1.0f);
    if (c.normalTexture >= 0) {
      coatSamples.mappedNormal = texture(c.normalTexture, c.normalUv, uv, footprint) * 2.0f - 1.0f;
      coatSamples.mappedNormal.x *= c.normalScale;
      coatSamples.mappedNormal.y *= c.normalScale;
    }
    coat = kernel::glintSurfaceCoat(surface, samples, coatSamples);
    coat.alpha = std::max(coat.alpha, kMinRoughnessAlpha);
  }
  auto shaded = [&](SurfaceMaterial::Specular specular) {
    return ShadedPoint{frame, surface.wo, surface.emission,
                       SurfaceMaterial(surface.diffuse, std::move(specular), specularAlbedo, coat)};
  };
  if (!layer.enabled || model_ == SpecularModel::CookTorrance) {
    // The smooth lobe, at least as rough as the CPU BSDFs accept (a glTF roughness below 0.07).
    return shaded(CookTorranceBsdf(glm::max(surface.smoothAlpha, glm::vec2(kMinRoughnessAlpha)), surface.smoothRho, fresnel,
                                   Spectrum(1.0f), m.specular));
  }
  // The glint footprint: glint uv = mesh uv * uv_scale, and so are its derivatives. Coloured cells
  // (the layer's random colours) are the BSDF's own tint.
  // The layer lies in the base colour texture's uv, its KHR_texture_transform applied, as in the
  // rasteriser.
  const TransformedLookup layerUv = transformedLookup(m.baseColourUv, uv, footprint);
  SurfaceFootprint glintFootprint;
  glintFootprint.uv = kernel::glintMaterialUv(material, layerUv.uv);
  glintFootprint.duvdx = kernel::glintMaterialUv(material, layerUv.footprint.duvdx);
  glintFootprint.duvdy = kernel::glintMaterialUv(material, layerUv.footprint.duvdy);
  if (model_ == SpecularModel::ZirrKaplanyan || model_ == SpecularModel::ZirrKaplanyanReference) {
    // The layer's parameters mapped (docs/zirr-kaplanyan.md); it has no relative area, so its mean
    // is scaled by it to match the glint BRDF's, as the rasteriser scales it.
    return shaded(ZirrKaplanyanBsdf(surface.glint, glintFootprint, fresnel, Spectrum(surface.glint.relativeArea)));
  }
  return shaded(GlintBsdf(dictionary_, surface.glint, glintFootprint, fresnel, Spectrum(1.0f), sampler_));
}

}  // namespace glint::trace
