// Shared fixtures of the test suite: dictionaries built once per process, random cases, quadrature.
#pragma once

#include <filesystem>
#include <functional>
#include <string>

#include <glm/glm.hpp>

#include "bsdf.h"
#include "dictionary.h"
#include "pcg.h"

namespace glint::test {

// The default dictionary (paper parameters, stratified lobes, seed 1), generated once.
const Dictionary& defaultDictionary();
// The authors' published EXR dictionary from ../shared, loaded once; nullptr when absent.
const Dictionary* authorsDictionary();
std::filesystem::path authorsDictionaryFolder();

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
// Runs `glint ARGS < stdinText` in `folder`.
RunResult runGlint(const std::filesystem::path& folder, const std::string& arguments, const std::string& stdinText = "");
// A bad input: a non-zero exit (not a crash), exactly one line on stderr that contains `problem`.
void expectOneLineError(const RunResult& result, const std::string& problem);

// Uniform in [low, high) from a PCG32 stream.
float uniform(Pcg32& rng, float low, float high);
// A random footprint: uv in [0, 1)^2, derivatives of log-uniform length in [minLength, maxLength]
// with independent random directions (anisotropic, possibly sheared ellipses).
SurfaceFootprint randomFootprint(Pcg32& rng, float minLength, float maxLength);
// A unit direction in the upper hemisphere with the given polar angle and a random azimuth.
glm::vec3 directionAt(float thetaRadians, float phiRadians);

// Midpoint rule over [-extent.x, extent.x] x [-extent.y, extent.y] with cells x cells samples, in
// parallel: the integral of a function of slope.
double integrateOverSlopes(const std::function<double(glm::vec2)>& integrand, glm::vec2 extent, int cells);

// The slope extent outside of which a glint P22 of roughness alpha has no mass: the dictionary's
// support 4 sigma_d, rotated (x sqrt 2) and scaled by alpha / alpha_d; beyond 4 alpha Beckmann cells
// keep under 1e-7 of their mass.
glm::vec2 glintSlopeExtent(const Dictionary& dictionary, glm::vec2 alpha);

}  // namespace glint::test
