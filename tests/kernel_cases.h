// The CPU-versus-GPU kernel test's cases, shared by the desktop GLSL test (tests/test_gl_kernel.cpp,
// a compute shader) and the WebGL2 test (tests/test_web.cpp, a fragment shader in a browser):
// random inputs over the whole parameter space, their layout for the GPU
// (shaders/kernel_eval.glsl), their values on the CPU and the comparison of both.
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "glint/kernel/glint_material.h"
#include "test_support.h"

namespace glint::test {

struct KernelInput {
  glm::vec4 uvAndDuvdx, duvdyAndAlpha, woAndLogDensity, wiAndRelativeArea, randomisationEtc, slopeDerivatives, target,
      footprintPolicy;
};
struct KernelCase {
  GlintParameters parameters;
  SurfaceFootprint footprint;
  glm::vec3 wo, wi;
  glm::vec4 derivatives{0.0f};  // the half vector slope's screen derivatives, for the filtered program
};
struct KernelValues {
  float f, d, p22, cookTorrance;
};

// The 2020 kernel's values of a case on the CPU, and the anti-aliased one's (glintFilteredP22) at
// the case's slope derivatives.
KernelValues evaluateOnCpu(const KernelCase& c);
KernelValues evaluateFilteredOnCpu(const KernelCase& c);
std::vector<KernelInput> kernelInputs(const std::vector<KernelCase>& cases);

// A random footprint policy: the paper's footprint (exact) in a third of the draws, else aniso, cells,
// drop or all three, over their ranges.
FootprintPolicy randomFootprintPolicy(Pcg32& rng);

// Uniform in [low, high) from the open-unit draw (never exactly high).
float uniformIn(Pcg32& rng, float low, float high);
// A random glint material (kernel/glint_material.h) over the accepted ranges (docs/conventions.md),
// with alphas and relative areas that the textures' samples push past the clamps, and every flag
// either way.
kernel::GlintMaterial randomGlintMaterial(Pcg32& rng);
// A texture sample: 8-bit values (glTF textures) in half the draws, exactly 0 or 1 in some, any
// value in [0, 1] otherwise.
float randomSample(Pcg32& rng);

// Random inputs over the whole parameter space: anisotropic roughness, densities from sparse to
// smooth, relative areas, footprints from magnified to minified, directions down to grazing, both
// smooth targets, both maskings, with and without multiple scattering, both LOD constructions.
std::vector<KernelCase> randomKernelCases(int count);
// The same with slope derivatives, for the anti-aliased kernel: slope correlation in a third of the
// cases, and derivatives from none to a few times the lobe's width, so that every mip level is read.
std::vector<KernelCase> randomFilteredKernelCases(int count);

// The GPU's values of the cases (of the 2020 kernel, or the anti-aliased one) against the CPU's:
// 99.9% must agree within cpuAndGpuAgree, every disagreement must be at a branch boundary
// (onBranchBoundary), more than half of the cases must see the lobe, and a tenth of them with each
// target and masking.
void expectCpuAndGpuAgree(const std::vector<KernelCase>& cases, bool filtered, const std::vector<KernelValues>& gpu,
                          const char* gpuName);

}  // namespace glint::test
