#include "kernel_cases.h"

#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "glint/kernel/multiple_scattering.h"

namespace glint::test {

namespace {

// Cook-Torrance with the case's target and masking.
float cookTorranceOnCpu(const KernelCase& c) {
  return CookTorranceBsdf(c.parameters.alpha, c.parameters.rho, Fresnel::none(), Spectrum(1.0f),
                          microfacetTarget(c.parameters))
      .f(c.wo, c.wi)
      .x;
}

}  // namespace

FootprintPolicy randomFootprintPolicy(Pcg32& rng) {
  FootprintPolicy policy = exactFootprintPolicy();
  switch (rng.nextBelow(6)) {
    case 0:
      policy.maxAnisotropy = uniform(rng, 1.0f, 8.0f);
      break;
    case 1:
      policy.maxCells = static_cast<float>(12 + rng.nextBelow(60));
      break;
    case 2:
      policy.minBlend = uniform(rng, 0.0f, 1.0f);
      break;
    case 3:
      policy.maxAnisotropy = uniform(rng, 1.0f, 8.0f);
      policy.maxCells = static_cast<float>(12 + rng.nextBelow(60));
      policy.minBlend = uniform(rng, 0.0f, 1.0f);
      break;
    default:  // the paper's footprint in a third of the cases
      break;
  }
  return policy;
}

KernelValues evaluateOnCpu(const KernelCase& c) {
  const GlintBsdf bsdf(defaultDictionary(), c.parameters, c.footprint);
  const glm::vec3 wh = glm::normalize(c.wo + c.wi);
  const float p22 = wh.z > 0.0f ? bsdf.p22(kernel::glintSlopeFromNormal(wh)) : 0.0f;
  return {bsdf.f(c.wo, c.wi).x, wh.z > 0.0f ? kernel::glintNdfFromP22(p22, wh.z) : 0.0f, p22, cookTorranceOnCpu(c)};
}

std::vector<KernelInput> kernelInputs(const std::vector<KernelCase>& cases) {
  std::vector<KernelInput> inputs;
  for (const KernelCase& c : cases) {
    const GlintParameters& p = c.parameters;
    inputs.push_back({{c.footprint.uv, c.footprint.duvdx},
                      {c.footprint.duvdy, p.alpha},
                      {c.wo, p.logDensity},
                      {c.wi, p.relativeArea},
                      {p.densityRandomisation, p.maxAnisotropy, static_cast<float>(p.patternSeed), p.rho},
                      c.derivatives,
                      {static_cast<float>(p.ndf), static_cast<float>(p.masking), p.multipleScattering ? 1.0f : 0.0f, 0.0f},
                      {p.footprintPolicy.maxAnisotropy, p.footprintPolicy.maxCells, p.footprintPolicy.minBlend,
                       static_cast<float>(p.lod)}});
  }
  return inputs;
}

// The anti-aliased P-SDF (glintFilteredP22) at the case's slope derivatives, on the CPU.
KernelValues evaluateFilteredOnCpu(const KernelCase& c) {
  const glm::vec3 wh = glm::normalize(c.wo + c.wi);
  if (wh.z <= 0.0f) return {0.0f, 0.0f, 0.0f, cookTorranceOnCpu(c)};
  const float p22 = kernel::glintFilteredP22(defaultDictionary().view(), c.parameters, c.footprint.uv, c.footprint.duvdx,
                                             c.footprint.duvdy, kernel::glintSlopeFromNormal(wh), c.derivatives);
  const float d = kernel::glintNdfFromP22(p22, wh.z);
  const float multiple = c.parameters.multipleScattering
                             ? kernel::glintMultipleScatteringReflectance(c.parameters.ndf, c.parameters.masking,
                                                                     c.parameters.alpha, c.wo, c.wi)
                             : 0.0f;
  const float f =
      (c.wo.z > 0.0f && c.wi.z > 0.0f ? kernel::glintMaskedReflectance(c.parameters, c.wo, c.wi, wh, d) : 0.0f) +
      multiple;
  return {f, d, p22, cookTorranceOnCpu(c)};
}

std::vector<KernelCase> randomKernelCases(int count) {
  Pcg32 rng(4242, 9);
  // The targets from a stream of their own, so that the other draws are those of the cases before
  // the targets existed.
  Pcg32 targets(4242, 10);
  Pcg32 policies(4242, 11);  // the footprint policies, a stream of their own for the same reason
  Pcg32 lods(4242, 12);      // the LOD constructions, likewise: a third of the cases each
  std::vector<KernelCase> cases;
  for (int i = 0; i < count; ++i) {
    KernelCase c;
    c.parameters = defaultGlintParameters();
    c.parameters.alpha = glm::vec2(uniform(rng, 0.05f, 1.0f), uniform(rng, 0.05f, 1.0f));
    c.parameters.logDensity = uniform(rng, 12.0f, 45.0f);
    c.parameters.relativeArea = rng.nextBelow(3) == 0 ? uniform(rng, 0.05f, 1.0f) : 1.0f;
    c.parameters.patternSeed = rng.nextBelow(4);
    c.parameters.rho = rng.nextBelow(3) == 0 ? uniform(rng, -0.99f, 0.99f) : 0.0f;
    c.parameters.ndf = static_cast<int>(targets.nextBelow(2));
    c.parameters.masking = static_cast<int>(targets.nextBelow(2));
    c.parameters.multipleScattering = targets.nextBelow(2) == 0;
    c.parameters.footprintPolicy = randomFootprintPolicy(policies);
    c.parameters.lod = static_cast<int>(lods.nextBelow(3));
    c.footprint = randomFootprint(rng, 1e-5f, 3e-2f);
    c.footprint.uv = c.footprint.uv * 3.0f - 1.0f;  // negative and beyond one period too
    c.wo = directionAt(uniform(rng, 0.0f, 1.55f), uniform(rng, 0.0f, 6.2832f));
    // Half vectors within the lobe (where glints are), the rest anywhere, grazing included.
    if (rng.nextBelow(4) != 0) {
      const glm::vec2 slope = glm::vec2(uniform(rng, -1.5f, 1.5f), uniform(rng, -1.5f, 1.5f)) * c.parameters.alpha;
      const glm::vec3 m = glm::normalize(glm::vec3(-slope, 1.0f));
      c.wi = glm::reflect(-c.wo, m);
    } else {
      c.wi = directionAt(uniform(rng, 0.0f, 1.55f), uniform(rng, 0.0f, 6.2832f));
    }
    cases.push_back(c);
  }
  return cases;
}

std::vector<KernelCase> randomFilteredKernelCases(int count) {
  std::vector<KernelCase> cases = randomKernelCases(count);
  Pcg32 rng(4343, 10);
  for (KernelCase& c : cases) {
    const float scale = rng.nextBelow(8) == 0 ? 0.0f : std::pow(10.0f, uniform(rng, -4.0f, 0.5f));
    c.derivatives = glm::vec4(uniform(rng, -1.0f, 1.0f), uniform(rng, -1.0f, 1.0f), uniform(rng, -1.0f, 1.0f),
                              uniform(rng, -1.0f, 1.0f)) * scale;
  }
  return cases;
}

// A disagreement is explained at a branch boundary (onBranchBoundary): a cell's rounded dictionary
// level, its relative-area mask, the ellipse's edge, the 4 sigma_d support.
void expectCpuAndGpuAgree(const std::vector<KernelCase>& cases, bool filtered, const std::vector<KernelValues>& gpu,
                          const char* gpuName) {
  ASSERT_EQ(gpu.size(), cases.size());
  const auto onCpu = [filtered](const KernelCase& c) { return filtered ? evaluateFilteredOnCpu(c) : evaluateOnCpu(c); };
  int disagreements = 0;
  int unexplained = 0;
  int nonZero = 0;
  int nonZeroPerTarget[2][2] = {{0, 0}, {0, 0}};  // [ndf][masking]
  double largestRelative = 0.0;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const KernelValues cpu = onCpu(cases[i]);
    nonZero += cpu.f > 1e-3f;
    nonZeroPerTarget[cases[i].parameters.ndf][cases[i].parameters.masking] += cpu.f > 1e-3f;
    if (cpu.f > 1e-3f) largestRelative = std::max(largestRelative, std::abs(double(gpu[i].f) / cpu.f - 1.0));
    EXPECT_TRUE(cpuAndGpuAgree(gpu[i].cookTorrance, cpu.cookTorrance)) << "Cook-Torrance, case " << i;
    if (cpuAndGpuAgree(gpu[i].f, cpu.f) && cpuAndGpuAgree(gpu[i].d, cpu.d) && cpuAndGpuAgree(gpu[i].p22, cpu.p22)) continue;
    ++disagreements;
    if (!onBranchBoundary(cases[i], gpu[i].f, [&](const KernelCase& moved) { return onCpu(moved).f; })) {
      ++unexplained;
      ADD_FAILURE() << "case " << i << ": GPU f " << gpu[i].f << " D " << gpu[i].d << ", CPU f " << cpu.f << " D "
                    << cpu.d << " (not at a branch boundary)";
    }
  }
  const int count = static_cast<int>(cases.size());
  EXPECT_GT(nonZero, count / 2);  // most cases see the lobe: the agreement is not between zeros
  for (const auto& ndf : nonZeroPerTarget) {
    for (int seen : ndf) EXPECT_GT(seen, count / 10);  // and every target with every masking
  }
  EXPECT_LE(disagreements, count / 1000) << "99.9% of " << count << " must agree within 1e-3 relative";
  EXPECT_EQ(unexplained, 0);
  ::testing::Test::RecordProperty("disagreements", disagreements);
  std::printf("CPU vs %s%s: %d of %zu disagree beyond 1e-3 relative (+1e-5 absolute); largest relative "
              "difference where f > 1e-3: %.2e\n", gpuName, filtered ? " (anti-aliased)" : "", disagreements, cases.size(),
              largestRelative);
}

float uniformIn(Pcg32& rng, float low, float high) {
  return low + (high - low) * static_cast<float>(rng.nextOpenUnit());
}

// A random material over the accepted ranges (docs/conventions.md), with alphas and relative areas
// that the textures' samples push past the clamps, and every flag either way.
kernel::GlintMaterial randomGlintMaterial(Pcg32& rng) {
  kernel::GlintMaterial m{};
  m.alpha = {uniformIn(rng, 0.005f, 2.0f), uniformIn(rng, 0.005f, 2.0f)};
  m.rho = uniformIn(rng, -0.99f, 0.99f);
  m.logDensity = uniformIn(rng, 0.0f, 100.0f);
  m.relativeArea = uniformIn(rng, 1e-5f, 1.0f);
  m.densityRandomisation = uniformIn(rng, 0.0f, 10.0f);
  m.maxAnisotropy = uniformIn(rng, 1.0f, 64.0f);
  m.patternSeed = rng.next();
  m.logDensityRange = {uniformIn(rng, 0.0f, 100.0f), uniformIn(rng, 0.0f, 100.0f)};
  m.uvScale = std::exp2(uniformIn(rng, -8.0f, 8.0f));
  m.hasLogDensityTexture = rng.nextBelow(2);
  m.ndf = static_cast<int>(rng.nextBelow(2));
  m.masking = static_cast<int>(rng.nextBelow(2));
  m.colouredCells = rng.nextBelow(2);
  m.multipleScattering = rng.nextBelow(2);
  m.enabled = rng.nextBelow(2);
  m.lod = static_cast<int>(rng.nextBelow(2));
  return m;
}

// A texture sample: 8-bit values (glTF textures) in half the draws, exactly 0 or 1 in some, any
// value in [0, 1] otherwise.
float randomSample(Pcg32& rng) {
  switch (rng.nextBelow(4)) {
    case 0: return static_cast<float>(rng.nextBelow(256)) / 255.0f;
    case 1: return static_cast<float>(rng.nextBelow(2));
    default: return static_cast<float>(rng.nextOpenUnit());
  }
}

}  // namespace glint::test
