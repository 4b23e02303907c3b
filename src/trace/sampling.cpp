#include "trace/sampling.h"

#include <algorithm>
#include <cmath>

namespace glint::trace {

namespace {

// SplitMix64's finaliser (Steele, Lea & Flood 2014): decorrelates neighbouring (pixel, sample)
// pairs before they seed PCG32, whose nearby seeds would otherwise start on nearby states.
std::uint64_t mix64(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

std::vector<Distribution1D> makeRows(const std::vector<float>& weights, int width, int height) {
  std::vector<Distribution1D> rows;
  rows.reserve(static_cast<std::size_t>(height));
  for (int y = 0; y < height; ++y) {
    const auto begin = weights.begin() + static_cast<std::ptrdiff_t>(y) * width;
    rows.emplace_back(std::vector<float>(begin, begin + width));
  }
  return rows;
}

std::vector<float> rowIntegrals(const std::vector<Distribution1D>& rows) {
  std::vector<float> integrals;
  for (const Distribution1D& row : rows) integrals.push_back(row.integral());
  return integrals;
}

}  // namespace

Pcg32 sampleStream(std::uint32_t pixel, std::uint32_t sample) {
  return Pcg32(mix64((static_cast<std::uint64_t>(sample) << 32) | pixel), 0x7261637465ull);
}

Distribution1D::Distribution1D(const std::vector<float>& weights) : weights_(weights) {
  const std::size_t n = weights_.size();
  cdf_.assign(n + 1, 0.0f);
  double sum = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    sum += std::max(0.0f, weights_[i]);
    cdf_[i + 1] = static_cast<float>(sum);
  }
  integral_ = n > 0 ? static_cast<float>(sum / static_cast<double>(n)) : 0.0f;
  if (sum > 0.0) {
    for (std::size_t i = 1; i <= n; ++i) cdf_[i] = static_cast<float>(cdf_[i] / sum);
  } else {
    // No weight anywhere: fall back to the uniform density so that sampling stays defined.
    for (std::size_t i = 1; i <= n; ++i) cdf_[i] = static_cast<float>(i) / static_cast<float>(n);
    for (float& w : weights_) w = 1.0f;
  }
  cdf_[n] = 1.0f;
}

float Distribution1D::sample(float u, float* pdf, int* cell) const {
  const int n = size();
  // The last i with cdf_[i] <= u, kept within [0, n - 1].
  const auto it = std::upper_bound(cdf_.begin(), cdf_.end(), u);
  const int i = std::clamp(static_cast<int>(it - cdf_.begin()) - 1, 0, n - 1);
  const float width = cdf_[i + 1] - cdf_[i];
  const float offset = width > 0.0f ? (u - cdf_[i]) / width : 0.5f;
  if (pdf) *pdf = width * static_cast<float>(n);
  if (cell) *cell = i;
  return std::min((static_cast<float>(i) + std::clamp(offset, 0.0f, 1.0f)) / static_cast<float>(n), 0x1.fffffep-1f);
}

float Distribution1D::pdf(float x) const {
  const int n = size();
  const int i = std::clamp(static_cast<int>(x * static_cast<float>(n)), 0, n - 1);
  return (cdf_[i + 1] - cdf_[i]) * static_cast<float>(n);
}

Distribution2D::Distribution2D(const std::vector<float>& weights, int width, int height)
    : rows_(makeRows(weights, width, height)), marginal_(rowIntegrals(rows_)) {}

glm::vec2 Distribution2D::sample(glm::vec2 u, float* pdf) const {
  float pdfV = 0.0f;
  float pdfU = 0.0f;
  int row = 0;
  const float v = marginal_.sample(u.y, &pdfV, &row);
  const float x = rows_[static_cast<std::size_t>(row)].sample(u.x, &pdfU, nullptr);
  if (pdf) *pdf = pdfU * pdfV;
  return {x, v};
}

float Distribution2D::pdf(glm::vec2 p) const {
  const int row = std::clamp(static_cast<int>(p.y * static_cast<float>(rows_.size())), 0,
                             static_cast<int>(rows_.size()) - 1);
  return marginal_.pdf(p.y) * rows_[static_cast<std::size_t>(row)].pdf(p.x);
}

}  // namespace glint::trace
