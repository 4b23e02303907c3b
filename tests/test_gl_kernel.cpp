// CPU versus GLSL: the same kernel source evaluated by the library and by a compute shader on the
// headless context must agree (docs/conventions.md, "One model, two languages").
#include <cmath>

#include <gtest/gtest.h>

#include "gl/context.h"
#include "gl/dictionary_texture.h"
#include "gl/shader.h"
#include "gl_support.h"
#include "kernel/multiple_scattering.h"
#include "test_support.h"

namespace glint {
namespace {

using namespace glint::test;

struct KernelInput {
  glm::vec4 uvAndDuvdx, duvdyAndAlpha, woAndLogDensity, wiAndRelativeArea, randomisationEtc, slopeDerivatives, target;
};
struct Case {
  GlintParameters parameters;
  SurfaceFootprint footprint;
  glm::vec3 wo, wi;
  glm::vec4 derivatives{0.0f};  // the half vector slope's screen derivatives, for the filtered program
};
struct Values {
  float f, d, p22, cookTorrance;
};

// Cook-Torrance with the case's target and masking.
float cookTorranceOnCpu(const Case& c) {
  return CookTorranceBsdf(c.parameters.alpha, c.parameters.rho, Fresnel::none(), Spectrum(1.0f),
                          microfacetTarget(c.parameters))
      .f(c.wo, c.wi)
      .x;
}

Values evaluateOnCpu(const Case& c) {
  const GlintBsdf bsdf(defaultDictionary(), c.parameters, c.footprint);
  const glm::vec3 wh = glm::normalize(c.wo + c.wi);
  const float p22 = wh.z > 0.0f ? bsdf.p22(kernel::slopeFromNormal(wh)) : 0.0f;
  return {bsdf.f(c.wo, c.wi).x, wh.z > 0.0f ? kernel::ndfFromP22(p22, wh.z) : 0.0f, p22, cookTorranceOnCpu(c)};
}

std::vector<KernelInput> kernelInputs(const std::vector<Case>& cases) {
  std::vector<KernelInput> inputs;
  for (const Case& c : cases) {
    const GlintParameters& p = c.parameters;
    inputs.push_back({{c.footprint.uv, c.footprint.duvdx},
                      {c.footprint.duvdy, p.alpha},
                      {c.wo, p.logDensity},
                      {c.wi, p.relativeArea},
                      {p.densityRandomisation, p.maxAnisotropy, static_cast<float>(p.patternSeed), p.rho},
                      c.derivatives,
                      {static_cast<float>(p.ndf), static_cast<float>(p.masking), p.multipleScattering ? 1.0f : 0.0f, 0.0f}});
  }
  return inputs;
}

// The anti-aliased P-SDF (glintFilteredP22) at the case's slope derivatives, on the CPU.
Values evaluateFilteredOnCpu(const Case& c) {
  const glm::vec3 wh = glm::normalize(c.wo + c.wi);
  if (wh.z <= 0.0f) return {0.0f, 0.0f, 0.0f, cookTorranceOnCpu(c)};
  const float p22 = kernel::glintFilteredP22(defaultDictionary().view(), c.parameters, c.footprint.uv, c.footprint.duvdx,
                                             c.footprint.duvdy, kernel::slopeFromNormal(wh), c.derivatives);
  const float d = kernel::ndfFromP22(p22, wh.z);
  const float multiple = c.parameters.multipleScattering
                             ? kernel::multipleScatteringReflectance(c.parameters.ndf, c.parameters.masking,
                                                                     c.parameters.alpha, c.wo, c.wi)
                             : 0.0f;
  const float f =
      (c.wo.z > 0.0f && c.wi.z > 0.0f ? kernel::glintMaskedReflectance(c.parameters, c.wo, c.wi, wh, d) : 0.0f) +
      multiple;
  return {f, d, p22, cookTorranceOnCpu(c)};
}

std::vector<Values> evaluateOnGpu(const std::vector<Case>& cases, bool filtered = false) {
  useGlContext();
  gl::ShaderProgram program({{GL_COMPUTE_SHADER, "kernel_eval.comp"}}, {{"GLINT_FILTERED", filtered ? "1" : "0"}});
  gl::DictionaryTexture dictionary(defaultDictionary());
  return dispatchCompute<Values>(program, kernelInputs(cases), [&] { dictionary.bind(program); });
}

// The renderer's walk for several lights (glintP22Set, three slopes, coloured cells): P22 of case
// i's footprint at the half vectors of its wo and the wi of cases i, i + 1, i + 2, from one walk
// and from each slope walked alone in the same program (kernel_eval.comp, SLOPE_SET).
struct SlopeSetValues {
  glm::vec4 together[3];
  glm::vec4 alone[3];
};

std::vector<SlopeSetValues> evaluateSlopeSetOnGpu(const std::vector<Case>& cases) {
  useGlContext();
  gl::ShaderProgram program({{GL_COMPUTE_SHADER, "kernel_eval.comp"}}, {{"GLINT_SLOPE_COUNT", "3"}, {"SLOPE_SET", "1"}});
  gl::DictionaryTexture dictionary(defaultDictionary());
  return dispatchCompute<SlopeSetValues>(program, kernelInputs(cases), [&] { dictionary.bind(program); });
}

// Random inputs over the whole parameter space: anisotropic roughness, densities from sparse to
// smooth, relative areas, footprints from magnified to minified, directions down to grazing, both
// smooth targets, both maskings, with and without multiple scattering (drawn from a stream of their own, so that the other draws are
// those of the Beckmann-only cases before the targets existed).
std::vector<Case> randomCases(int count) {
  Pcg32 rng(4242, 9);
  Pcg32 targets(4242, 10);
  std::vector<Case> cases;
  for (int i = 0; i < count; ++i) {
    Case c;
    c.parameters = defaultGlintParameters();
    c.parameters.alpha = glm::vec2(uniform(rng, 0.05f, 1.0f), uniform(rng, 0.05f, 1.0f));
    c.parameters.logDensity = uniform(rng, 12.0f, 45.0f);
    c.parameters.relativeArea = rng.nextBelow(3) == 0 ? uniform(rng, 0.05f, 1.0f) : 1.0f;
    c.parameters.patternSeed = rng.nextBelow(4);
    c.parameters.rho = rng.nextBelow(3) == 0 ? uniform(rng, -0.99f, 0.99f) : 0.0f;
    c.parameters.ndf = static_cast<int>(targets.nextBelow(2));
    c.parameters.masking = static_cast<int>(targets.nextBelow(2));
    c.parameters.multipleScattering = targets.nextBelow(2) == 0;
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

// A disagreement is explained at a branch boundary (onBranchBoundary): a cell's rounded dictionary
// level, its relative-area mask, the ellipse's edge, the 4 sigma_d support.
// Ten thousand random cases through one of the two programs (2020, or anti-aliased at each case's
// slope derivatives) against the CPU.
void expectCpuAndGlslAgree(const std::vector<Case>& cases, bool filtered) {
  const std::vector<Values> gpu = evaluateOnGpu(cases, filtered);
  const auto onCpu = [filtered](const Case& c) { return filtered ? evaluateFilteredOnCpu(c) : evaluateOnCpu(c); };
  int disagreements = 0;
  int unexplained = 0;
  int nonZero = 0;
  int nonZeroPerTarget[2][2] = {{0, 0}, {0, 0}};  // [ndf][masking]
  double largestRelative = 0.0;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const Values cpu = onCpu(cases[i]);
    nonZero += cpu.f > 1e-3f;
    nonZeroPerTarget[cases[i].parameters.ndf][cases[i].parameters.masking] += cpu.f > 1e-3f;
    if (cpu.f > 1e-3f) largestRelative = std::max(largestRelative, std::abs(double(gpu[i].f) / cpu.f - 1.0));
    EXPECT_TRUE(cpuAndGpuAgree(gpu[i].cookTorrance, cpu.cookTorrance)) << "Cook-Torrance, case " << i;
    if (cpuAndGpuAgree(gpu[i].f, cpu.f) && cpuAndGpuAgree(gpu[i].d, cpu.d) && cpuAndGpuAgree(gpu[i].p22, cpu.p22)) continue;
    ++disagreements;
    if (!onBranchBoundary(cases[i], gpu[i].f, [&](const Case& moved) { return onCpu(moved).f; })) {
      ++unexplained;
      ADD_FAILURE() << "case " << i << ": GPU f " << gpu[i].f << " D " << gpu[i].d << ", CPU f " << cpu.f << " D "
                    << cpu.d << " (not at a branch boundary)";
    }
  }
  EXPECT_GT(nonZero, 5000);  // most cases see the lobe: the agreement is not between zeros
  for (const auto& ndf : nonZeroPerTarget) {
    for (int count : ndf) EXPECT_GT(count, 1000);  // and every target with every masking
  }
  EXPECT_LE(disagreements, 10) << "99.9% of 10000 must agree within 1e-3 relative";
  EXPECT_EQ(unexplained, 0);
  ::testing::Test::RecordProperty("disagreements", disagreements);
  std::printf("CPU vs GLSL%s: %d of %zu disagree beyond 1e-3 relative (+1e-5 absolute); largest relative "
              "difference where f > 1e-3: %.2e\n", filtered ? " (anti-aliased)" : "", disagreements, cases.size(),
              largestRelative);
}

TEST(KernelGl, CpuAndGlslAgreeOnTenThousandRandomInputs) { expectCpuAndGlslAgree(randomCases(10000), false); }

// The anti-aliased kernel: slope correlation in a third of the cases (randomCases), and slope
// derivatives from none to a few times the lobe's width, so that every mip level is read.
TEST(KernelGl, AntiAliasedCpuAndGlslAgreeOnTenThousandRandomInputs) {
  std::vector<Case> cases = randomCases(10000);
  Pcg32 rng(4343, 10);
  for (Case& c : cases) {
    const float scale = rng.nextBelow(8) == 0 ? 0.0f : std::pow(10.0f, uniform(rng, -4.0f, 0.5f));
    c.derivatives = glm::vec4(uniform(rng, -1.0f, 1.0f), uniform(rng, -1.0f, 1.0f), uniform(rng, -1.0f, 1.0f),
                              uniform(rng, -1.0f, 1.0f)) * scale;
  }
  expectCpuAndGlslAgree(cases, true);
}

// The renderer evaluates all of a pixel's lights over one walk of the footprint's cells: each slope
// must get what a walk for it alone gets, in P22 (against the one-slope program of the test above)
// and in the colour-weighted channels (against the same program walking that slope alone). Same
// GPU, same operations in the same order, so the values must be equal; 1e-6 relative only absorbs
// a compiler that schedules them differently.
TEST(KernelGl, SlopeSetMatchesOneSlopeAtATime) {
  constexpr int kSlopes = 3;
  const std::vector<Case> cases = randomCases(3000);
  const std::size_t n = cases.size();
  std::vector<Case> alone;  // case i with the wi of case i + k, for k = 0, 1, 2
  for (int k = 0; k < kSlopes; ++k) {
    for (std::size_t i = 0; i < n; ++i) {
      Case c = cases[i];
      c.wi = cases[(i + static_cast<std::size_t>(k)) % n].wi;
      alone.push_back(c);
    }
  }
  const std::vector<Values> single = evaluateOnGpu(alone);
  const std::vector<SlopeSetValues> set = evaluateSlopeSetOnGpu(cases);
  auto agree = [](float got, float expected) { return std::abs(got - expected) <= 1e-6f * std::abs(expected); };
  int equal = 0;
  int nonZero = 0;
  int tinted = 0;
  for (std::size_t i = 0; i < n; ++i) {
    for (int k = 0; k < kSlopes; ++k) {
      const float expected = single[static_cast<std::size_t>(k) * n + i].p22;
      const glm::vec4 together = set[i].together[k];
      const glm::vec4 walkedAlone = set[i].alone[k];
      nonZero += expected > 1e-3f;
      tinted += together.x != together.w || together.y != together.w;
      equal += together.w == expected && together == walkedAlone;
      EXPECT_TRUE(agree(together.w, expected)) << "case " << i << ", slope " << k << ": " << together.w << " vs " << expected;
      for (int c = 0; c < 4; ++c) {
        EXPECT_TRUE(agree(together[c], walkedAlone[c])) << "case " << i << ", slope " << k << ", channel " << c;
      }
    }
  }
  EXPECT_GT(nonZero, 1000);  // the slopes see lobes: the agreement is not between zeros
  EXPECT_GT(tinted, 1000);   // and the cells' colours: the colour sums are compared too
  std::printf("slope set: %d of %zu (P22, colour) values bit-equal to one slope at a time\n", equal, kSlopes * n);
}

TEST(KernelGl, ContextIsOpenGl45) {
  useGlContext();
  const gl::ContextInfo info = gl::currentContextInfo();
  EXPECT_NE(info.version.find("4.5"), std::string::npos) << info.version;
}

}  // namespace
}  // namespace glint
