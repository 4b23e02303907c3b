// Importance sampling of the glint BSDFs (docs/sampling.md): chi-square tests of every sampler
// against its own pdf, exact checks of the sample weights and of the mass that masked cells take
// away, pdf normalisation, and white-furnace albedos by sampling against deterministic quadrature.
// Suites: SamplingStat (statistical, fixed seeds), Sampling (exact).
#include <algorithm>
#include <array>
#include <cstdlib>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <numeric>
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <tbb/parallel_for.h>

#include "glint/error.h"
#include "glint/microfacet_sampling.h"
#include "test_support.h"

namespace glint {
namespace {

using namespace glint::test;

// ---------------------------------------------------------------------------------------------
// The chi-square harness, after pbrt-v3's and Mitsuba's: the sphere binned in (theta, phi),
// observed counts from the sampler, expected counts from its pdf integrated over each bin by
// quadrature, bins of expected count below 5 pooled, one extra bin for the samples that come back
// empty (below the horizon, masked cells) with expected count N (1 - integral of the pdf).

// Regularised upper incomplete gamma function Q(a, x) = Gamma(a, x) / Gamma(a): the series of
// P = 1 - Q for x < a + 1, else Legendre's continued fraction for Q evaluated by the modified Lentz
// method (both in Abramowitz & Stegun 6.5.29 and 6.5.31).
double regularisedGammaQ(double a, double x) {
  if (x <= 0.0) return 1.0;
  const double logPrefactor = -x + a * std::log(x) - std::lgamma(a);
  if (x < a + 1.0) {
    double term = 1.0 / a;
    double sum = term;
    for (int n = 1; n < 100000; ++n) {
      term *= x / (a + n);
      sum += term;
      if (std::abs(term) < std::abs(sum) * 1e-16) break;
    }
    return std::max(0.0, 1.0 - sum * std::exp(logPrefactor));
  }
  constexpr double kTiny = 1e-300;
  double b = x + 1.0 - a;
  double c = 1.0 / kTiny;
  double d = 1.0 / b;
  double h = d;
  for (int i = 1; i < 100000; ++i) {
    const double an = -i * (i - a);
    b += 2.0;
    d = an * d + b;
    if (std::abs(d) < kTiny) d = kTiny;
    c = b + an / c;
    if (std::abs(c) < kTiny) c = kTiny;
    d = 1.0 / d;
    const double delta = d * c;
    h *= delta;
    if (std::abs(delta - 1.0) < 1e-16) break;
  }
  return std::exp(logPrefactor) * h;
}

// p-value of a chi-square statistic with `dof` degrees of freedom.
double chiSquarePValue(double statistic, int dof) { return regularisedGammaQ(0.5 * dof, 0.5 * statistic); }

// (theta, phi) bins over the whole sphere; theta in [0, pi] from +z, phi in [0, 2 pi).
struct SphereBins {
  int thetaBins = 72;  // 2.5 degrees
  int phiBins = 144;
  int count() const { return thetaBins * phiBins; }
  int index(glm::vec3 w) const {
    const double theta = std::acos(std::clamp(static_cast<double>(w.z), -1.0, 1.0));
    double phi = std::atan2(static_cast<double>(w.y), static_cast<double>(w.x));
    if (phi < 0.0) phi += 2.0 * M_PI;
    const int i = std::min(thetaBins - 1, static_cast<int>(theta / M_PI * thetaBins));
    const int j = std::min(phiBins - 1, static_cast<int>(phi / (2.0 * M_PI) * phiBins));
    return i * phiBins + j;
  }
};

using SampleFunction = std::function<std::optional<BsdfSample>(float uChoice, glm::vec2 u)>;
using DirectionFunction = std::function<double(glm::vec3 wi)>;  // a pdf, or f |cos|

constexpr int kChunk = 1 << 14;

float unitFloat(Pcg32& rng) { return std::min(static_cast<float>(rng.nextOpenUnit()), sampling::kOneMinusEpsilon); }

// Observed counts per bin, and in the last entry the samples that came back empty. Chunks of
// kChunk samples each draw from their own PCG32 stream, so the counts do not depend on the threads.
std::vector<double> observedCounts(const SampleFunction& sample, const SphereBins& bins, int sampleCount,
                                   std::uint64_t seed) {
  const int chunks = (sampleCount + kChunk - 1) / kChunk;
  std::vector<std::vector<int>> perChunk(static_cast<std::size_t>(chunks));
  tbb::parallel_for(0, chunks, [&](int c) {
    std::vector<int> counts(static_cast<std::size_t>(bins.count() + 1), 0);
    Pcg32 rng(seed, static_cast<std::uint64_t>(c));
    const int end = std::min(sampleCount, (c + 1) * kChunk);
    for (int i = c * kChunk; i < end; ++i) {
      const float uChoice = unitFloat(rng);
      const float ux = unitFloat(rng);
      const float uy = unitFloat(rng);
      const std::optional<BsdfSample> s = sample(uChoice, glm::vec2(ux, uy));
      ++counts[static_cast<std::size_t>(s ? bins.index(s->wi) : bins.count())];
    }
    perChunk[static_cast<std::size_t>(c)] = std::move(counts);
  });
  std::vector<double> total(static_cast<std::size_t>(bins.count() + 1), 0.0);
  for (const auto& counts : perChunk) {
    for (std::size_t k = 0; k < counts.size(); ++k) total[k] += counts[k];
  }
  return total;
}

// Integrals over the bins of a function of direction g (a pdf, or f |cos|) by the midpoint rule on
// a (theta, phi) grid inside each bin, weight sin(theta) dtheta dphi: no cell of the grid straddles
// a bin edge, and no Jacobian is involved. The pdfs are functions of the (generalised) half
// vector's slope whose finest features have a known size there (a third of the dictionary's texel
// spacing for sparse glints: slopeStep), so the grid is made as fine as the local stretch of the
// map from directions to half-vector slopes asks: grazing views stretch it by 1 / <wo, m> across
// the plane of incidence, refraction narrows lobes by a third, and the poles squeeze phi. `slopeOf`
// gives that slope, nullopt where the pdf is 0 by construction; g is called only where the slope
// lies in [-box, box]^2, outside of which every pdf here is 0 (or holds under 1e-7 of its mass,
// Beckmann).
using SlopeFunction = std::function<std::optional<glm::dvec2>(glm::dvec3 wi)>;

glm::dvec3 sphericalDirection(double theta, double phi) {
  return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}

// One cell of a bin, [theta0, theta0 + dTheta] x [phi0, phi0 + dPhi], with the slopes of its four
// corners: skipped when its image lies away from the box by more than twice its own extent in slope
// (at most twice the box), split in four while its image is longer than 16 steps along theta or
// phi (so that the parts far from the box, towards a singularity of the half vector, drop out),
// else integrated by the midpoint rule with ceil(1.2 extent / slopeStep) points along each (at most
// 64 at the deepest level, reached only beside such singularities). With
// 1.2 every case of this file passes at 10^6 samples too; 1.0 left the sparsest case (alpha 0.1,
// log density 15, 5 degrees) a chi-square excess of 18% of its degrees of freedom at 10^6.
//
// With the GGX target the pdf reaches far out (a heavy tail, cells up to 10 times wider), so its box
// is the whole plane in effect and the step grows with the slope: slopeStep * max(1, stepGrowth
// |slope|) at the cell's corner nearest the origin. It can, because a GGX cell that reaches a slope
// s is at least s / (5.7 alpha) times wider than a Beckmann cell, and so are its lobes.
struct CellIntegrator {
  const DirectionFunction& g;
  const SlopeFunction& slopeOf;
  glm::dvec2 box;
  double slopeStep;
  double stepGrowth;

  bool inBox(glm::dvec2 slope, double margin) const {
    return std::abs(slope.x) <= box.x + margin && std::abs(slope.y) <= box.y + margin;
  }

  static double edge(const std::optional<glm::dvec2>& a, const std::optional<glm::dvec2>& b) {
    return a && b ? glm::length(*a - *b) : 0.0;
  }

  // corners: [theta index][phi index]
  double integrate(double theta0, double dTheta, double phi0, double dPhi, const std::optional<glm::dvec2> (&c)[2][2],
                   int depth) const {
    constexpr int kMaxPoints = 16;
    constexpr int kMaxDepth = 6;
    const double extentTheta = std::max(edge(c[0][0], c[1][0]), edge(c[0][1], c[1][1]));
    const double extentPhi = std::max(edge(c[0][0], c[0][1]), edge(c[1][0], c[1][1]));
    const double margin = 2.0 * std::min(std::max(extentTheta, extentPhi), std::max(box.x, box.y));
    bool near = false;
    for (const auto& row : c) {
      for (const auto& corner : row) near = near || (corner && inBox(*corner, margin));
    }
    if (!near) return 0.0;
    double nearest = std::numeric_limits<double>::infinity();
    for (const auto& row : c) {
      for (const auto& corner : row) nearest = corner ? std::min(nearest, glm::length(*corner)) : nearest;
    }
    const double slopeStep = stepGrowth > 0.0 && std::isfinite(nearest)
                                 ? this->slopeStep * std::max(1.0, stepGrowth * nearest)
                                 : this->slopeStep;
    constexpr double kFactor = 1.2;
    const int kTheta = std::max(1, static_cast<int>(std::ceil(kFactor * extentTheta / slopeStep)));
    const int kPhi = std::max(1, static_cast<int>(std::ceil(kFactor * extentPhi / slopeStep)));
    if ((kTheta > kMaxPoints || kPhi > kMaxPoints) && depth < kMaxDepth) {
      std::optional<glm::dvec2> grid[3][3];
      for (int a = 0; a < 3; ++a) {
        for (int b = 0; b < 3; ++b) {
          grid[a][b] = (a % 2 == 0 && b % 2 == 0) ? c[a / 2][b / 2]
                                                  : slopeOf(sphericalDirection(theta0 + 0.5 * dTheta * a, phi0 + 0.5 * dPhi * b));
        }
      }
      double sum = 0.0;
      for (int a = 0; a < 2; ++a) {
        for (int b = 0; b < 2; ++b) {
          const std::optional<glm::dvec2> corners[2][2] = {{grid[a][b], grid[a][b + 1]}, {grid[a + 1][b], grid[a + 1][b + 1]}};
          sum += integrate(theta0 + 0.5 * dTheta * a, 0.5 * dTheta, phi0 + 0.5 * dPhi * b, 0.5 * dPhi, corners, depth + 1);
        }
      }
      return sum;
    }
    const int nTheta = std::min(kTheta, 4 * kMaxPoints);
    const int nPhi = std::min(kPhi, 4 * kMaxPoints);
    const double hTheta = dTheta / nTheta;
    const double hPhi = dPhi / nPhi;
    double sum = 0.0;
    for (int a = 0; a < nTheta; ++a) {
      const double theta = theta0 + (a + 0.5) * hTheta;
      const double sinTheta = std::sin(theta);
      for (int b = 0; b < nPhi; ++b) {
        const glm::dvec3 w = sphericalDirection(theta, phi0 + (b + 0.5) * hPhi);
        const std::optional<glm::dvec2> slope = slopeOf(w);
        if (!slope || !inBox(*slope, 0.0)) continue;
        sum += g(glm::vec3(w)) * sinTheta;
      }
    }
    return sum * hTheta * hPhi;
  }
};

std::vector<double> binIntegrals(const DirectionFunction& g, const SlopeFunction& slopeOf, glm::dvec2 box,
                                 const SphereBins& bins, double slopeStep, double stepGrowth = 0.0) {
  std::vector<double> integrals(static_cast<std::size_t>(bins.count()), 0.0);
  const double dTheta = M_PI / bins.thetaBins;
  const double dPhi = 2.0 * M_PI / bins.phiBins;
  const CellIntegrator integrator{g, slopeOf, box, slopeStep, stepGrowth};
  tbb::parallel_for(0, bins.thetaBins, [&](int i) {
    std::vector<std::optional<glm::dvec2>> lower(static_cast<std::size_t>(bins.phiBins + 1));
    std::vector<std::optional<glm::dvec2>> upper(lower.size());
    for (int j = 0; j <= bins.phiBins; ++j) {
      lower[static_cast<std::size_t>(j)] = slopeOf(sphericalDirection(i * dTheta, j * dPhi));
      upper[static_cast<std::size_t>(j)] = slopeOf(sphericalDirection((i + 1) * dTheta, j * dPhi));
    }
    for (int j = 0; j < bins.phiBins; ++j) {
      const auto k = static_cast<std::size_t>(j);
      const std::optional<glm::dvec2> corners[2][2] = {{lower[k], lower[k + 1]}, {upper[k], upper[k + 1]}};
      integrals[static_cast<std::size_t>(i * bins.phiBins + j)] = integrator.integrate(i * dTheta, dTheta, j * dPhi, dPhi, corners, 0);
    }
  });
  return integrals;
}

glm::dvec2 slopeOfNormal(glm::dvec3 m) { return {-m.x / m.z, -m.y / m.z}; }

// The slope of the half vector of (wo, wi) for a reflection: wi on wo's side, half vector turned to
// the outside; nullopt elsewhere (the pdf is 0 there).
SlopeFunction reflectionSlope(glm::vec3 wo) {
  const glm::dvec3 o(wo);
  return [o](glm::dvec3 wi) -> std::optional<glm::dvec2> {
    if (wi.z * o.z <= 0.0) return std::nullopt;
    glm::dvec3 m = o + wi;
    if (glm::dot(m, m) == 0.0) return std::nullopt;
    m = glm::normalize(m);
    if (m.z < 0.0) m = -m;
    if (m.z <= 1e-9) return std::nullopt;
    return slopeOfNormal(m);
  };
}

// For a dielectric: the reflection's half vector on wo's side, the generalised half vector
// wo + (n_wi / n_wo) wi (Walter et al. 2007, Eq. 16) on the other side, turned to the outside.
SlopeFunction dielectricSlope(glm::vec3 wo, float eta) {
  const glm::dvec3 o(wo);
  return [o, eta](glm::dvec3 wi) -> std::optional<glm::dvec2> {
    if (wi.z == 0.0) return std::nullopt;
    const double etap = wi.z * o.z > 0.0 ? 1.0 : (o.z > 0.0 ? eta : 1.0 / eta);
    glm::dvec3 m = o + etap * wi;
    if (glm::dot(m, m) == 0.0) return std::nullopt;
    m = glm::normalize(m);
    if (m.z < 0.0) m = -m;
    if (m.z <= 1e-9) return std::nullopt;
    return slopeOfNormal(m);
  };
}

struct ChiSquareResult {
  double statistic = 0.0;
  int dof = 0;
  double pValue = 0.0;
  std::string problem;     // non-empty when samples fell where the pdf is 0
  double pdfIntegral = 0;  // over the sphere, by quadrature
  double emptyFraction = 0;  // of the samples
};

// pbrt-v3's pooling: bins sorted by expected count; those under 5 pooled together, and the pool
// grows by the next bins until it reaches 5. Samples in bins of expected count 0 are an error
// beyond 1e-5 of all samples (pbrt-v3's allowance for quadrature that misses thin slivers).
ChiSquareResult chiSquare(const std::vector<double>& observed, const std::vector<double>& expected, int sampleCount) {
  constexpr double kMinExpected = 5.0;
  std::vector<std::size_t> order(expected.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return expected[a] < expected[b]; });
  ChiSquareResult result;
  double pooledObserved = 0.0;
  double pooledExpected = 0.0;
  for (std::size_t k : order) {
    if (expected[k] <= 0.0) {
      if (observed[k] > sampleCount * 1e-5) {
        result.problem = std::to_string(observed[k]) + " samples in bin " + std::to_string(k) + " of pdf 0";
      }
    } else if (expected[k] < kMinExpected || (pooledExpected > 0.0 && pooledExpected < kMinExpected)) {
      pooledObserved += observed[k];
      pooledExpected += expected[k];
    } else {
      const double difference = observed[k] - expected[k];
      result.statistic += difference * difference / expected[k];
      ++result.dof;
    }
  }
  if (pooledExpected > 0.0) {
    const double difference = pooledObserved - pooledExpected;
    result.statistic += difference * difference / pooledExpected;
    ++result.dof;
  }
  result.dof -= 1;  // the counts sum to the sample count
  result.pValue = result.dof > 0 ? chiSquarePValue(result.statistic, result.dof) : 1.0;
  return result;
}

// The whole test for one sampler: observed and expected counts, then the statistic.
struct Quadrature {
  SlopeFunction slopeOf;
  glm::dvec2 box;
  double slopeStep;
  double stepGrowth = 0.0;  // CellIntegrator
};

ChiSquareResult runChiSquare(const SampleFunction& sample, const DirectionFunction& pdf, const Quadrature& quadrature,
                             int sampleCount, std::uint64_t seed) {
  const SphereBins bins;
  const std::vector<double> observed = observedCounts(sample, bins, sampleCount, seed);
  const std::vector<double> integrals =
      binIntegrals(pdf, quadrature.slopeOf, quadrature.box, bins, quadrature.slopeStep, quadrature.stepGrowth);
  std::vector<double> expected(integrals.size() + 1);
  double integral = 0.0;
  for (std::size_t k = 0; k < integrals.size(); ++k) {
    expected[k] = integrals[k] * sampleCount;
    integral += integrals[k];
  }
  expected.back() = std::max(0.0, 1.0 - integral) * sampleCount;
  ChiSquareResult result = chiSquare(observed, expected, sampleCount);
  result.pdfIntegral = integral;
  result.emptyFraction = observed.back() / sampleCount;
  return result;
}

// ---------------------------------------------------------------------------------------------
// The cases. Every chi-square test of this file counts in the Sidak correction: each is run at
// significance 1 - (1 - 0.01)^(1 / kChiSquareTests), so that the whole file rejects a correct
// sampler with probability 0.01.

struct SamplingCase {
  std::string name;
  enum class Kind { Glint, CookTorrance, Dielectric } kind = Kind::Glint;
  GlintSampler sampler = GlintSampler::Mixture;
  float alpha = 0.25f;
  float logDensity = 21.0f;
  float thetaDegrees = 45.0f;  // of wo from the normal; above 90 the viewer is inside (dielectric)
  float relativeArea = 1.0f;
  float eta = 1.5f;
  float rho = 0.0f;  // slope correlation
  int ndf = kernel::GLINT_NDF_BECKMANN;  // the smooth target (kernel/microfacet_targets.h)
  bool multipleScattering = false;  // the compensation lobe (kernel/multiple_scattering.h)
  FootprintPolicy footprintPolicy = exactFootprintPolicy();  // --footprint
  int lod = kernel::GLINT_LOD_PAPER;  // the LOD construction (kernel glintLodCell)
};

// Footprint of a pixel: 1.5:1, rotated, area pi |det| = 1.5e-6 uv^2, so a log density of 15, 21,
// 32 puts about 5, 2000, 1.2e11 microfacets in it (32: about 10% of its cells are in the smooth
// Beckmann limit, the rest at dictionary levels around 12). Its LOD is 4.2: about 10 cells of level
// 4 and 5 of level 5, blended 0.8 : 0.2.
SurfaceFootprint caseFootprint(int index) {
  SurfaceFootprint footprint;
  footprint.uv = glm::vec2(0.137f + 0.0731f * static_cast<float>(index), 0.613f - 0.0419f * static_cast<float>(index));
  footprint.duvdx = glm::vec2(7.0e-4f, 4.7e-4f);
  footprint.duvdy = glm::vec2(-2.6e-4f, 5.0e-4f);
  return footprint;
}

GlintParameters caseParameters(const SamplingCase& c) {
  GlintParameters parameters = defaultGlintParameters();
  parameters.alpha = glm::vec2(c.alpha);
  parameters.logDensity = c.logDensity;
  parameters.relativeArea = c.relativeArea;
  parameters.rho = c.rho;
  parameters.ndf = c.ndf;
  parameters.multipleScattering = c.multipleScattering;
  parameters.footprintPolicy = c.footprintPolicy;
  parameters.lod = c.lod;
  return parameters;
}

glm::vec3 caseWo(const SamplingCase& c, int index) {
  return directionAt(glm::radians(c.thetaDegrees), 0.3f + 0.7f * static_cast<float>(index));
}

std::vector<SamplingCase> chiSquareCases() {
  std::vector<SamplingCase> cases;
  auto label = [](float value) {
    std::string text = std::to_string(value);
    text = text.substr(0, text.find_last_not_of('0') + 1);
    if (text.back() == '.') text.pop_back();
    std::replace(text.begin(), text.end(), '.', 'p');
    return text;
  };
  for (float alpha : {0.1f, 0.25f, 0.6f}) {
    for (float logDensity : {15.0f, 21.0f, 32.0f}) {
      for (float theta : {5.0f, 45.0f, 75.0f}) {
        SamplingCase c;
        c.name = "Mixture_alpha" + label(alpha) + "_density" + label(logDensity) + "_theta" + label(theta);
        c.alpha = alpha;
        c.logDensity = logDensity;
        c.thetaDegrees = theta;
        cases.push_back(c);
      }
    }
  }
  for (float alpha : {0.1f, 0.25f, 0.6f}) {
    for (float theta : {5.0f, 45.0f, 75.0f}) {
      SamplingCase c;
      c.name = "Gaussian_alpha" + label(alpha) + "_theta" + label(theta);
      c.sampler = GlintSampler::Gaussian;
      c.alpha = alpha;
      c.thetaDegrees = theta;
      cases.push_back(c);
    }
  }
  {
    SamplingCase c;
    c.name = "Mixture_relativeArea0p5";
    c.relativeArea = 0.5f;
    cases.push_back(c);
  }
  // Slope correlation (Chermain et al. 2021): the cells' upper-triangular map, the correlated
  // Beckmann of the smooth cells and of the Gaussian sampler.
  struct Correlated {
    const char* name;
    SamplingCase::Kind kind;
    GlintSampler sampler;
    float logDensity, theta, rho;
  };
  for (const Correlated& r : {
           Correlated{"Mixture_rho0p6", SamplingCase::Kind::Glint, GlintSampler::Mixture, 21.0f, 45.0f, 0.6f},
           Correlated{"Mixture_rhoMinus0p9_sparse", SamplingCase::Kind::Glint, GlintSampler::Mixture, 15.0f, 30.0f, -0.9f},
           Correlated{"Mixture_rho0p7_dense", SamplingCase::Kind::Glint, GlintSampler::Mixture, 32.0f, 60.0f, 0.7f},
           Correlated{"Gaussian_rho0p5", SamplingCase::Kind::Glint, GlintSampler::Gaussian, 21.0f, 45.0f, 0.5f},
           Correlated{"CookTorrance_rhoMinus0p7", SamplingCase::Kind::CookTorrance, GlintSampler::Mixture, 21.0f, 45.0f,
                      -0.7f},
       }) {
    SamplingCase c;
    c.name = r.name;
    c.kind = r.kind;
    c.sampler = r.sampler;
    c.logDensity = r.logDensity;
    c.thetaDegrees = r.theta;
    c.rho = r.rho;
    cases.push_back(c);
  }
  // The GGX target (kernel/microfacet_targets.h): the cells' scale mixture, its smooth remainder
  // and the smooth GGX cells, sampled by the mixture sampler; GGX slopes for the Gaussian sampler
  // and Cook-Torrance. The masking does not enter the sampler or its pdf.
  struct Ggx {
    const char* name;
    SamplingCase::Kind kind;
    GlintSampler sampler;
    float alpha, logDensity, theta, rho;
    int ndf = kernel::GLINT_NDF_GGX;
    bool multipleScattering = false;
  };
  for (const Ggx& g : {
           Ggx{"Mixture_ggx_alpha0p1_density21_theta5", SamplingCase::Kind::Glint, GlintSampler::Mixture, 0.1f, 21.0f, 5.0f, 0.0f},
           Ggx{"Mixture_ggx_alpha0p25_density15_theta45", SamplingCase::Kind::Glint, GlintSampler::Mixture, 0.25f, 15.0f, 45.0f, 0.0f},
           Ggx{"Mixture_ggx_alpha0p25_density21_theta75", SamplingCase::Kind::Glint, GlintSampler::Mixture, 0.25f, 21.0f, 75.0f, 0.0f},
           Ggx{"Mixture_ggx_alpha0p6_density32_theta45", SamplingCase::Kind::Glint, GlintSampler::Mixture, 0.6f, 32.0f, 45.0f, 0.0f},
           Ggx{"Mixture_ggx_rho0p6", SamplingCase::Kind::Glint, GlintSampler::Mixture, 0.25f, 21.0f, 45.0f, 0.6f},
           Ggx{"Gaussian_ggx_alpha0p25_theta45", SamplingCase::Kind::Glint, GlintSampler::Gaussian, 0.25f, 21.0f, 45.0f, 0.0f},
           Ggx{"CookTorrance_ggx_alpha0p3_theta30", SamplingCase::Kind::CookTorrance, GlintSampler::Mixture, 0.3f, 21.0f, 30.0f, 0.0f},
           Ggx{"CookTorrance_ggx_alpha0p3_theta80", SamplingCase::Kind::CookTorrance, GlintSampler::Mixture, 0.3f, 21.0f, 80.0f, 0.0f},
           // With the multiple-scattering compensation: the cosine lobe drawn with probability
           // 1 - E(mu_o) and the mixture's pdf.
           Ggx{"Mixture_ggx_ms_alpha0p6_density21_theta45", SamplingCase::Kind::Glint, GlintSampler::Mixture, 0.6f, 21.0f, 45.0f, 0.0f, kernel::GLINT_NDF_GGX, true},
           Ggx{"Mixture_ggx_ms_alpha1_density32_theta75", SamplingCase::Kind::Glint, GlintSampler::Mixture, 1.0f, 32.0f, 75.0f, 0.0f, kernel::GLINT_NDF_GGX, true},
           Ggx{"Mixture_beckmann_ms_alpha0p6_density15_theta30", SamplingCase::Kind::Glint, GlintSampler::Mixture, 0.6f, 15.0f, 30.0f, 0.0f, kernel::GLINT_NDF_BECKMANN, true},
           Ggx{"CookTorrance_ggx_ms_alpha0p8_theta60", SamplingCase::Kind::CookTorrance, GlintSampler::Mixture, 0.8f, 21.0f, 60.0f, 0.0f, kernel::GLINT_NDF_GGX, true},
       }) {
    SamplingCase c;
    c.name = g.name;
    c.kind = g.kind;
    c.sampler = g.sampler;
    c.alpha = g.alpha;
    c.logDensity = g.logDensity;
    c.thetaDegrees = g.theta;
    c.rho = g.rho;
    c.ndf = g.ndf;
    c.multipleScattering = g.multipleScattering;
    cases.push_back(c);
  }
  for (float theta : {30.0f, 80.0f}) {
    SamplingCase c;
    c.name = "CookTorrance_alpha0p3_theta" + label(theta);
    c.kind = SamplingCase::Kind::CookTorrance;
    c.alpha = 0.3f;
    c.thetaDegrees = theta;
    cases.push_back(c);
  }
  struct Dielectric {
    const char* name;
    float alpha, logDensity, theta, eta, relativeArea;
    GlintSampler sampler;
  };
  for (const Dielectric& d : {
           Dielectric{"Dielectric_alpha0p1_outside30", 0.1f, 21.0f, 30.0f, 1.5f, 1.0f, GlintSampler::Mixture},
           Dielectric{"Dielectric_alpha0p25_outside75_sparse", 0.25f, 15.0f, 75.0f, 1.5f, 1.0f, GlintSampler::Mixture},
           Dielectric{"Dielectric_alpha0p6_outside30_dense", 0.6f, 32.0f, 30.0f, 1.5f, 1.0f, GlintSampler::Mixture},
           Dielectric{"Dielectric_alpha0p25_inside30", 0.25f, 21.0f, 150.0f, 1.5f, 1.0f, GlintSampler::Mixture},
           Dielectric{"Dielectric_alpha0p25_inside60_tir", 0.25f, 21.0f, 120.0f, 1.5f, 1.0f, GlintSampler::Mixture},
           Dielectric{"Dielectric_alpha0p25_eta0p67_outside45", 0.25f, 21.0f, 45.0f, 1.0f / 1.5f, 1.0f,
                      GlintSampler::Mixture},
           Dielectric{"Dielectric_alpha0p25_relativeArea0p5", 0.25f, 21.0f, 45.0f, 1.5f, 0.5f, GlintSampler::Mixture},
           Dielectric{"Dielectric_Gaussian_alpha0p25_outside45", 0.25f, 21.0f, 45.0f, 1.5f, 1.0f,
                      GlintSampler::Gaussian},
       }) {
    SamplingCase c;
    c.name = d.name;
    c.kind = SamplingCase::Kind::Dielectric;
    c.alpha = d.alpha;
    c.logDensity = d.logDensity;
    c.thetaDegrees = d.theta;
    c.eta = d.eta;
    c.relativeArea = d.relativeArea;
    c.sampler = d.sampler;
    cases.push_back(c);
  }
  // Footprint policies (glintPixelFootprint): the sampler walks the policy's levels and cells, as
  // the P-SDF does. cells=12 raises the case footprint's LOD from 4.2 past its two levels' 10 and 5
  // cells; with drop=0.5 a single level is left where the blend falls below one half.
  struct Policy {
    const char* name;
    float alpha, logDensity, theta;
    const char* policy;
  };
  for (const Policy& p : {
           Policy{"Mixture_cells12_alpha0p25_density21_theta45", 0.25f, 21.0f, 45.0f, "cells=12"},
           Policy{"Mixture_cells12_alpha0p1_density15_theta5", 0.1f, 15.0f, 5.0f, "cells=12"},
           Policy{"Mixture_cells16_drop0p5_alpha0p6_density32_theta75", 0.6f, 32.0f, 75.0f, "cells=16,drop=0.5"},
           Policy{"Mixture_cells24_aniso2_alpha0p25_density21_theta30", 0.25f, 21.0f, 30.0f, "aniso=2,cells=24"},
       }) {
    SamplingCase c;
    c.name = p.name;
    c.alpha = p.alpha;
    c.logDensity = p.logDensity;
    c.thetaDegrees = p.theta;
    c.footprintPolicy = footprintPolicyFromString(p.policy);
    cases.push_back(c);
  }
  // The consistent LOD construction: the sampler draws a block's complement marginal
  // (sampleDictionaryMarginal) and the parent's rotation, as the P-SDF reads them. Sparse (dictionary
  // levels near 0 and 1, where own cells at level 0 have no blocks), moderate, dense, GGX, masked
  // cells, a footprint policy, the dielectric. The tree LOD construction: the sampler draws the tree
  // table and the distributions that the cell's descent from its own cell chose, with the own cell's
  // rotation (method.md 2.8). At log density 15 and 21 the case footprint's levels (4 and 5) lie
  // below the own level (10 and 6), so its cells are blocks; at 32 the own level is 0 and every cell
  // is own; at 12, with relative area 0.3, the cells lie about nine levels below the own level
  // (13), where single lobes share out their coverage and sample() misses in the dark ones.
  struct Construction {
    const char* name;
    SamplingCase::Kind kind;
    float alpha, logDensity, theta, relativeArea;
    int ndf;
    const char* policy;
    int lod;
  };
  constexpr int kConsistent = kernel::GLINT_LOD_CONSISTENT, kTree = kernel::GLINT_LOD_TREE;
  for (const Construction& q : {
           Construction{"Mixture_consistent_alpha0p25_density15_theta45", SamplingCase::Kind::Glint, 0.25f, 15.0f, 45.0f, 1.0f, kernel::GLINT_NDF_BECKMANN, "", kConsistent},
           Construction{"Mixture_consistent_alpha0p1_density21_theta5", SamplingCase::Kind::Glint, 0.1f, 21.0f, 5.0f, 1.0f, kernel::GLINT_NDF_BECKMANN, "", kConsistent},
           Construction{"Mixture_consistent_alpha0p6_density32_theta75", SamplingCase::Kind::Glint, 0.6f, 32.0f, 75.0f, 1.0f, kernel::GLINT_NDF_BECKMANN, "", kConsistent},
           Construction{"Mixture_consistent_ggx_alpha0p25_density21_theta45", SamplingCase::Kind::Glint, 0.25f, 21.0f, 45.0f, 1.0f, kernel::GLINT_NDF_GGX, "", kConsistent},
           Construction{"Mixture_consistent_relativeArea0p5", SamplingCase::Kind::Glint, 0.25f, 21.0f, 45.0f, 0.5f, kernel::GLINT_NDF_BECKMANN, "", kConsistent},
           Construction{"Mixture_consistent_cells12_alpha0p25_density21_theta30", SamplingCase::Kind::Glint, 0.25f, 21.0f, 30.0f, 1.0f, kernel::GLINT_NDF_BECKMANN, "cells=12", kConsistent},
           Construction{"Dielectric_consistent_alpha0p25_outside45", SamplingCase::Kind::Dielectric, 0.25f, 21.0f, 45.0f, 1.0f, kernel::GLINT_NDF_BECKMANN, "", kConsistent},
           Construction{"Mixture_tree_alpha0p25_density15_theta45", SamplingCase::Kind::Glint, 0.25f, 15.0f, 45.0f, 1.0f, kernel::GLINT_NDF_BECKMANN, "", kTree},
           Construction{"Mixture_tree_alpha0p1_density21_theta5", SamplingCase::Kind::Glint, 0.1f, 21.0f, 5.0f, 1.0f, kernel::GLINT_NDF_BECKMANN, "", kTree},
           Construction{"Mixture_tree_alpha0p6_density32_theta75", SamplingCase::Kind::Glint, 0.6f, 32.0f, 75.0f, 1.0f, kernel::GLINT_NDF_BECKMANN, "", kTree},
           Construction{"Mixture_tree_ggx_alpha0p25_density21_theta45", SamplingCase::Kind::Glint, 0.25f, 21.0f, 45.0f, 1.0f, kernel::GLINT_NDF_GGX, "", kTree},
           Construction{"Dielectric_tree_alpha0p25_outside45", SamplingCase::Kind::Dielectric, 0.25f, 21.0f, 45.0f, 1.0f, kernel::GLINT_NDF_BECKMANN, "", kTree},
           Construction{"Mixture_tree_relativeArea0p3_density12", SamplingCase::Kind::Glint, 0.25f, 12.0f, 45.0f, 0.3f, kernel::GLINT_NDF_BECKMANN, "", kTree},
       }) {
    SamplingCase c;
    c.name = q.name;
    c.kind = q.kind;
    c.alpha = q.alpha;
    c.logDensity = q.logDensity;
    c.thetaDegrees = q.theta;
    c.relativeArea = q.relativeArea;
    c.ndf = q.ndf;
    if (*q.policy) c.footprintPolicy = footprintPolicyFromString(q.policy);
    c.lod = q.lod;
    cases.push_back(c);
  }
  return cases;
}

const int kChiSquareTests = static_cast<int>(chiSquareCases().size());
const double kSignificance = 1.0 - std::pow(1.0 - 0.01, 1.0 / kChiSquareTests);
// Samples per chi-square test: 2 x 10^5 keeps the file near 40 s on 2 cores (docs/sampling.md has
// the results at 10^6 too, from GLINT_CHI_SQUARE_SAMPLES=1000000).
const int kChiSquareSamples = std::getenv("GLINT_CHI_SQUARE_SAMPLES") ? std::atoi(std::getenv("GLINT_CHI_SQUARE_SAMPLES")) : 200000;

// The half vector's slope lies in this box wherever a glint or Beckmann pdf of roughness alpha can
// be non-zero (glintSlopeExtent: the dictionary's rotated, scaled support; Beckmann keeps under
// 1e-7 of its mass beyond it), with 1% to spare.
glm::dvec2 supportBox(float alpha, float rho = 0.0f) {
  return glm::dvec2(glintSlopeExtent(defaultDictionary(), glm::vec2(alpha), rho)) * 1.01;
}

// The quadrature's step in half-vector slope: a third of the dictionary's texel spacing
// 4 sigma_d / R, scaled by alpha / alpha_d, where glints are sparse. A level-0 lobe (std 0.02 in
// the dictionary's slopes) spans two texels (0.022 apart), so the interpolated marginals are tents
// whose kinks the midpoint rule must resolve. Dense glints (many overlapping lobes) and Beckmann
// are smooth: a texel spacing is enough.
double quadratureSlopeStep(const SamplingCase& c) {
  const DictionaryParameters& d = defaultDictionary().parameters();
  const double texel = static_cast<double>(d.texelSpacing()) * c.alpha / d.alpha;
  const bool spiky = c.kind != SamplingCase::Kind::CookTorrance && c.sampler == GlintSampler::Mixture &&
                     c.logDensity < 30.0f;
  return spiky ? texel / 3.0 : texel;
}

// ---------------------------------------------------------------------------------------------
// pdf normalisation: the integral of the pdf over the sphere (the chi-square quadrature) against
// the visible mass in the slope plane, integral of D_wo(m) over the normals whose reflection (or
// refraction) stays valid. With relative area 1 and no loss below the horizon it is 1; masked cells
// take their share away; grazing views lose what reflects below the horizon.

// Integral over the slope plane of D_wo(m) dm = G1(wo, m) <wo, m> P22(s) / (m.z wo.z) ds, each
// normal weighted by `valid(m)` (the probability that its scattering is returned): midpoints
// slopeStep apart over glintSlopeExtent (sparse glints need a third of a texel: 200 x 200 points,
// a texel apart, were off by 4e-3 on alpha 0.25, log density 15).
double visibleMass(const std::function<double(glm::vec2)>& p22, glm::vec3 wo, glm::vec2 extent, double slopeStep,
                   const std::function<double(glm::vec3)>& valid) {
  const glm::vec3 up = wo.z > 0.0f ? wo : -wo;
  return integrateOverSlopes(
      [&](glm::vec2 slope) {
        const glm::vec3 m = sampling::normalFromSlope(slope);
        const double c = glm::dot(up, m);
        if (c <= 0.0) return 0.0;
        const double weight = valid(m);
        if (weight == 0.0) return 0.0;
        return weight * kernel::glintVCavityG1(up, m) * c * p22(slope) / (m.z * up.z);
      },
      extent, static_cast<int>(std::ceil(2.0 * std::max(extent.x, extent.y) / slopeStep)));
}

class SamplingStat : public ::testing::TestWithParam<int> {};

TEST_P(SamplingStat, ChiSquareAgainstOwnPdf) {
  const int index = GetParam();
  const SamplingCase c = chiSquareCases()[static_cast<std::size_t>(index)];
  const glm::vec3 wo = caseWo(c, index);
  const SurfaceFootprint footprint = caseFootprint(index);
  const GlintParameters parameters = caseParameters(c);
  const std::uint64_t seed = 1000u + static_cast<std::uint64_t>(index);
  Quadrature quadrature;
  // GGX, or the compensation's cosine lobe: the whole plane in effect (GGX keeps 1e-8 of its mass
  // beyond 1e4 alpha), the step growing from 4 alpha out (CellIntegrator).
  const bool ggx = c.ndf == kernel::GLINT_NDF_GGX || c.multipleScattering;
  quadrature.box = ggx ? glm::dvec2(1e4 * c.alpha) : supportBox(c.alpha, c.rho);
  quadrature.stepGrowth = ggx ? 1.0 / (4.0 * c.alpha) : 0.0;
  quadrature.slopeStep = quadratureSlopeStep(c);
  quadrature.slopeOf = reflectionSlope(wo);
  ChiSquareResult result;
  double mass = 0.0;  // the visible mass in the slope plane
  const glm::vec2 extent = glintSlopeExtent(defaultDictionary(), parameters.alpha, parameters.rho);
  const GlintBsdf microfacets(defaultDictionary(), parameters, footprint, Fresnel::none(), Spectrum(1.0f), c.sampler);
  const std::function<double(glm::vec2)> p22 = [&](glm::vec2 slope) {
    return c.sampler == GlintSampler::Gaussian || c.kind == SamplingCase::Kind::CookTorrance
               ? static_cast<double>(kernel::glintTargetP22(c.ndf, slope, parameters.alpha, parameters.rho))
               : static_cast<double>(microfacets.p22(slope));
  };
  const auto reflectionValid = [&](glm::vec3 m) { return glm::reflect(-wo, m).z * wo.z > 0.0f ? 1.0 : 0.0; };
  if (c.kind == SamplingCase::Kind::Glint) {
    result = runChiSquare([&](float uc, glm::vec2 u) { return microfacets.sample(wo, uc, u); },
                          [&](glm::vec3 wi) { return microfacets.pdf(wo, wi); }, quadrature, kChiSquareSamples, seed);
    if (!ggx) mass = visibleMass(p22, wo, extent, quadrature.slopeStep, reflectionValid);
  } else if (c.kind == SamplingCase::Kind::CookTorrance) {
    const CookTorranceBsdf bsdf(glm::vec2(c.alpha), c.rho, Fresnel::none(), Spectrum(1.0f), microfacetTarget(parameters));
    result = runChiSquare([&](float uc, glm::vec2 u) { return bsdf.sample(wo, uc, u); },
                          [&](glm::vec3 wi) { return bsdf.pdf(wo, wi); }, quadrature, kChiSquareSamples, seed);
    if (!ggx) mass = visibleMass(p22, wo, extent, quadrature.slopeStep, reflectionValid);
  } else {
    const GlintDielectricBsdf bsdf(defaultDictionary(), parameters, footprint, c.eta, c.sampler);
    quadrature.slopeOf = dielectricSlope(wo, c.eta);
    result = runChiSquare([&](float uc, glm::vec2 u) { return bsdf.sample(wo, uc, u); },
                          [&](glm::vec3 wi) { return bsdf.pdf(wo, wi); }, quadrature, kChiSquareSamples, seed);
    // Reflection with probability F, refraction with 1 - F, each returned only if it leaves on the
    // side it must.
    mass = visibleMass(p22, wo, extent, quadrature.slopeStep, [&](glm::vec3 m) {
      const double fresnel = sampling::fresnelDielectric(glm::dot(wo, m), c.eta);
      const std::optional<glm::vec3> t = sampling::refractDirection(wo, m, c.eta);
      return reflectionValid(m) * fresnel + (t && t->z * wo.z < 0.0f ? 1.0 - fresnel : 0.0);
    });
  }
  std::printf("chi2 %-40s stat %8.1f dof %5d p %.4f | pdf integral %.5f, visible mass %.5f, empty %.5f\n",
              c.name.c_str(), result.statistic, result.dof, result.pValue, result.pdfIntegral, mass,
              result.emptyFraction);
  RecordProperty("p_value", std::to_string(result.pValue));
  EXPECT_TRUE(result.problem.empty()) << result.problem;
  EXPECT_GT(result.dof, 20);  // the test has bins to compare
  EXPECT_GT(result.pValue, kSignificance) << "statistic " << result.statistic << ", dof " << result.dof
                                          << ", Sidak-corrected significance " << kSignificance;
  // pdf normalisation: the sphere quadrature of pdf() (solid angle measured directly, no Jacobian)
  // equals the visible mass in the slope plane (none of pdf()'s own arithmetic) within 2e-3 (both
  // quadratures' errors; seen below 5e-4). Seen from near the normal with relative area 1 and
  // alpha <= 0.25 nothing reflects below the horizon: the mass is the P-NDF's, 1.
  // GGX's visible mass (and the compensation's) is not computed here (its slope-plane grid would
  // have to reach 1e4 alpha): the empty samples are compared with what the sphere quadrature of
  // pdf() lacks instead.
  if (!ggx) EXPECT_NEAR(result.pdfIntegral, mass, 2e-3);
  if (c.kind != SamplingCase::Kind::Dielectric && c.relativeArea == 1.0f && c.thetaDegrees < 10.0f &&
      c.alpha <= 0.25f && !ggx) {
    EXPECT_NEAR(result.pdfIntegral, 1.0, 2e-3);
  }
  // The samples that come back empty are the mass the pdf lacks (sampling error: 5 standard errors).
  const double missing = 1.0 - (ggx ? result.pdfIntegral : mass);
  EXPECT_NEAR(result.emptyFraction, missing,
              5.0 * std::sqrt(std::max(missing * (1.0 - missing), 1e-6) / kChiSquareSamples) + 2e-3);
}

INSTANTIATE_TEST_SUITE_P(, SamplingStat, ::testing::Range(0, static_cast<int>(chiSquareCases().size())),
                         [](const ::testing::TestParamInfo<int>& info) {
                           return chiSquareCases()[static_cast<std::size_t>(info.param)].name;
                         });

// ---------------------------------------------------------------------------------------------
// Exact properties (Sampling).

TEST(Sampling, EverySampleCarriesFAndPdfAndItsWeight) {
  // 400 random materials, footprints (magnified to minified), view directions down to 88 degrees
  // (and from inside, for the dielectric), conductor Fresnel and colour, both samplers; 64 samples
  // each. For every sample: pdf > 0 and finite; f and pdf equal f(wo, wi) and pdf(wo, wi) (the
  // same arithmetic: 1e-6 relative); weight = f |cos| / pdf within 1e-3 relative (seen below
  // 1e-6; a weight that forgot the cosine or a mixture's pdf is off by far more). Both smooth targets, both maskings, with and without the
  // multiple-scattering lobe, drawn from a stream of their own (the other draws are those of the
  // Beckmann-only cases before).
  Pcg32 rng(77, 11);
  Pcg32 targets(77, 12);
  int checked = 0;
  int empty = 0;
  double worstWeight = 0.0;
  auto relative = [](double a, double b) { return std::abs(a - b) / std::max({std::abs(a), std::abs(b), 1e-30}); };
  for (int i = 0; i < 400; ++i) {
    GlintParameters parameters = defaultGlintParameters();
    parameters.alpha = glm::vec2(uniform(rng, 0.03f, 1.0f), uniform(rng, 0.03f, 1.0f));
    parameters.logDensity = uniform(rng, 12.0f, 40.0f);
    parameters.relativeArea = rng.nextBelow(3) == 0 ? uniform(rng, 0.2f, 1.0f) : 1.0f;
    parameters.patternSeed = rng.nextBelow(8);
    parameters.ndf = static_cast<int>(targets.nextBelow(2));
    parameters.masking = static_cast<int>(targets.nextBelow(2));
    parameters.multipleScattering = targets.nextBelow(2) == 0;
    const SurfaceFootprint footprint = randomFootprint(rng, 1e-5f, 3e-2f);
    const GlintSampler sampler = rng.nextBelow(2) == 0 ? GlintSampler::Mixture : GlintSampler::Gaussian;
    const int kind = static_cast<int>(rng.nextBelow(3));  // glint, Cook-Torrance, dielectric
    glm::vec3 wo = directionAt(uniform(rng, 0.0f, glm::radians(88.0f)), uniform(rng, 0.0f, 6.2832f));
    if (kind == 2 && rng.nextBelow(2) == 0) wo.z = -wo.z;
    const Fresnel fresnel = Fresnel::conductor(Spectrum(0.2f, 0.9f, 1.1f), Spectrum(3.9f, 2.4f, 2.2f));
    const Spectrum colour(0.9f, 0.6f, 0.3f);
    const float eta = std::array<float, 4>{1.33f, 1.5f, 2.4f, 1.0f / 1.5f}[rng.nextBelow(4)];
    const GlintBsdf glint(defaultDictionary(), parameters, footprint, fresnel, colour, sampler);
    const CookTorranceBsdf cookTorrance(parameters.alpha, parameters.rho, fresnel, colour, microfacetTarget(parameters));
    const GlintDielectricBsdf dielectric(defaultDictionary(), parameters, footprint, eta, sampler);
    for (int k = 0; k < 64; ++k) {
      const float uChoice = unitFloat(rng);
      const glm::vec2 u(unitFloat(rng), unitFloat(rng));
      std::optional<BsdfSample> s;
      Spectrum f(0.0f);
      float pdf = 0.0f;
      if (kind == 0) {
        s = glint.sample(wo, uChoice, u);
        if (s) f = glint.f(wo, s->wi), pdf = glint.pdf(wo, s->wi);
      } else if (kind == 1) {
        s = cookTorrance.sample(wo, uChoice, u);
        if (s) f = cookTorrance.f(wo, s->wi), pdf = cookTorrance.pdf(wo, s->wi);
      } else {
        s = dielectric.sample(wo, uChoice, u);
        if (s) f = dielectric.f(wo, s->wi), pdf = dielectric.pdf(wo, s->wi);
      }
      if (!s) {
        ++empty;
        continue;
      }
      ++checked;
      ASSERT_TRUE(s->pdf > 0.0f && std::isfinite(s->pdf)) << "case " << i << " sample " << k;
      ASSERT_NEAR(glm::length(s->wi), 1.0f, 1e-5f);
      ASSERT_LE(relative(s->pdf, pdf), 1e-6) << "case " << i << " sample " << k;
      EXPECT_EQ(s->transmission, kind == 2 && s->wi.z * wo.z < 0.0f);
      for (int channel = 0; channel < 3; ++channel) {
        ASSERT_TRUE(std::isfinite(s->weight[channel]));
        ASSERT_LE(relative(s->f[channel], f[channel]), 1e-6) << "case " << i << " sample " << k;
        const double expected = static_cast<double>(f[channel]) * std::abs(s->wi.z) / pdf;
        const double error = relative(s->weight[channel], expected);
        worstWeight = std::max(worstWeight, error);
        ASSERT_LE(error, 1e-3) << "case " << i << " sample " << k << " channel " << channel;
      }
    }
  }
  std::printf("%d samples checked (%d came back empty); largest relative weight error %.2e\n", checked, empty,
              worstWeight);
  EXPECT_GT(checked, 20000);
}

TEST(Sampling, MaskedCellsTakeAwayExactlyTheirMass) {
  // With relative area 0.5 a cell holds microfacets with probability 1/2, and sample() returns
  // nothing when it picks one that has none. Whether it does depends on uChoice alone (the LOD,
  // then the cell), so sweeping uChoice over 2^16 stratified values measures the missing mass to
  // about the number of cells / 2^16; viewed from the normal with alpha 0.1 nothing can reflect
  // below the horizon. It must equal 1 - integral of P22_P (slope quadrature, error under 2e-4).
  // Under the tree construction a cell's microfacets cover a share of it (its coverage, method.md
  // 2.8), which sample() takes by uChoice too: at log density 15 the footprint's cells lie about
  // seven levels below the own level (11), where single lobes share out relative area 0.3 unevenly.
  GlintParameters parameters = defaultGlintParameters();
  parameters.alpha = glm::vec2(0.1f);
  const glm::vec3 wo(0.0f, 0.0f, 1.0f);
  constexpr int kSweep = 1 << 16;
  struct Layer {
    int lod;
    float logDensity;
    std::vector<float> relativeAreas;
  };
  for (const Layer& layer : {Layer{kernel::GLINT_LOD_PAPER, 21.0f, {0.5f, 1.0f}},
                             Layer{kernel::GLINT_LOD_TREE, 15.0f, {0.3f, 1.0f}}}) {
    parameters.lod = layer.lod;
    parameters.logDensity = layer.logDensity;
    for (int position = 0; position < 4; ++position) {
      const SurfaceFootprint footprint = caseFootprint(300 + position);
      for (float relativeArea : layer.relativeAreas) {
        parameters.relativeArea = relativeArea;
        const GlintBsdf bsdf(defaultDictionary(), parameters, footprint);
        int missing = 0;
        for (int i = 0; i < kSweep; ++i) {
          missing += !bsdf.sample(wo, (i + 0.5f) / kSweep, glm::vec2(0.3f, 0.7f)).has_value();
        }
        const double mass = integrateOverSlopes([&](glm::vec2 s) { return static_cast<double>(bsdf.p22(s)); },
                                                glintSlopeExtent(defaultDictionary(), parameters.alpha), 400);
        const double missingFraction = static_cast<double>(missing) / kSweep;
        std::printf("lod %d, position %d, relative area %.1f: missing %.5f, 1 - integral of P22 %.5f\n", layer.lod,
                    position, relativeArea, missingFraction, 1.0 - mass);
        EXPECT_NEAR(missingFraction, 1.0 - mass, 1e-3);
        if (relativeArea == 1.0f) EXPECT_EQ(missing, 0);
      }
    }
  }
}

TEST(Sampling, DictionaryMarginalInversionMatchesItsCdf) {
  // x = sampleDictionaryMarginal(u) must satisfy CDF(x) = u for the kernel's interpolated marginal
  // (CDF by a 20000-step trapezoid rule of Dictionary::marginal over [-4 sigma_d, x], normalised:
  // 1e-5 accurate for these piecewise-linear functions), at every level, within 1e-4.
  const Dictionary& dictionary = defaultDictionary();
  const float domain = dictionary.parameters().slopeDomain();
  auto cdf = [&](int level, int distribution, float x) {
    constexpr int kSteps = 20000;
    auto integral = [&](float to) {
      const double h = (static_cast<double>(to) + domain) / kSteps;
      double sum = 0.0;
      for (int k = 0; k <= kSteps; ++k) {
        const double weight = (k == 0 || k == kSteps) ? 0.5 : 1.0;
        sum += weight * dictionary.marginal(level, distribution, static_cast<float>(-domain + k * h));
      }
      return sum * h;
    };
    return integral(x) / integral(domain);
  };
  double worst = 0.0;
  for (int level : {0, 3, 8, 15}) {
    for (int distribution : {0, 77, 191}) {
      float previous = -domain;
      for (float u : {0.01f, 0.1f, 0.25f, 0.4f, 0.49f, 0.5f, 0.51f, 0.6f, 0.75f, 0.9f, 0.99f}) {
        const float x = sampling::sampleDictionaryMarginal(dictionary.view(), level, distribution, 0, u);
        EXPECT_GE(x, previous);
        EXPECT_LT(std::abs(x), domain);
        previous = x;
        const double error = std::abs(cdf(level, distribution, x) - u);
        worst = std::max(worst, error);
        EXPECT_LT(error, 1e-4) << "level " << level << " distribution " << distribution << " u " << u;
      }
    }
  }
  RecordProperty("worst_cdf_error", std::to_string(worst));
}

TEST(Sampling, GaussianSamplerIsCookTorrancesAndMixtureTendsToIt) {
  // The Gaussian sampler draws the same Beckmann visible normals as Cook-Torrance: same wi, same
  // pdf for the same random numbers. At log density 80 every cell is in the smooth limit, so the
  // mixture's pdf is Cook-Torrance's too (1e-4: float rounding of the two NDF paths).
  Pcg32 rng(5, 8);
  for (int i = 0; i < 2000; ++i) {
    GlintParameters parameters = defaultGlintParameters();
    parameters.alpha = glm::vec2(uniform(rng, 0.05f, 1.0f), uniform(rng, 0.05f, 1.0f));
    parameters.logDensity = 80.0f;
    const SurfaceFootprint footprint = randomFootprint(rng, 1e-5f, 1e-2f);
    const glm::vec3 wo = directionAt(uniform(rng, 0.0f, 1.5f), uniform(rng, 0.0f, 6.28f));
    const CookTorranceBsdf cookTorrance(parameters.alpha);
    const GlintBsdf gaussian(defaultDictionary(), parameters, footprint, Fresnel::none(), Spectrum(1.0f),
                             GlintSampler::Gaussian);
    const GlintBsdf mixture(defaultDictionary(), parameters, footprint);
    const float uChoice = unitFloat(rng);
    const glm::vec2 u(unitFloat(rng), unitFloat(rng));
    const std::optional<BsdfSample> a = cookTorrance.sample(wo, uChoice, u);
    const std::optional<BsdfSample> b = gaussian.sample(wo, uChoice, u);
    ASSERT_EQ(a.has_value(), b.has_value()) << "case " << i;
    if (!a) continue;
    ASSERT_EQ(a->wi, b->wi);
    ASSERT_NEAR(a->pdf, b->pdf, 1e-6f * a->pdf);
    ASSERT_NEAR(a->weight.x, b->weight.x, 1e-4f * a->weight.x + 1e-7f);
    ASSERT_NEAR(mixture.pdf(wo, a->wi), a->pdf, 1e-4f * a->pdf);
  }
}

TEST(Sampling, DielectricTransmissionIsReciprocalUpToTheIndicesSquared) {
  // Radiance BTDF (Walter et al. 2007, Eq. 21): f(wo, wi) / n_wo^2 = f(wi, wo) / n_wi^2; reflection
  // is plainly reciprocal. The two directions compute the half vector with different float
  // roundings, which the glint lobes (0.04 alpha wide in slope) amplify: 1e-3 relative (seen 1.5e-4).
  Pcg32 rng(21, 3);
  int transmitted = 0;
  float worst = 0.0f;
  for (int i = 0; i < 4000; ++i) {
    GlintParameters parameters = defaultGlintParameters();
    parameters.alpha = glm::vec2(uniform(rng, 0.1f, 0.8f));
    parameters.logDensity = uniform(rng, 15.0f, 35.0f);
    const float eta = uniform(rng, 1.2f, 2.0f);
    const GlintDielectricBsdf bsdf(defaultDictionary(), parameters, randomFootprint(rng, 1e-4f, 1e-2f), eta);
    glm::vec3 wo = directionAt(uniform(rng, 0.0f, 1.5f), uniform(rng, 0.0f, 6.28f));
    if (rng.nextBelow(2) == 0) wo.z = -wo.z;
    const std::optional<BsdfSample> s = bsdf.sample(wo, unitFloat(rng), glm::vec2(unitFloat(rng), unitFloat(rng)));
    if (!s) continue;
    const float nWo = wo.z > 0.0f ? 1.0f : eta;
    const float nWi = s->wi.z > 0.0f ? 1.0f : eta;
    const float forward = bsdf.f(wo, s->wi).x / (nWo * nWo);
    const float backward = bsdf.f(s->wi, wo).x / (nWi * nWi);
    ASSERT_NEAR(forward, backward, 1e-3f * std::max(forward, backward)) << "case " << i;
    worst = std::max(worst, std::abs(forward - backward) / std::max(forward, backward));
    transmitted += s->transmission && forward > 0.0f;
  }
  EXPECT_GT(transmitted, 1000);
  std::printf("largest relative difference %.2e\n", worst);
}

TEST(Sampling, DielectricRejectsIndicesOutOfRange) {
  for (float eta : {1.0f, 0.1f, 7.0f, std::nanf("")}) {
    try {
      GlintDielectricBsdf(defaultDictionary(), defaultGlintParameters(), SurfaceFootprint{}, eta);
      ADD_FAILURE() << "eta " << eta << " accepted";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("eta"), std::string::npos) << e.what();
    }
  }
}

// ---------------------------------------------------------------------------------------------
// White furnace (F = 1): the directional albedo as the mean sample weight (empty samples count 0)
// against deterministic quadrature, within 1%.

struct Estimate {
  double mean;
  double standardError;
};

Estimate meanWeight(const SampleFunction& sample, int sampleCount, std::uint64_t seed) {
  const int chunks = (sampleCount + kChunk - 1) / kChunk;
  std::vector<std::pair<double, double>> sums(static_cast<std::size_t>(chunks));
  tbb::parallel_for(0, chunks, [&](int c) {
    Pcg32 rng(seed, static_cast<std::uint64_t>(c));
    double sum = 0.0;
    double sum2 = 0.0;
    for (int i = c * kChunk; i < std::min(sampleCount, (c + 1) * kChunk); ++i) {
      const float uChoice = unitFloat(rng);
      const glm::vec2 u(unitFloat(rng), unitFloat(rng));
      const std::optional<BsdfSample> s = sample(uChoice, u);
      const double w = s ? s->weight.x : 0.0;
      sum += w;
      sum2 += w * w;
    }
    sums[static_cast<std::size_t>(c)] = {sum, sum2};
  });
  double sum = 0.0;
  double sum2 = 0.0;
  for (const auto& [a, b] : sums) sum += a, sum2 += b;
  const double mean = sum / sampleCount;
  const double variance = std::max(0.0, sum2 / sampleCount - mean * mean);
  return {mean, std::sqrt(variance / sampleCount)};
}

TEST_F(SamplingStat, WhiteFurnaceBySamplingMatchesQuadrature) {
  // The glint BRDF at alpha 0.1, 0.25, 0.6 and 0, 45, 75 degrees (log density 21, about 2000
  // microfacets in the footprint) and once with relative area 0.5: the mixture sampler's mean
  // weight (10^5 samples) against the slope-plane quadrature of test_support (directionalAlbedo),
  // and the Gaussian sampler's (4 x 10^5 samples; its weights vary far more) on four of them. Each
  // must be within 1%, with a standard error under 0.3% for that to mean something.
  constexpr int kMixtureSamples = 100000;
  constexpr int kGaussianSamples = 400000;
  int index = 0;
  for (float alpha : {0.1f, 0.25f, 0.6f}) {
    for (float theta : {0.0f, 45.0f, 75.0f}) {
      for (float relativeArea : {1.0f, 0.5f}) {
        if (relativeArea != 1.0f && !(alpha == 0.25f && theta == 45.0f)) continue;
        ++index;
        GlintParameters parameters = defaultGlintParameters();
        parameters.alpha = glm::vec2(alpha);
        parameters.logDensity = 21.0f;
        parameters.relativeArea = relativeArea;
        const SurfaceFootprint footprint = caseFootprint(400 + index);
        const glm::vec3 wo = directionAt(glm::radians(theta), 0.4f + static_cast<float>(index));
        const GlintBsdf mixture(defaultDictionary(), parameters, footprint);
        const double reference = directionalAlbedo(mixture, wo, parameters.alpha, 200);
        const Estimate m =
            meanWeight([&](float uc, glm::vec2 u) { return mixture.sample(wo, uc, u); }, kMixtureSamples, 7000u + index);
        std::printf("furnace alpha %.2f theta %2.0f area %.1f: quadrature %.5f | mixture %.5f +- %.5f (%+.2f%%)", alpha,
                    theta, relativeArea, reference, m.mean, m.standardError, 100.0 * (m.mean / reference - 1.0));
        EXPECT_NEAR(m.mean / reference, 1.0, 0.01);
        EXPECT_LT(m.standardError / reference, 0.003);
        if (relativeArea == 1.0f && (theta == 45.0f || (alpha == 0.25f && theta == 75.0f))) {
          const GlintBsdf gaussian(defaultDictionary(), parameters, footprint, Fresnel::none(), Spectrum(1.0f),
                                   GlintSampler::Gaussian);
          const Estimate g = meanWeight([&](float uc, glm::vec2 u) { return gaussian.sample(wo, uc, u); },
                                        kGaussianSamples, 8000u + index);
          std::printf(" | Gaussian %.5f +- %.5f (%+.2f%%)", g.mean, g.standardError, 100.0 * (g.mean / reference - 1.0));
          EXPECT_NEAR(g.mean / reference, 1.0, 0.01);
          EXPECT_LT(g.standardError / reference, 0.003);
        }
        std::printf("\n");
      }
    }
  }
}

TEST_F(SamplingStat, DielectricWhiteFurnaceBySamplingMatchesQuadrature) {
  // The glittering dielectric (eta 1.5, alpha 0.25, log density 21) seen from outside and from
  // inside: mean weight of 10^5 samples against the sphere quadrature of f |cos| (the chi-square
  // quadrature with f |cos| in place of the pdf), within 1%. The radiance BTDF carries
  // (n_wo / n_wi)^2, so the value is not an albedo from inside.
  int index = 0;
  for (float theta : {30.0f, 70.0f, 150.0f}) {
    ++index;
    SamplingCase c;
    c.kind = SamplingCase::Kind::Dielectric;
    c.alpha = 0.25f;
    c.thetaDegrees = theta;
    const GlintParameters parameters = caseParameters(c);
    const glm::vec3 wo = caseWo(c, 500 + index);
    const GlintDielectricBsdf bsdf(defaultDictionary(), parameters, caseFootprint(500 + index), c.eta);
    double reference = 0.0;
    for (double v : binIntegrals([&](glm::vec3 wi) { return bsdf.f(wo, wi).x * std::abs(wi.z); },
                                 dielectricSlope(wo, c.eta), supportBox(c.alpha), SphereBins{}, quadratureSlopeStep(c))) {
      reference += v;
    }
    const Estimate e = meanWeight([&](float uc, glm::vec2 u) { return bsdf.sample(wo, uc, u); }, 100000, 9000u + index);
    std::printf("dielectric furnace theta %.0f: quadrature %.5f | sampled %.5f +- %.5f (%+.2f%%)\n", theta, reference,
                e.mean, e.standardError, 100.0 * (e.mean / reference - 1.0));
    EXPECT_NEAR(e.mean / reference, 1.0, 0.01);
    EXPECT_LT(e.standardError / reference, 0.0025);
  }
}

}  // namespace
}  // namespace glint
