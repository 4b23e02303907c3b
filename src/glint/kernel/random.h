// Hashing and the few special functions the glint kernel draws its per-cell randomness with.
#ifndef GLINT_KERNEL_RANDOM_H
#define GLINT_KERNEL_RANDOM_H

#include "prelude.h"

GLINT_KERNEL_BEGIN

// Jarzynski & Olano 2020, "Hash Functions for GPU Rendering" (JCGT 9(3)): their pcg4d, a bijection of
// uvec4, so distinct inputs never collide. The model feeds it a collision-free cell seed and takes
// its four lanes as four independent uniform draws.
GLINT_FN uvec4 glintPcg4d(uvec4 v) {
  v = v * 1664525u + 1013904223u;
  v.x += v.y * v.w;
  v.y += v.z * v.x;
  v.z += v.x * v.y;
  v.w += v.y * v.z;
  v = v ^ (v >> 16u);
  v.x += v.y * v.w;
  v.y += v.z * v.x;
  v.z += v.x * v.y;
  v.w += v.y * v.z;
  return v;
}

// The same paper's one-lane "pcg" (PCG's RXS-M-XS output on one LCG step), a bijection of uint: a
// quarter of glintPcg4d's cost for a single word.
GLINT_FN uint glintPcg(uint v) {
  uint state = v * 747796405u + 2891336453u;
  uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

// A uniform float in (0, 1] from the top 24 bits k of a hash, identical on CPU and GPU:
// (k + 1/2) / 2^24, which rounds to a multiple of 2^-24 once k >= 2^23, so the top value is exactly
// 1 (a 2^-24 chance, which every caller tolerates). Never 0: erfinv(2u - 1) and log(u) stay finite.
GLINT_FN float glintHashToUnitOpen(uint h) {
  return (float(h >> 8u) + 0.5f) * (1.0f / 16777216.0f);
}

// Inverse error function, single precision: Giles 2010, "Approximating the erfinv function" (GPU
// Computing Gems Jade, ch. 10), relative error below 4e-7 on (-1, 1): central and tail polynomials
// in w = -log((1-x)(1+x)).
GLINT_FN float glintErfinvApprox(float x) {
  float w = -log((1.0f - x) * (1.0f + x));
  float p;
  if (w < 5.0f) {
    w = w - 2.5f;
    p = 2.81022636e-08f;
    p = 3.43273939e-07f + p * w;
    p = -3.5233877e-06f + p * w;
    p = -4.39150654e-06f + p * w;
    p = 0.00021858087f + p * w;
    p = -0.00125372503f + p * w;
    p = -0.00417768164f + p * w;
    p = 0.246640727f + p * w;
    p = 1.50140941f + p * w;
  } else {
    w = sqrt(w) - 3.0f;
    p = -0.000200214257f;
    p = 0.000100950558f + p * w;
    p = 0.00134934322f + p * w;
    p = -0.00367342844f + p * w;
    p = 0.00573950773f + p * w;
    p = -0.0076224613f + p * w;
    p = 0.00943887047f + p * w;
    p = 1.00167406f + p * w;
    p = 2.83297682f + p * w;
  }
  return p * x;
}

// Standard normal CDF Phi(z) = erfc(-z / sqrt 2) / 2, erfc from the Chebyshev fit of Press et al.,
// "Numerical Recipes" (2nd ed., section 6.2, erfcc): fractional error below 1.2e-7 everywhere, so Phi
// keeps its relative precision deep in the lower tail, where glintLevelDraw's thresholds lie.
GLINT_FN float glintNormalCdf(float z) {
  float x = abs(z) * 0.70710678f;
  float t = 1.0f / (1.0f + 0.5f * x);
  float p = 0.17087277f;
  p = -0.82215223f + t * p;
  p = 1.48851587f + t * p;
  p = -1.13520398f + t * p;
  p = 0.27886807f + t * p;
  p = -0.18628806f + t * p;
  p = 0.09678418f + t * p;
  p = 0.37409196f + t * p;
  p = 1.00002368f + t * p;
  p = -1.26551223f + t * p;
  float upperTail = 0.5f * t * exp(p - x * x);  // Phi(-|z|)
  return z < 0.0f ? upperTail : 1.0f - upperTail;
}

GLINT_KERNEL_END

#endif
