// Dictionary generation (method.md section 1; docs/dictionary.md). Two stages:
//   1. lobe means, drawn sequentially from one PCG32 stream per placement rule (cheap);
//   2. tabulation and normalisation, one oneTBB task per distribution (the costly part).
// Every output value depends only on the parameters: each distribution is tabulated by one task
// in a fixed order, so the bytes are the same for any thread count.
#include <cmath>
#include <numeric>

#include <tbb/parallel_for.h>

#include "glint/dictionary.h"
#include "glint/error.h"
#include "glint/pcg.h"

namespace glint {

namespace {

// |mu| for a uniform u in (0, 1): the quantile of the half-normal |Normal(0, sigma)|. The tabulated
// densities are even, so only |mu| matters, and stratifying u stratifies |mu| over its whole range.
double halfNormalQuantile(double u, double sigma) {
  return -sigma * normalQuantile(0.5 * (1.0 - u));
}

// Each distribution's uniforms for its lobes, in nesting order.
std::vector<std::vector<double>> independentUniforms(const DictionaryParameters& p) {
  const std::size_t lobesPerDistribution = std::size_t{1} << (p.numLevels - 1);
  std::vector<std::vector<double>> uniforms(static_cast<std::size_t>(p.numDistributions));
  for (int n = 0; n < p.numDistributions; ++n) {
    Pcg32 rng(p.seed, static_cast<std::uint64_t>(n));
    uniforms[n].resize(lobesPerDistribution);
    for (double& u : uniforms[n]) u = rng.nextOpenUnit();
  }
  return uniforms;
}

// Stratified placement: level 0 puts the N first lobes in N equal strata of (0, 1), dealt to the
// distributions in a random order. Each further level halves every stratum and puts a new lobe,
// uniformly, in the half its stratum's lobe left empty; the new lobes are dealt at random, 2^l to
// each distribution. So the lobes of level l over all distributions, N 2^l of them, occupy the
// N 2^l strata one each, while every single distribution still receives random strata.
std::vector<std::vector<double>> stratifiedUniforms(const DictionaryParameters& p) {
  Pcg32 rng(p.seed, 0x5717a71f1edull);
  const auto N = static_cast<std::size_t>(p.numDistributions);
  std::vector<std::vector<double>> uniforms(N);
  for (auto& u : uniforms) u.reserve(std::size_t{1} << (p.numLevels - 1));

  auto deal = [&](std::vector<double>& lobes) {  // a uniform random permutation, then slices
    for (std::size_t i = lobes.size() - 1; i > 0; --i) {  // Fisher-Yates
      std::swap(lobes[i], lobes[rng.nextBelow(static_cast<std::uint32_t>(i + 1))]);
    }
    const std::size_t each = lobes.size() / N;
    for (std::size_t n = 0; n < N; ++n) {
      uniforms[n].insert(uniforms[n].end(), lobes.begin() + static_cast<std::ptrdiff_t>(n * each),
                         lobes.begin() + static_cast<std::ptrdiff_t>((n + 1) * each));
    }
  };

  std::vector<double> strata(N);  // the lobe occupying stratum j, strata of width 1 / size
  for (std::size_t j = 0; j < N; ++j) strata[j] = (static_cast<double>(j) + rng.nextOpenUnit()) / static_cast<double>(N);
  std::vector<double> first = strata;
  deal(first);
  for (int level = 1; level < p.numLevels; ++level) {
    const std::size_t count = strata.size();
    const double halfWidth = 0.5 / static_cast<double>(count);
    std::vector<double> finer(2 * count);
    std::vector<double> added(count);
    for (std::size_t j = 0; j < count; ++j) {
      const double lower = static_cast<double>(j) / static_cast<double>(count);
      const bool inLowerHalf = strata[j] < lower + halfWidth;
      const double emptyHalf = inLowerHalf ? lower + halfWidth : lower;
      // 32 random bits place a lobe well within even the finest stratum (width 2^-22.6 here).
      added[j] = emptyHalf + halfWidth * ((static_cast<double>(rng.next()) + 0.5) * 0x1.0p-32);
      finer[2 * j + (inLowerHalf ? 0 : 1)] = strata[j];
      finer[2 * j + (inLowerHalf ? 1 : 0)] = added[j];
    }
    deal(added);
    strata = std::move(finer);
  }
  return uniforms;
}

std::vector<std::vector<double>> lobeUniforms(const DictionaryParameters& p) {
  return p.placement == LobePlacement::Independent ? independentUniforms(p) : stratifiedUniforms(p);
}

// Adds the even lobe g(x; mu, s) + g(-x; mu, s), without its constant factor, to the texels at
// slopes x_k = k * spacing. Terms farther than 6 s from the lobe (below 1.6e-8 of its peak, far
// under binary16's 4.9e-4 resolution) are left out. Along the chain of slopes i * spacing around
// mu, exp(-(x - mu)^2 / (2 s^2)) follows the exact recurrence g(i+1) = g(i) r(i), r(i+1) = r(i) q
// with q = exp(-spacing^2 / s^2): three exp per lobe instead of one per texel. Chain slopes below
// zero are the mirrored lobe g(-x; mu, s): index -k lands on texel k (index 0 counts twice).
void addEvenLobe(std::vector<double>& accumulator, double mu, double s, double spacing) {
  const int texels = static_cast<int>(accumulator.size());
  const double inv2s2 = 1.0 / (2.0 * s * s);
  const int centre = static_cast<int>(std::lround(mu / spacing));
  const int reach = static_cast<int>(std::ceil(6.0 * s / spacing));
  const double offset = centre * spacing - mu;  // |offset| <= spacing / 2
  const double q = std::exp(-2.0 * spacing * spacing * inv2s2);
  double up = std::exp(-offset * offset * inv2s2);
  double down = up;
  double upRatio = std::exp(-(2.0 * offset * spacing + spacing * spacing) * inv2s2);
  double downRatio = std::exp(-(-2.0 * offset * spacing + spacing * spacing) * inv2s2);
  auto add = [&](int index, double value) {
    if (index >= 0 && index < texels) accumulator[static_cast<std::size_t>(index)] += value;
    if (index <= 0 && -index < texels) accumulator[static_cast<std::size_t>(-index)] += value;
  };
  add(centre, up);
  for (int d = 1; d <= reach; ++d) {  // two independent chains: twice the instruction parallelism
    up *= upRatio;
    upRatio *= q;
    down *= downRatio;
    downRatio *= q;
    add(centre + d, up);
    add(centre - d, down);
  }
}

}  // namespace

std::vector<std::vector<double>> generateLobeMeans(const DictionaryParameters& parameters) {
  parameters.validate();
  std::vector<std::vector<double>> means = lobeUniforms(parameters);
  const double sigma = parameters.sigma();
  tbb::parallel_for(std::size_t{0}, means.size(), [&](std::size_t n) {
    for (double& u : means[n]) u = halfNormalQuantile(u, sigma);
  });
  return means;
}

Dictionary generateDictionary(const DictionaryParameters& parameters) {
  if (parameters.placement == LobePlacement::Imported) {
    throw Error("dictionary generation needs placement 'stratified' or 'independent'");
  }
  const std::vector<std::vector<double>> uniforms = [&] {
    parameters.validate();
    return lobeUniforms(parameters);
  }();
  const int L = parameters.numLevels;
  const int N = parameters.numDistributions;
  const int R = parameters.texelsPerDistribution;
  const double sigma = parameters.sigma();
  const double s = parameters.lobeStd;
  const double spacing = static_cast<double>(parameters.slopeDomain()) / R;
  const double gaussianNorm = 1.0 / (s * std::sqrt(2.0 * M_PI));
  std::vector<float> values(static_cast<std::size_t>(L) * N * R);

  tbb::parallel_for(0, N, [&](int n) {
    // p_l(x) = 1 / (2 * 2^l) * sum_{k < 2^l} [g(x; mu_k, s) + g(-x; mu_k, s)]  (method.md 1).
    std::vector<double> sum(static_cast<std::size_t>(R), 0.0);
    std::size_t added = 0;
    for (int level = 0; level < L; ++level) {
      const std::size_t lobes = std::size_t{1} << level;
      for (; added < lobes; ++added) {
        const double mu = halfNormalQuantile(uniforms[static_cast<std::size_t>(n)][added], sigma);
        addEvenLobe(sum, mu, s, spacing);
      }
      // Normalise with the kernel's interpolation: piecewise linear through texel k at slope
      // k * spacing, falling to 0 at the domain's end; its integral over [-4 sigma_d, 4 sigma_d]
      // is the trapezoid sum 2 * spacing * (sum_k T_k - T_0 / 2).
      const double scale = gaussianNorm / (2.0 * static_cast<double>(lobes));
      double integral = 0.0;
      for (int k = 0; k < R; ++k) integral += sum[static_cast<std::size_t>(k)] * scale;
      integral = 2.0 * spacing * (integral - 0.5 * sum[0] * scale);
      float* row = &values[(static_cast<std::size_t>(level) * N + n) * R];
      for (int k = 0; k < R; ++k) row[k] = static_cast<float>(sum[static_cast<std::size_t>(k)] * scale / integral);
    }
  });
  return Dictionary(parameters, values);
}

}  // namespace glint
