#include "glint/microfacet_sampling.h"

#include <algorithm>
#include <cmath>

namespace glint::sampling {

float remapUniform(float u, float low, float width) {
  return std::clamp((u - low) / width, 0.0f, kOneMinusEpsilon);
}

glm::vec3 sampleCosineHemisphere(glm::vec2 u) {
  // Shirley & Chiu's concentric map keeps strata compact (pbrt-v3, ConcentricSampleDisk).
  const glm::vec2 offset = 2.0f * u - glm::vec2(1.0f);
  glm::vec2 d(0.0f);
  if (offset.x != 0.0f || offset.y != 0.0f) {
    float r;
    float theta;
    if (std::abs(offset.x) > std::abs(offset.y)) {
      r = offset.x;
      theta = 0.25f * kernel::GLINT_PI * (offset.y / offset.x);
    } else {
      r = offset.y;
      theta = 0.5f * kernel::GLINT_PI - 0.25f * kernel::GLINT_PI * (offset.x / offset.y);
    }
    d = r * glm::vec2(std::cos(theta), std::sin(theta));
  }
  const float z = std::sqrt(std::max(0.0f, 1.0f - d.x * d.x - d.y * d.y));
  return {d.x, d.y, z};
}

glm::vec3 normalFromSlope(glm::vec2 slope) { return glm::normalize(glm::vec3(-slope.x, -slope.y, 1.0f)); }

namespace {

// The slope sigma L z of a whitened pair z = radius (cos, sin), angle 2 pi v: the covariance's
// Cholesky factor, sigma_x (sqrt(1 - rho^2) z.x + rho z.y), sigma_y z.y, sigma = alpha / sqrt(2)
// (exactly the uncorrelated sigma z when rho = 0). Beckmann, GGX and its remainder are all
// elliptical with this scale matrix: only their radius differs.
glm::vec2 ellipticalSlope(glm::vec2 alpha, float rho, float radius, float v) {
  const float phi = 2.0f * kernel::GLINT_PI * v;
  const float c = std::cos(phi);
  const float s = std::sin(phi);
  return alpha * 0.70710678f * radius * glm::vec2(std::sqrt(1.0f - rho * rho) * c + rho * s, s);
}

}  // namespace

glm::vec2 sampleBeckmannSlope(glm::vec2 alpha, float rho, glm::vec2 u) {
  // Box-Muller: radius sqrt(-2 ln(1 - u.x)) of a unit Gaussian pair.
  return ellipticalSlope(alpha, rho, std::sqrt(-2.0f * std::log1p(-std::min(u.x, kOneMinusEpsilon))), u.y);
}

glm::vec2 sampleGgxSlope(glm::vec2 alpha, float rho, glm::vec2 u) {
  // Whitened, the density of t = |z|^2 / 2 is (1 + t)^-2: t = u / (1 - u), radius sqrt(2 t).
  const double x = std::min(u.x, kOneMinusEpsilon);
  return ellipticalSlope(alpha, rho, static_cast<float>(std::sqrt(2.0 * x / (1.0 - x))), u.y);
}

glm::vec2 sampleGgxTailSlope(glm::vec2 alpha, float rho, glm::vec2 u) {
  // Solve S(y) = v for y = 1 + t, S(y) = (1 - e^(-y W)) / (y (1 - e^-W)), decreasing from S(1) = 1;
  // S(y) <= 1 / (y (1 - e^-W)) bounds the root by 1 / (v (1 - e^-W)).
  const double w = kernel::GLINT_GGX_TAIL_PRECISION;
  const double mass = -std::expm1(-w);
  const double v = 1.0 - std::min(u.x, kOneMinusEpsilon);
  double low = 1.0;
  double high = std::max(1.0, 1.0 / (v * mass));
  for (int i = 0; i < 200 && high - low > 1e-12 * high; ++i) {
    const double y = 0.5 * (low + high);
    (-std::expm1(-y * w) / (y * mass) > v ? low : high) = y;
  }
  const double t = 0.5 * (low + high) - 1.0;
  return ellipticalSlope(alpha, rho, static_cast<float>(std::sqrt(2.0 * std::max(t, 0.0))), u.y);
}

glm::vec2 sampleTargetSlope(int ndf, glm::vec2 alpha, float rho, glm::vec2 u) {
  return ndf == kernel::GLINT_NDF_GGX ? sampleGgxSlope(alpha, rho, u) : sampleBeckmannSlope(alpha, rho, u);
}

float sampleDictionaryMarginal(kernel::GlintDictionaryView dict, int level, int distribution, int complement, float u) {
  // The even density, one half each side, inverted monotonically: u in [0, 1/2) covers
  // (-4 sigma_d, 0], u in [1/2, 1) covers [0, 4 sigma_d); v is the CDF of |x| on its half (exact in
  // double).
  const float sign = u < 0.5f ? -1.0f : 1.0f;
  const double v = u < 0.5f ? 1.0 - 2.0 * static_cast<double>(u) : 2.0 * static_cast<double>(u) - 1.0;
  // On [0, 4 sigma_d) the marginal is piecewise linear between texel values a_k at x_k = k h,
  // h = 4 sigma_d / R, with a_R = 0: segment k holds h (a_k + a_{k+1}) / 2 of the mass. A
  // complement block's marginal (kernel glintBlockMarginal) is 2 p_{level+1} - p_level, piecewise
  // linear on the same texels; its few texels below zero (at most 4e-4 of the peak, binary16
  // rounding) are drawn as zero.
  const int texels = dict.texelsPerDistribution;
  auto texel = [&](int k) {
    if (k >= texels) return 0.0;
    const double prefix = kernel::glintDictionaryTexel(dict, level, distribution, k);
    if (complement == 0) return prefix;
    return std::max(0.0, 2.0 * static_cast<double>(kernel::glintDictionaryTexel(dict, level + 1, distribution, k)) - prefix);
  };
  double total = 0.0;
  for (int k = 0; k < texels; ++k) total += 0.5 * (texel(k) + texel(k + 1));
  const double target = v * total;
  double before = 0.0;
  int segment = -1;
  for (int k = 0; k < texels; ++k) {
    const double mass = 0.5 * (texel(k) + texel(k + 1));
    if (mass > 0.0) {
      segment = k;
      if (target < before + mass) break;
      before += mass;
    }
  }
  if (segment < 0) return 0.0f;  // an empty marginal: no dictionary has one (they integrate to 1)
  // Within the segment the density is a + (b - a) t, t in [0, 1): solve the CDF
  // a t + (b - a) t^2 / 2 = r for t, in the form that stays accurate when b - a -> 0.
  const double a = texel(segment);
  const double b = texel(segment + 1);
  const double r = std::max(0.0, target - before);
  const double root = a + std::sqrt(std::max(0.0, a * a + 2.0 * (b - a) * r));
  const double t = root > 0.0 ? std::clamp(2.0 * r / root, 0.0, 1.0) : 0.0;
  const double spacing = static_cast<double>(kernel::glintDictionaryDomain(dict)) / texels;
  return sign * static_cast<float>((segment + t) * spacing);
}

std::optional<glm::vec2> sampleGlintSlope(kernel::GlintDictionaryView dict, const kernel::GlintParameters& params,
                                          glm::vec2 uv, glm::vec2 duvdx, glm::vec2 duvdy, float& uChoice,
                                          glm::vec2 u) {
  const kernel::GlintFootprint footprint = kernel::glintPixelFootprint(duvdx, duvdy, params, dict.numLevels);
  if (footprint.degenerate) return sampleTargetSlope(params.ndf, params.alpha, params.rho, u);
  // P22_P = (1 - w) P22_il + w P22_il+1 (method.md 2.3): level il + 1 with probability w.
  int level = kernel::glintLodLevel(footprint);
  const float blend = kernel::glintLodBlend(footprint);
  if (blend > 0.0f) {
    if (uChoice < blend) {
      uChoice = remapUniform(uChoice, 0.0f, blend);
      level += 1;
    } else {
      uChoice = remapUniform(uChoice, blend, 1.0f - blend);
    }
  }
  // P22_level = sum_c w_c P22_c / sum_c w_c (method.md 2.4): cell c with probability w_c / sum w.
  // Same walk, same weights, same float sum as glintLevelP22, twice: the sum, then the choice.
  const kernel::GlintCellGrid grid =
      kernel::glintCellGrid(footprint, kernel::glintWrapUv(uv, dict.numLevels), dict.numLevels, level);
  float weightSum = 0.0f;
  for (kernel::GlintCellWalk walk = kernel::glintWalkStart(grid); kernel::glintWalkGoing(grid, walk);
       walk = kernel::glintWalkStep(grid, walk)) {
    const float weight = kernel::glintWalkWeight(grid, walk);
    if (weight > 0.0f) weightSum += weight;
  }
  if (!(weightSum > 0.0f)) return std::nullopt;  // glintLevelP22 is 0 there too
  const float target = uChoice * weightSum;
  // The first cell whose running sum passes the target; the last one catches a target that
  // rounding put past the sum.
  float before = 0.0f;
  glm::ivec2 cell(0);
  float cellWeight = 0.0f;
  float cellStart = 0.0f;
  bool found = false;
  for (kernel::GlintCellWalk walk = kernel::glintWalkStart(grid); kernel::glintWalkGoing(grid, walk) && !found;
       walk = kernel::glintWalkStep(grid, walk)) {
    const float weight = kernel::glintWalkWeight(grid, walk);
    if (weight > 0.0f) {
      cell = kernel::glintCellAt(grid, walk.s, walk.t);
      cellWeight = weight;
      cellStart = before;
      found = target < before + weight;
      before += weight;
    }
  }
  uChoice = remapUniform(target, cellStart, cellWeight);

  // The cell's random properties, drawn by the kernel exactly as the P-SDF draws them (a block of
  // its parent's under the consistent LOD construction).
  const kernel::GlintLevelDraw draw = kernel::glintLevelDraw(dict, params, footprint.logDensity, level);
  const kernel::GlintLodDraws draws = kernel::glintLodDraws(dict, params, footprint.logDensity, level, draw);
  const kernel::GlintCell drawn = kernel::glintLodCell(dict, params, draws, cell.x, cell.y, level);
  // Its P22 integrates to its coverage (1 but under the tree construction): no slope beyond it.
  if (drawn.coverage < 1.0f) {
    if (!(uChoice < drawn.coverage)) return std::nullopt;
    uChoice = remapUniform(uChoice, 0.0f, drawn.coverage);
  }
  if (drawn.smoothLimit) return sampleTargetSlope(params.ndf, params.alpha, params.rho, u);
  if (drawn.ggxTail) return sampleGgxTailSlope(params.alpha, params.rho, u);
  if (!drawn.readsDictionary) return std::nullopt;
  const glm::uvec4 hash = drawn.hash;
  const int dictLevel = drawn.dictionaryLevel;
  const glm::ivec2 distributions = drawn.distributions;
  // Tensor product: x' and y' independent, each from its marginal (method.md 2.5).
  const float x = sampleDictionaryMarginal(dict, dictLevel, distributions.x, drawn.complement.x, u.x);
  const float y = sampleDictionaryMarginal(dict, dictLevel, distributions.y, drawn.complement.y, u.y);
  // Back from the dictionary's space: slope = M R(theta) (x', y') / sqrt(w), the inverse of
  // glintDictionarySlope(glintUnscaledSlope(slope) sqrt(w))'s (x', y') = R(-theta) M^-1 slope
  // sqrt(w) (w = 1 but for GGX cells).
  const glm::vec2 rotation = kernel::glintCellRotation(hash);
  const glm::vec2 rotated(rotation.x * x - rotation.y * y, rotation.y * x + rotation.x * y);
  return kernel::glintScaledSlope(dict, params, rotated / drawn.unscale);
}

glm::vec3 sampleVCavityVisibleNormal(glm::vec3 wo, glm::vec3 m, float& u) {
  const glm::vec3 mirror(-m.x, -m.y, m.z);
  const float front = std::max(0.0f, glm::dot(wo, m));
  const float back = std::max(0.0f, glm::dot(wo, mirror));
  const float total = front + back;
  if (!(total > 0.0f)) return m;
  const float target = u * total;
  if (target < back) {
    u = remapUniform(target, 0.0f, back);
    return mirror;
  }
  u = remapUniform(target, back, front);
  return m;
}

float visibleNdf(glm::vec3 wo, glm::vec3 m, float ndf) {
  const float cosine = glm::dot(wo, m);
  if (wo.z <= 0.0f || m.z <= 0.0f || cosine <= 0.0f) return 0.0f;
  return kernel::glintVCavityG1(wo, m) * cosine * ndf / wo.z;
}

float vcavityG1TwoSided(glm::vec3 w, glm::vec3 m) {
  const float cosine = glm::dot(w, m);
  if (cosine * w.z <= 0.0f) return 0.0f;
  return std::min(1.0f, std::abs(2.0f * m.z * w.z / cosine));
}

float fresnelDielectric(float cosThetaI, float eta) {
  cosThetaI = std::clamp(cosThetaI, -1.0f, 1.0f);
  if (cosThetaI < 0.0f) {  // from inside: the relative index is inverted
    eta = 1.0f / eta;
    cosThetaI = -cosThetaI;
  }
  // Snell: sin(theta_t) = sin(theta_i) / eta.
  const float sin2T = (1.0f - cosThetaI * cosThetaI) / (eta * eta);
  if (sin2T >= 1.0f) return 1.0f;
  const float cosThetaT = std::sqrt(std::max(0.0f, 1.0f - sin2T));
  const float parallel = (eta * cosThetaI - cosThetaT) / (eta * cosThetaI + cosThetaT);
  const float perpendicular = (cosThetaI - eta * cosThetaT) / (cosThetaI + eta * cosThetaT);
  return 0.5f * (parallel * parallel + perpendicular * perpendicular);
}

std::optional<glm::vec3> refractDirection(glm::vec3 w, glm::vec3 m, float eta) {
  float cosThetaI = glm::dot(m, w);
  glm::vec3 n = m;
  if (cosThetaI < 0.0f) {  // w inside: refract into the outside through the flipped facet
    eta = 1.0f / eta;
    cosThetaI = -cosThetaI;
    n = -m;
  }
  const float sin2T = std::max(0.0f, 1.0f - cosThetaI * cosThetaI) / (eta * eta);
  if (sin2T >= 1.0f) return std::nullopt;
  const float cosThetaT = std::sqrt(1.0f - sin2T);
  // Heckbert's form (pbrt-v4 Refract): t = -w / eta + (cos_i / eta - cos_t) n.
  return glm::normalize(-w / eta + (cosThetaI / eta - cosThetaT) * n);
}

}  // namespace glint::sampling
