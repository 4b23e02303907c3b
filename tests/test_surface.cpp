// The surface both renderers shade (kernel/surface.h), assembled on the CPU (the path tracer's) and
// in GLSL (the rasteriser's and the page's) from the same random samples, and its rules checked on
// the CPU: the frame, the glTF metal-roughness lobes, the glint layer's textures and normal-map
// widening.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "gl/renderer.h"
#include "gl/shader.h"
#include "gl_support.h"
#include "glint/kernel/clearcoat.h"
#include "glint/kernel/surface.h"
#include "glint/pcg.h"
#include "kernel_cases.h"
#include "test_support.h"

namespace glint {
namespace {

using namespace glint::test;

// coat: clearcoat factor and roughness samples; coatNormal: its normal map's normal; light: a direction
// in the surface's frame for the coat's lobe.
struct SurfaceCase {
  glm::vec4 baseColour, metallicRoughnessOcclusion, emission, normal, tangent, mappedNormal, view, glintSamples,
      normalMapCovariance, footprintPolicy, coat, coatNormal, light;
};
// coatN: the coat's normal and weight; coatT: its tangent and alpha; coatLight: its reflected share
// times its cosine at the case's light, and the emission's share through it. The last is compared
// relative to itself (the coat's lobe is as sharp as alpha^2 makes it).
struct SurfaceOutput {
  glm::vec4 t, b, n, wo, baseColour, metallicRoughnessOcclusionLayer, diffuse, f0, emission, smoothLobe, glint, glintMore,
      coatN, coatT, coatLight;
};
constexpr int kOutputVectors = sizeof(SurfaceOutput) / sizeof(glm::vec4);

kernel::GlintSurfaceSamples samplesOf(const SurfaceCase& c) {
  kernel::GlintSurfaceSamples s;
  s.baseColour = c.baseColour;
  s.metallicRoughness = glm::vec2(c.metallicRoughnessOcclusion);
  s.occlusion = c.metallicRoughnessOcclusion.z;
  s.emission = glm::vec3(c.emission);
  s.normal = glm::vec3(c.normal);
  s.tangent = c.tangent;
  s.mappedNormal = glm::vec3(c.mappedNormal);
  s.view = glm::vec3(c.view);
  s.glintSamples = glm::vec3(c.glintSamples);
  s.normalMapCovariance = glm::vec3(c.normalMapCovariance);
  return s;
}

FootprintPolicy policyOf(const SurfaceCase& c) {
  return FootprintPolicy{c.footprintPolicy.x, c.footprintPolicy.y, c.footprintPolicy.z};
}

SurfaceOutput surfaceOnCpu(const SurfaceCase& c, const kernel::GlintMaterial& material) {
  const kernel::GlintSurfaceSamples samples = samplesOf(c);
  const kernel::GlintSurface s = kernel::glintSurface(samples, material, policyOf(c));
  const kernel::GlintCoat coat = kernel::glintSurfaceCoat(s, samples, {glm::vec2(c.coat), glm::vec3(c.coatNormal)});
  return {glm::vec4(s.t, 0.0f),
          glm::vec4(s.b, 0.0f),
          glm::vec4(s.n, 0.0f),
          glm::vec4(s.wo, 0.0f),
          s.baseColour,
          glm::vec4(s.metallic, s.roughness, s.occlusion, static_cast<float>(s.hasGlintLayer)),
          glm::vec4(s.diffuse, 0.0f),
          glm::vec4(s.f0, 0.0f),
          glm::vec4(s.emission, 0.0f),
          glm::vec4(s.smoothAlpha, s.smoothRho, 0.0f),
          glm::vec4(s.glint.alpha, s.glint.rho, s.glint.logDensity),
          glm::vec4(s.glint.relativeArea, s.glint.densityRandomisation, s.glint.maxAnisotropy, 0.0f),
          glm::vec4(coat.n, coat.weight),
          glm::vec4(coat.t, coat.alpha),
          glm::vec4(kernel::glintCoatReflectedCosine(coat, s.wo, glm::vec3(c.light)),
                    kernel::glintCoatedEmissionWeight(c.coat.x, samples.normal, samples.view), 0.0f, 0.0f)};
}

glm::vec3 randomDirection(Pcg32& rng) {
  const float z = uniformIn(rng, -1.0f, 1.0f);
  const float phi = uniformIn(rng, 0.0f, 6.2831853f);
  const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
  return {r * std::cos(phi), r * std::sin(phi), z};
}

// A random shading point: interpolated normals of any length, tangents at any angle to them (along
// them in 2% of the cases: degenerate mesh data), normal-map normals from flat to steep (none in a
// quarter, a zero vector in 3%: a broken map), views from either side but not within 0.01 of the
// mapped surface's plane, where which side the normal is turned to hangs on the last bit; base
// colours and metal-roughness over [0, 1] (roughness below the floor in a tenth), a normal-map
// covariance in half of the cases.
SurfaceCase randomSurfaceCase(Pcg32& rng) {
  SurfaceCase c{};
  c.baseColour = {uniformIn(rng, 0, 1), uniformIn(rng, 0, 1), uniformIn(rng, 0, 1), uniformIn(rng, 0, 1)};
  c.metallicRoughnessOcclusion = {randomSample(rng), rng.nextBelow(10) == 0 ? uniformIn(rng, 0.0f, 0.03f) : randomSample(rng),
                                  uniformIn(rng, 0, 1), 0.0f};
  c.emission = {uniformIn(rng, 0, 10), uniformIn(rng, 0, 10), uniformIn(rng, 0, 10), 0.0f};
  const glm::vec3 normal = randomDirection(rng);
  c.normal = glm::vec4(normal * uniformIn(rng, 0.5f, 2.0f), 0.0f);
  const bool degenerate = rng.nextBelow(50) == 0;
  const glm::vec3 tangent = degenerate ? normal * 2.0f : randomDirection(rng);
  c.tangent = glm::vec4(tangent, rng.nextBelow(2) == 0 ? -1.0f : 1.0f);
  switch (rng.nextBelow(8)) {
    case 0:
    case 1: c.mappedNormal = {0.0f, 0.0f, 1.0f, 0.0f}; break;
    case 2: c.mappedNormal = rng.nextBelow(4) == 0 ? glm::vec4(0.0f) : glm::vec4(0.0f, 0.0f, 1.0f, 0.0f); break;
    default: {
      const float scale = uniformIn(rng, 0.0f, 2.0f);
      c.mappedNormal = {uniformIn(rng, -1, 1) * scale, uniformIn(rng, -1, 1) * scale, uniformIn(rng, 0, 1), 0.0f};
    }
  }
  // The view, away from the plane of the mapped normal (computed as the kernel does).
  kernel::GlintSurfaceSamples probe = samplesOf(c);
  for (int tries = 0; tries < 100; ++tries) {
    c.view = glm::vec4(randomDirection(rng), 0.0f);
    probe.view = glm::vec3(c.view);
    probe.mappedNormal = glm::vec3(c.mappedNormal);
    const kernel::GlintSurface s = kernel::glintSurface(probe, kernel::GlintMaterial{}, exactFootprintPolicy());
    if (std::abs(glm::dot(s.n, probe.view)) > 0.01f) break;
  }
  c.glintSamples = {randomSample(rng), randomSample(rng), randomSample(rng), 0.0f};
  if (rng.nextBelow(2) == 0) {
    const float vx = uniformIn(rng, 0.0f, 0.5f);
    const float vy = uniformIn(rng, 0.0f, 0.5f);
    c.normalMapCovariance = {vx, uniformIn(rng, -0.99f, 0.99f) * std::sqrt(vx * vy), vy, 0.0f};
  }
  const FootprintPolicy policy = randomFootprintPolicy(rng);
  c.footprintPolicy = {policy.maxAnisotropy, policy.maxCells, policy.minBlend, 0.0f};
  // A coat in three cases of four, rough enough (roughness 0.2 to 1) that its lobe is not sharper than
  // the two frames' rounding; its own normal map in half of them; a light from anywhere.
  c.coat = rng.nextBelow(4) == 0 ? glm::vec4(0.0f) : glm::vec4(uniformIn(rng, 0, 1), uniformIn(rng, 0.2f, 1.0f), 0.0f, 0.0f);
  c.coatNormal = rng.nextBelow(2) == 0 ? glm::vec4(0.0f, 0.0f, 1.0f, 0.0f)
                                       : glm::vec4(uniformIn(rng, -0.5f, 0.5f), uniformIn(rng, -0.5f, 0.5f), uniformIn(rng, 0.2f, 1.0f), 0.0f);
  c.light = glm::vec4(randomDirection(rng), 0.0f);
  return c;
}

// 100 random materials (enabled or not) at 64 random shading points each. Same source; the GPU's
// normalize, cross and sqrt round differently from glm's (Mesa lowers normalize to a reciprocal
// square root), and the differences carry through the frame into wo and the widened roughness. A
// tangent nearly along the normal loses most of its length when made perpendicular, which
// magnifies those last bits: each value is held to 1e-5 of its vector's largest component
// (measured on llvmpipe: at most 4.8e-6, at such tangents; a sign or a swapped term is of order 1),
// every flag exactly.
TEST(KernelGl, SurfaceAgreesWithTheCpu) {
  useGlContext();
  std::map<std::string, std::string> sources = gl::embeddedFiles();
  sources["surface_eval.comp"] = slurp(std::filesystem::path(GLINT_SOURCE_DIR) / "tests/shaders/surface_eval.comp");
  ASSERT_FALSE(sources["surface_eval.comp"].empty());
  const gl::ShaderProgram program({{GL_COMPUTE_SHADER, "surface_eval.comp"}}, {}, sources);
  constexpr int kMaterials = 100;
  constexpr int kCases = 64;
  Pcg32 rng(20261207, 3);
  int compared = 0;
  int flipped = 0;     // views from behind: the normal turned towards the viewer
  int degenerate = 0;  // tangents along the normal
  int widened = 0;     // glint layers widened by a normal-map covariance
  float largest = 0.0f;
  float largestCoat = 0.0f;  // of coatLight, relative to itself
  int coatLit = 0;           // cases whose coat reflects the light
  for (int i = 0; i < kMaterials; ++i) {
    const kernel::GlintMaterial material = randomGlintMaterial(rng);
    GLuint buffer = 0;
    glCreateBuffers(1, &buffer);
    glNamedBufferStorage(buffer, sizeof material, &material, 0);
    std::vector<SurfaceCase> cases;
    for (int k = 0; k < kCases; ++k) cases.push_back(randomSurfaceCase(rng));
    const std::vector<SurfaceOutput> gpu = dispatchCompute<SurfaceOutput>(
        program, cases, [&] { glBindBufferBase(GL_UNIFORM_BUFFER, gl::kGlintMaterialBinding, buffer); });
    glDeleteBuffers(1, &buffer);
    for (int k = 0; k < kCases; ++k) {
      const SurfaceCase& c = cases[static_cast<std::size_t>(k)];
      const SurfaceOutput cpu = surfaceOnCpu(c, material);
      const glm::vec4* expected = &cpu.t;
      const glm::vec4* got = &gpu[static_cast<std::size_t>(k)].t;
      const glm::vec4 coatLight = gpu[static_cast<std::size_t>(k)].coatLight;
      for (int j = 0; j < 2; ++j) {
        const float difference = std::abs(coatLight[j] - cpu.coatLight[j]) / std::max(std::abs(cpu.coatLight[j]), 1e-3f);
        largestCoat = std::max(largestCoat, difference);
        EXPECT_LE(difference, 1e-3f) << "material " << i << ", case " << k << ", coatLight[" << j << "]: GPU "
                                     << coatLight[j] << ", CPU " << cpu.coatLight[j];
      }
      coatLit += cpu.coatLight.x > 0.0f;
      for (int v = 0; v < kOutputVectors - 1; ++v) {
        const glm::vec4 e = expected[v];
        const float scale = std::max({std::abs(e.x), std::abs(e.y), std::abs(e.z), std::abs(e.w), 1e-3f});
        for (int j = 0; j < 4; ++j) {
          const float difference = std::abs(got[v][j] - e[j]) / scale;
          largest = std::max(largest, difference);
          EXPECT_LE(difference, 1e-5f) << "material " << i << ", case " << k << ", vector " << v << "[" << j
                                       << "]: GPU " << got[v][j] << ", CPU " << e[j];
        }
      }
      flipped += glm::dot(glm::vec3(c.normal), glm::vec3(c.view)) < 0.0f;
      degenerate += std::abs(glm::dot(glm::normalize(glm::vec3(c.normal)), glm::normalize(glm::vec3(c.tangent)))) > 0.9999f;
      widened += material.enabled != 0u && c.normalMapCovariance.x + c.normalMapCovariance.z > 0.0f;
      ++compared;
    }
  }
  EXPECT_EQ(compared, kMaterials * kCases);
  EXPECT_GT(flipped, 1000);   // both sides are seen
  EXPECT_GT(degenerate, 40);  // the tangent's fallback is exercised
  EXPECT_GT(widened, 500);
  EXPECT_GT(coatLit, 1000);
  std::printf("surface: %d cases, largest difference %.2e of the vector's largest component; coat %.2e of itself\n",
              compared, largest, largestCoat);
}

// The rules on the CPU, at hand-picked inputs whose answers are known without the kernel.
TEST(Surface, AssemblesTheGltfMetalRoughnessSurface) {
  kernel::GlintSurfaceSamples s;
  s.baseColour = {0.8f, 0.4f, 0.2f, 0.5f};
  s.metallicRoughness = {0.25f, 0.01f};  // roughness below the floor
  s.emission = {1.0f, 2.0f, 3.0f};
  s.occlusion = 0.75f;
  s.normal = {0.0f, 0.0f, 2.0f};  // not unit
  s.tangent = {1.0f, 0.0f, 0.5f, -1.0f};  // not perpendicular, left-handed
  s.mappedNormal = {0.0f, 0.0f, 1.0f};
  s.view = {0.0f, 0.6f, 0.8f};
  s.glintSamples = {1.0f, 1.0f, 1.0f};
  s.normalMapCovariance = glm::vec3(0.0f);
  kernel::GlintMaterial layer{};
  const kernel::GlintSurface a = kernel::glintSurface(s, layer, exactFootprintPolicy());
  EXPECT_EQ(a.n, glm::vec3(0, 0, 1));
  EXPECT_EQ(a.t, glm::vec3(1, 0, 0));
  EXPECT_EQ(a.b, glm::vec3(0, -1, 0));  // cross(n, t) = +y, times the handedness
  EXPECT_NEAR(a.wo.y, -0.6f, 1e-7f);
  EXPECT_NEAR(a.wo.z, 0.8f, 1e-7f);
  EXPECT_EQ(a.roughness, kernel::GLINT_SURFACE_MIN_ROUGHNESS);
  EXPECT_EQ(a.smoothAlpha, glm::vec2(0.03f * 0.03f));
  EXPECT_EQ(a.smoothRho, 0.0f);
  EXPECT_NEAR(a.diffuse.x, 0.8f * 0.75f / 3.14159265f, 1e-7f);
  EXPECT_NEAR(a.f0.x, 0.04f * 0.75f + 0.8f * 0.25f, 1e-7f);
  EXPECT_EQ(a.emission, s.emission);
  EXPECT_EQ(a.occlusion, 0.75f);
  EXPECT_EQ(a.hasGlintLayer, 0u);

  // Seen from behind: the normal turned towards the viewer, the frame with it.
  s.view = {0.0f, 0.6f, -0.8f};
  const kernel::GlintSurface behind = kernel::glintSurface(s, layer, exactFootprintPolicy());
  EXPECT_EQ(behind.n, glm::vec3(0, 0, -1));
  EXPECT_NEAR(behind.wo.z, 0.8f, 1e-7f);

  // A glint layer: its alpha times the roughness texture's sample (0.3, 0.2 times 0.5), widened by
  // the normal map's covariance: Beckmann's slope variances alpha^2 / 2 plus (0.01, 0.02), back to
  // alpha = sqrt(2 variance): sqrt(2 (0.0225 / 2 + 0.01)) = 0.2062, sqrt(2 (0.01 / 2 + 0.02)) = 0.2236.
  layer.enabled = 1u;
  layer.alpha = {0.3f, 0.2f};
  layer.relativeArea = 1.0f;
  layer.maxAnisotropy = 8.0f;
  layer.uvScale = 1.0f;
  s.view = {0.0f, 0.6f, 0.8f};
  s.glintSamples = {0.5f, 1.0f, 1.0f};
  s.normalMapCovariance = {0.01f, 0.0f, 0.02f};
  const kernel::GlintSurface glinty = kernel::glintSurface(s, layer, exactFootprintPolicy());
  EXPECT_EQ(glinty.hasGlintLayer, 1u);
  EXPECT_NEAR(glinty.glint.alpha.x, std::sqrt(2.0f * (0.15f * 0.15f / 2.0f + 0.01f)), 1e-6f);
  EXPECT_NEAR(glinty.glint.alpha.y, std::sqrt(2.0f * (0.1f * 0.1f / 2.0f + 0.02f)), 1e-6f);
  EXPECT_EQ(glinty.glint.rho, 0.0f);
  EXPECT_EQ(glinty.smoothAlpha, glinty.glint.alpha);
  EXPECT_GT(glinty.glint.alpha.x, 0.15f);  // widened

  // A broken normal map (a zero vector) leaves the geometric normal; a tangent along the normal
  // falls back to a perpendicular one.
  s.mappedNormal = glm::vec3(0.0f);
  s.tangent = {0.0f, 0.0f, 3.0f, 1.0f};
  const kernel::GlintSurface broken = kernel::glintSurface(s, layer, exactFootprintPolicy());
  EXPECT_EQ(broken.n, glm::vec3(0, 0, 1));
  EXPECT_NEAR(glm::dot(broken.t, broken.n), 0.0f, 1e-7f);
  EXPECT_NEAR(glm::length(broken.t), 1.0f, 1e-6f);
}

}  // namespace
}  // namespace glint
