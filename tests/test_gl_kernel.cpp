// CPU versus GLSL: the same kernel source evaluated by the library and by a compute shader on the
// headless context must agree (docs/conventions.md, "One model, five languages").
#include <cmath>

#include <gtest/gtest.h>

#include "gl/context.h"
#include "gl/dictionary_texture.h"
#include "gl/shader.h"
#include "gl_support.h"
#include "kernel_cases.h"
#include "test_support.h"

namespace glint {
namespace {

using namespace glint::test;

using Case = KernelCase;
using Values = KernelValues;

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

// Ten thousand random cases through one of the two programs (2020, or anti-aliased at each case's
// slope derivatives) against the CPU.
void expectCpuAndGlslAgree(const std::vector<Case>& cases, bool filtered) {
  expectCpuAndGpuAgree(cases, filtered, evaluateOnGpu(cases, filtered), "GLSL");
}

TEST(KernelGl, CpuAndGlslAgreeOnTenThousandRandomInputs) { expectCpuAndGlslAgree(randomKernelCases(10000), false); }

// The anti-aliased kernel at random slope derivatives (randomFilteredKernelCases).
TEST(KernelGl, AntiAliasedCpuAndGlslAgreeOnTenThousandRandomInputs) {
  expectCpuAndGlslAgree(randomFilteredKernelCases(10000), true);
}

// The renderer evaluates all of a pixel's lights over one walk of the footprint's cells: each slope
// must get what a walk for it alone gets, in P22 (against the one-slope program of the test above)
// and in the colour-weighted channels (against the same program walking that slope alone). Same
// GPU, same operations in the same order, so the values must be equal; 1e-6 relative only absorbs
// a compiler that schedules them differently.
TEST(KernelGl, SlopeSetMatchesOneSlopeAtATime) {
  constexpr int kSlopes = 3;
  const std::vector<Case> cases = randomKernelCases(3000);
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
