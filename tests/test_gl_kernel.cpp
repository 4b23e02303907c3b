// CPU versus GLSL: the same kernel source evaluated by the library and by a compute shader on the
// headless context must agree (docs/conventions.md, "One model, five languages").
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstddef>
#include <cstring>
#include <map>
#include <string>

#include <gtest/gtest.h>

#include "gl/context.h"
#include "gl/dictionary_texture.h"
#include "gl/renderer.h"
#include "gl/shader.h"
#include "gl_support.h"
#include "glint/kernel/glint_material.h"
#include "glint/pcg.h"
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

// ---- The glint material (kernel/glint_material.h) ----------------------------------------------

// A case of shaders/glint_material_eval.comp and what it writes: GlintParameters and the glint uv,
// as the bits of each value.
struct MaterialCase {
  glm::vec4 samples;          // roughness, log-density, relative-area samples; unused
  glm::vec4 footprintPolicy;  // aniso, cells, drop; unused
  glm::vec4 uv;               // a mesh uv; unused
};
struct MaterialOutput {
  glm::uvec4 words[5];
};

std::uint32_t bitsOf(float value) {
  std::uint32_t bits = 0;
  std::memcpy(&bits, &value, sizeof bits);
  return bits;
}

// The CPU's answer in the compute shader's layout.
MaterialOutput materialOutputOnCpu(const kernel::GlintMaterial& material, const MaterialCase& c) {
  const FootprintPolicy policy{c.footprintPolicy.x, c.footprintPolicy.y, c.footprintPolicy.z};
  const GlintParameters p = kernel::glintMaterialParameters(material, c.samples.x, c.samples.y, c.samples.z, policy);
  const glm::vec2 glintUv = kernel::glintMaterialUv(material, glm::vec2(c.uv));
  MaterialOutput out;
  out.words[0] = {bitsOf(p.alpha.x), bitsOf(p.alpha.y), bitsOf(p.rho), bitsOf(p.logDensity)};
  out.words[1] = {bitsOf(p.relativeArea), bitsOf(p.densityRandomisation), bitsOf(p.maxAnisotropy), p.patternSeed};
  out.words[2] = {p.colouredCells ? 1u : 0u, static_cast<std::uint32_t>(p.ndf), static_cast<std::uint32_t>(p.masking),
                  p.multipleScattering ? 1u : 0u};
  out.words[3] = {bitsOf(p.footprintPolicy.maxAnisotropy), bitsOf(p.footprintPolicy.maxCells),
                  bitsOf(p.footprintPolicy.minBlend), static_cast<std::uint32_t>(p.lod)};
  out.words[4] = {bitsOf(glintUv.x), bitsOf(glintUv.y), 0u, 0u};
  return out;
}

gl::ShaderProgram glintMaterialProgram() {
  useGlContext();
  return gl::ShaderProgram({{GL_COMPUTE_SHADER, "glint_material_eval.comp"}});
}

// The renderer's mapping from a material and its textures' samples to the kernel's parameters,
// on the CPU (the path tracer's) and in GLSL (the rasteriser's and the page's): 200 random
// materials, each uploaded into a uniform buffer of all of them at the OpenGL's offset alignment
// and bound by range as the renderer binds them, at 64 random samples, uvs and footprint policies
// each. Same source, correctly rounded operations (products, clamps, copies): every value
// bit-equal, but for the log density a log-density texture maps through mix(), which glm computes
// as x (1 - t) + y t and Mesa lowers to its own sequence: the two round differently, so it is
// held to 1e-6 of the range's larger end, a few of its ulps (measured on llvmpipe: 24% of them
// differ, by at most 43 ulps of a result near the range's smaller end).
TEST(KernelGl, GlintMaterialParametersAgreeWithTheCpu) {
  const gl::ShaderProgram program = glintMaterialProgram();
  constexpr int kMaterials = 200;
  constexpr int kCases = 64;
  Pcg32 rng(20261130, 7);
  std::vector<kernel::GlintMaterial> materials;
  for (int i = 0; i < kMaterials; ++i) materials.push_back(randomGlintMaterial(rng));
  GLint alignment = 1;
  glGetIntegerv(GL_UNIFORM_BUFFER_OFFSET_ALIGNMENT, &alignment);
  const std::size_t stride = (sizeof(kernel::GlintMaterial) + alignment - 1) / alignment * alignment;
  std::vector<std::uint8_t> bytes(stride * materials.size(), 0);
  for (std::size_t i = 0; i < materials.size(); ++i) {
    std::memcpy(bytes.data() + i * stride, &materials[i], sizeof(kernel::GlintMaterial));
  }
  GLuint buffer = 0;
  glCreateBuffers(1, &buffer);
  glNamedBufferStorage(buffer, static_cast<GLsizeiptr>(bytes.size()), bytes.data(), 0);
  int compared = 0;
  int mixed = 0;  // log densities from a log-density texture
  int mixedBitEqual = 0;
  std::int64_t maxUlps = 0;  // between those that differ (both non-negative: bits order as values)
  int alphaClamped = 0;
  int areaClamped = 0;
  for (std::size_t i = 0; i < materials.size(); ++i) {
    std::vector<MaterialCase> cases;
    for (int k = 0; k < kCases; ++k) {
      const FootprintPolicy policy = randomFootprintPolicy(rng);
      cases.push_back({glm::vec4(randomSample(rng), randomSample(rng), randomSample(rng), 0.0f),
                       glm::vec4(policy.maxAnisotropy, policy.maxCells, policy.minBlend, 0.0f),
                       glm::vec4(uniformIn(rng, -4.0f, 4.0f), uniformIn(rng, -4.0f, 4.0f), 0.0f, 0.0f)});
    }
    const std::vector<MaterialOutput> gpu = dispatchCompute<MaterialOutput>(program, cases, [&] {
      glBindBufferRange(GL_UNIFORM_BUFFER, gl::kGlintMaterialBinding, buffer, static_cast<GLintptr>(i * stride),
                        sizeof(kernel::GlintMaterial));
    });
    for (int k = 0; k < kCases; ++k) {
      const MaterialCase& c = cases[static_cast<std::size_t>(k)];
      const MaterialOutput cpu = materialOutputOnCpu(materials[i], c);
      MaterialOutput got = gpu[static_cast<std::size_t>(k)];
      if (materials[i].hasLogDensityTexture != 0u) {
        float gpuLogDensity = 0.0f;
        float cpuLogDensity = 0.0f;
        std::memcpy(&gpuLogDensity, &got.words[0].w, sizeof(float));
        std::memcpy(&cpuLogDensity, &cpu.words[0].w, sizeof(float));
        const glm::vec2 range = materials[i].logDensityRange;
        EXPECT_NEAR(gpuLogDensity, cpuLogDensity, 1e-6f * std::max(std::abs(range.x), std::abs(range.y)))
            << "material " << i << ", case " << k << ": the log density of sample " << c.samples.y;
        mixedBitEqual += got.words[0].w == cpu.words[0].w;
        const std::int64_t ulps = static_cast<std::int64_t>(got.words[0].w) - static_cast<std::int64_t>(cpu.words[0].w);
        maxUlps = std::max(maxUlps, ulps < 0 ? -ulps : ulps);
        ++mixed;
        got.words[0].w = cpu.words[0].w;  // compared above
      }
      for (int w = 0; w < 5; ++w) {
        EXPECT_EQ(got.words[w], cpu.words[w]) << "material " << i << ", case " << k << ", word " << w << " (samples "
                                              << c.samples.x << ", " << c.samples.y << ", " << c.samples.z << ")";
      }
      alphaClamped += materials[i].alpha.x * c.samples.x < 0.01f;
      areaClamped += materials[i].relativeArea * c.samples.z < 1e-4f;
      ++compared;
    }
  }
  glDeleteBuffers(1, &buffer);
  EXPECT_EQ(compared, kMaterials * kCases);
  EXPECT_GT(alphaClamped, 100);  // the clamps are exercised, not only the products
  EXPECT_GT(areaClamped, 100);
  EXPECT_GT(mixed, 1000);
  std::printf("glint material: %d cases; of the %d log densities mapped from a texture, %d bit-equal, the others "
              "at most %lld ulps apart\n",
              compared, mixed, mixedBitEqual, static_cast<long long>(maxUlps));
}

// The std140 layout the GLSL compiler gives the renderer's material block
// (shaders/glint_material_block.glsl) is the C++ struct's: every member at its C++ offset, the
// block the struct's size, at the renderer's binding.
TEST(KernelGl, GlintMaterialBlockLayoutIsTheCppLayout) {
  const gl::ShaderProgram program = glintMaterialProgram();
  using M = kernel::GlintMaterial;
  const std::map<std::string, GLint> cpp = {
      {"alpha", offsetof(M, alpha)},
      {"rho", offsetof(M, rho)},
      {"logDensity", offsetof(M, logDensity)},
      {"relativeArea", offsetof(M, relativeArea)},
      {"densityRandomisation", offsetof(M, densityRandomisation)},
      {"maxAnisotropy", offsetof(M, maxAnisotropy)},
      {"patternSeed", offsetof(M, patternSeed)},
      {"logDensityRange", offsetof(M, logDensityRange)},
      {"uvScale", offsetof(M, uvScale)},
      {"hasLogDensityTexture", offsetof(M, hasLogDensityTexture)},
      {"ndf", offsetof(M, ndf)},
      {"masking", offsetof(M, masking)},
      {"colouredCells", offsetof(M, colouredCells)},
      {"multipleScattering", offsetof(M, multipleScattering)},
      {"enabled", offsetof(M, enabled)},
      {"lod", offsetof(M, lod)},
      {"padding1", offsetof(M, padding1)},
      {"padding2", offsetof(M, padding2)}};
  const GLuint block = glGetProgramResourceIndex(program.id(), GL_UNIFORM_BLOCK, "GlintMaterialBlock");
  ASSERT_NE(block, GL_INVALID_INDEX);
  const GLenum blockProperties[] = {GL_BUFFER_DATA_SIZE, GL_BUFFER_BINDING, GL_NUM_ACTIVE_VARIABLES};
  GLint blockValues[3] = {};
  glGetProgramResourceiv(program.id(), GL_UNIFORM_BLOCK, block, 3, blockProperties, 3, nullptr, blockValues);
  EXPECT_EQ(blockValues[0], static_cast<GLint>(sizeof(M)));
  EXPECT_EQ(blockValues[1], static_cast<GLint>(gl::kGlintMaterialBinding));
  std::vector<GLint> members(static_cast<std::size_t>(blockValues[2]));
  const GLenum activeVariables = GL_ACTIVE_VARIABLES;
  glGetProgramResourceiv(program.id(), GL_UNIFORM_BLOCK, block, 1, &activeVariables,
                         static_cast<GLsizei>(members.size()), nullptr, members.data());
  std::map<std::string, GLint> glsl;
  for (GLint member : members) {
    char name[128] = {};
    glGetProgramResourceName(program.id(), GL_UNIFORM, static_cast<GLuint>(member), sizeof name, nullptr, name);
    const GLenum offsetProperty = GL_OFFSET;
    GLint offset = -1;
    glGetProgramResourceiv(program.id(), GL_UNIFORM, static_cast<GLuint>(member), 1, &offsetProperty, 1, nullptr,
                           &offset);
    const std::string prefix = "uGlintMaterial.";
    const std::string full = name;
    EXPECT_EQ(full.rfind(prefix, 0), 0u) << full;
    glsl[full.substr(prefix.size())] = offset;
  }
  EXPECT_EQ(glsl, cpp);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}

TEST(KernelGl, ContextIsOpenGl45) {
  useGlContext();
  const gl::ContextInfo info = gl::currentContextInfo();
  EXPECT_NE(info.version.find("4.5"), std::string::npos) << info.version;
}

}  // namespace
}  // namespace glint
