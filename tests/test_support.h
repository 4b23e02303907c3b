// Shared fixtures of the test suite: dictionaries built once per process, random cases, quadrature.
#pragma once

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "glint/bsdf.h"
#include "glint/dictionary.h"
#include "glint/pcg.h"

namespace glint::test {

// The default dictionary (paper parameters, stratified lobes, seed 1), generated once.
const Dictionary& defaultDictionary();
// The authors' published EXR dictionary from ../shared, loaded once; nullptr when absent.
const Dictionary* authorsDictionary();
std::filesystem::path authorsDictionaryFolder();

// The built-in scenes at the scale of the paper's performance table (atrium and car: a quarter and
// three quarters of a million triangles), which have tests of their own at small sizes, and the
// others (builtinSceneNames() without them), which have golden images and go through the slowest
// whole-program checks (the viewer against render, the page against the desktop).
bool isPaperScaleScene(const std::string& name);
std::vector<std::string> smallBuiltinSceneNames();

// A fresh, empty temporary folder for one test.
std::filesystem::path temporaryFolder(const std::string& name);

// The `glint` program, for the *Cli suites.
struct RunResult {
  int exitCode;  // -1 when the process died from a signal
  std::string out;
  std::string err;
};
// A whole file's bytes ("" when it cannot be read).
std::string slurp(const std::filesystem::path& path);
// CRC-32 (IEEE 802.3, zlib's and PNG's), written bit by bit, for fixtures that carry checksums.
std::uint32_t crc32Ieee(std::string_view bytes);
// Runs `glint ARGS < stdinText` in `folder`.
// `environment` (e.g. "PATH=/nonexistent") is set for glint alone.
RunResult runGlint(const std::filesystem::path& folder, const std::string& arguments, const std::string& stdinText = "",
                   const std::string& environment = "");
// A bad input: a non-zero exit (not a crash), exactly one line on stderr that contains `problem`.
void expectOneLineError(const RunResult& result, const std::string& problem);
// The message of the glint::Error `body` throws ("" and a test failure when it throws none).
std::string errorOf(const std::function<void()>& body);

// Uniform in [low, high) from a PCG32 stream.
float uniform(Pcg32& rng, float low, float high);
// Two uniform draws, in [low.x, high.x) and [low.y, high.y), y drawn before x. A call's arguments
// are evaluated in an unspecified order (g++ right to left, clang left to right), so
// glm::vec2(uniform(...), uniform(...)) draws other cases under each compiler; the fixed-seed
// tests' bounds were measured with g++'s order, which this keeps under both.
glm::vec2 uniformPair(Pcg32& rng, glm::vec2 low, glm::vec2 high);
// A random footprint: uv in [0, 1)^2, derivatives of log-uniform length in [minLength, maxLength]
// with independent random directions (anisotropic, possibly sheared ellipses).
SurfaceFootprint randomFootprint(Pcg32& rng, float minLength, float maxLength);
// Uv derivatives whose footprint ellipse has principal semi-axes `major` (along the uv direction
// at `uvAngle` radians) and `minor`, seen by screen axes turned by `screenAngle` from them: the
// columns duvdx, duvdy of J = R(uvAngle) diag(major, minor) R(screenAngle). They are perpendicular
// only when screenAngle is a multiple of 90 degrees; otherwise they are conjugate semi-diameters
// of the same ellipse.
std::pair<glm::vec2, glm::vec2> turnedDerivatives(float major, float minor, float uvAngle, float screenAngle);
// A unit direction in the upper hemisphere with the given polar angle and a random azimuth.
glm::vec3 directionAt(float thetaRadians, float phiRadians);
// directionAt of a polar angle in [0, maxTheta) and an azimuth in [0, maxPhi), the azimuth drawn
// first (uniformPair's order).
glm::vec3 randomDirectionAt(Pcg32& rng, float maxTheta, float maxPhi);

// The mean of the glint P-NDF at m over `positions` random uv positions in [0, 1)^2 (PCG32 stream
// `stream` of seed 99), each with a square footprint of 1e-3 uv.
double meanNdfOverPositions(const GlintParameters& parameters, glm::vec3 m, int positions, std::uint64_t stream);

// Midpoint rule over [-extent.x, extent.x] x [-extent.y, extent.y] with cells x cells samples, in
// parallel: the integral of a function of slope.
double integrateOverSlopes(const std::function<double(glm::vec2)>& integrand, glm::vec2 extent, int cells);

// The integral of g over the whole slope plane, substituted per axis as slope = alpha sinh(t),
// t in [-T, T] with T = asinh(reach) (GGX keeps 1e-8 of its mass beyond 1e4 alpha), cells x cells
// midpoints: fine near the peak, and relative to the slope out in the tail (where a GGX glint
// cell's lobes are wide in proportion).
double integrateOverWholeSlopePlane(const std::function<double(glm::vec2)>& g, glm::vec2 alpha, int cells,
                                    float reach = 1e4f);

// The slope extent outside of which a glint P22 of roughness alpha has no mass: the dictionary's
// support 4 sigma_d, rotated (x sqrt 2) and scaled by alpha / alpha_d; beyond 4 alpha Beckmann cells
// keep under 1e-7 of their mass.
glm::vec2 glintSlopeExtent(const Dictionary& dictionary, glm::vec2 alpha, float rho = 0.0f);

// CPU versus GLSL (tests/test_gl_kernel.cpp, tests/test_zirr_kaplanyan.cpp): relative agreement
// with an absolute floor, values under 1e-5 (invisible in 8-bit output under an intensity of 1)
// counting as equal.
inline bool cpuAndGpuAgree(float gpu, float cpu) { return std::abs(gpu - cpu) <= 1e-3f * std::abs(cpu) + 1e-5f; }

// A disagreement is explained when the CPU result itself jumps by at least half as much under a
// perturbation of the inputs far below any visible scale (uv by 1e-6, wi by 1e-5): the input sits
// on one of the model's branch boundaries, where the two languages' float differences (sin, exp,
// log) legitimately pick different sides. `Case` has footprint.uv and wi; evaluateOnCpu(Case)
// returns the float compared.
template <typename Case, typename EvaluateOnCpu>
bool onBranchBoundary(const Case& c, float gpu, EvaluateOnCpu evaluateOnCpu) {
  const float cpu = evaluateOnCpu(c);
  for (int k = 0; k < 16; ++k) {
    Case moved = c;
    const float e = (k & 1 ? 1.0f : -1.0f);
    moved.footprint.uv += glm::vec2(k & 2 ? 1e-6f : 0.0f, k & 4 ? 1e-6f : 0.0f) * e;
    if (k & 8) moved.wi = glm::normalize(moved.wi + glm::vec3(1e-5f * e, -1e-5f * e, 0.0f));
    if (std::abs(evaluateOnCpu(moved) - cpu) >= 0.5f * std::abs(gpu - cpu)) return true;
  }
  return false;
}

// Directional albedo integral of f(wo, wi) cos(theta_i) dwi of a reflection-only BSDF (F = 1 for a
// white furnace), substituted to the slope plane of the half vector: dwi = 4 (wo.m) dwm and
// dwm = m.z^3 ds, over glintSlopeExtent(defaultDictionary(), alpha) with cells x cells midpoints.
// Deterministic; for a glint P22, 200 x 200 cells agree with 800 x 800 within 2e-4
// (tests/test_glint_brdf.cpp, kGridCells).
template <typename Bsdf>
double directionalAlbedo(const Bsdf& bsdf, glm::vec3 wo, glm::vec2 alpha, int cells) {
  return integrateOverSlopes(
      [&](glm::vec2 slope) {
        const glm::vec3 m = glm::normalize(glm::vec3(-slope.x, -slope.y, 1.0f));
        const float woDotM = glm::dot(wo, m);
        if (woDotM <= 0.0f) return 0.0;
        const glm::vec3 wi = 2.0f * woDotM * m - wo;
        if (wi.z <= 0.0f) return 0.0;
        return static_cast<double>(bsdf.f(wo, wi).x) * wi.z * 4.0 * woDotM * std::pow(m.z, 3.0);
      },
      glintSlopeExtent(defaultDictionary(), alpha), cells);
}

}  // namespace glint::test
