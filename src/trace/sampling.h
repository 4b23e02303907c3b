// Monte Carlo building blocks of the path tracer: per-sample random streams, hemisphere sampling,
// the power heuristic and piecewise-constant 1D / 2D distributions (pbrt-v3, section 13.6.7).
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "glint/microfacet_sampling.h"
#include "glint/pcg.h"

namespace glint::trace {

inline constexpr float kPi = 3.14159265358979f;

// The random stream of one sample of one pixel. Seeded from (pixel, sample) alone, so an image
// does not depend on the thread count or on the order in which tiles are rendered.
Pcg32 sampleStream(std::uint32_t pixel, std::uint32_t sample);

// Uniform in [0, 1) with 24 random bits: exactly representable, never rounds up to 1.
inline float uniformFloat(Pcg32& rng) { return static_cast<float>(rng.next() >> 8) * 0x1.0p-24f; }
inline glm::vec2 uniformFloat2(Pcg32& rng) {
  const float a = uniformFloat(rng);
  return {a, uniformFloat(rng)};
}

// Cosine-weighted directions about +z: the BSDFs' (glint/microfacet_sampling.h).
using sampling::cosineHemispherePdf;
using sampling::sampleCosineHemisphere;

// Veach's power heuristic (beta = 2) for one sample from each of two strategies.
inline float powerHeuristic(float pdfA, float pdfB) {
  const float a = pdfA * pdfA;
  const float b = pdfB * pdfB;
  return a + b > 0.0f ? a / (a + b) : 0.0f;
}

// A piecewise-constant density on [0, 1) from non-negative weights; all-zero weights give the
// uniform density.
class Distribution1D {
 public:
  explicit Distribution1D(const std::vector<float>& weights);
  // A continuous sample in [0, 1), its density, and the cell it fell in.
  float sample(float u, float* pdf, int* cell) const;
  float pdf(float x) const;     // density at x in [0, 1)
  float cellProbability(int cell) const { return cdf_[cell + 1] - cdf_[cell]; }  // of sample()'s cell
  float integral() const { return integral_; }  // mean of the weights
  int size() const { return static_cast<int>(weights_.size()); }

 private:
  std::vector<float> weights_;
  std::vector<float> cdf_;  // size() + 1 entries, cdf_[0] = 0, cdf_.back() = 1
  float integral_ = 0.0f;
};

// A piecewise-constant density on [0, 1)^2 from a width x height grid of weights (rows from v = 0):
// the marginal over rows, then the row's conditional.
class Distribution2D {
 public:
  Distribution2D(const std::vector<float>& weights, int width, int height);
  glm::vec2 sample(glm::vec2 u, float* pdf) const;
  float pdf(glm::vec2 p) const;

 private:
  std::vector<Distribution1D> rows_;
  Distribution1D marginal_;
};

}  // namespace glint::trace
