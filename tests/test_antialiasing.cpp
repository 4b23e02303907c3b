// The anti-aliasing extension (Chermain et al. 2021, kernel/glint_antialiasing.h): slope
// correlation, the dictionary's mip chain, the filtered marginals and the filtered P-SDF.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>

#include <gtest/gtest.h>

#include "glint/error.h"
#include "glint/kernel/normal_map_filtering.h"
#include "scene/builtin_scenes.h"
#include "scene/normal_map_moments.h"
#include "test_support.h"
#include "trace/texture.h"

namespace glint {
namespace {

using namespace glint::test;

kernel::GlintDictionaryView dictionaryView() { return defaultDictionary().view(); }

GlintParameters correlated(glm::vec2 alpha, float rho, float logDensity) {
  GlintParameters p = defaultGlintParameters();
  p.alpha = alpha;
  p.rho = rho;
  p.logDensity = logDensity;
  return p;
}

// ---- Slope correlation ------------------------------------------------------------------------

TEST(SlopeCorrelation, RhoZeroIsThe2020ScalingBitForBit) {
  // The 2020 model's map: slope * alpha_d / alpha, its inverse and Jacobian alpha_d^2 / (ax ay).
  const kernel::GlintDictionaryView dict = dictionaryView();
  Pcg32 rng(16, 1);
  for (int i = 0; i < 10000; ++i) {
    const GlintParameters p = correlated(glm::vec2(uniform(rng, 0.01f, 2.0f), uniform(rng, 0.01f, 2.0f)), 0.0f, 20.0f);
    const glm::vec2 slope(uniform(rng, -5.0f, 5.0f), uniform(rng, -5.0f, 5.0f));
    const glm::vec2 expected = slope * (glm::vec2(dict.alpha) / p.alpha);
    ASSERT_EQ(kernel::glintUnscaledSlope(dict, p, slope), expected) << "case " << i;
    ASSERT_EQ(kernel::glintScaledSlope(dict, p, slope), slope * (p.alpha / dict.alpha)) << "case " << i;
    ASSERT_EQ(kernel::glintScalingJacobian(dict, p), (dict.alpha * dict.alpha) / (p.alpha.x * p.alpha.y));
  }
}

// The cell map M (glintScaledSlope) as a matrix, read off the images of the unit vectors.
glm::dmat2 cellMap(const kernel::GlintDictionaryView& dict, const GlintParameters& p) {
  return glm::dmat2(glm::dvec2(kernel::glintScaledSlope(dict, p, {1.0f, 0.0f})),
                    glm::dvec2(kernel::glintScaledSlope(dict, p, {0.0f, 1.0f})));
}

TEST(SlopeCorrelation, CellMapCarriesTheFullCovariance) {
  // sigma_d^2 M M^T = [[sx^2, rho sx sy], [rho sx sy, sy^2]] (Eq. 18), det(M^-1) is the Jacobian,
  // and M^-1 inverts M.
  const kernel::GlintDictionaryView dict = dictionaryView();
  const double sigmaD = dict.alpha / std::sqrt(2.0);
  Pcg32 rng(16, 2);
  for (int i = 0; i < 1000; ++i) {
    const GlintParameters p =
        correlated(glm::vec2(uniform(rng, 0.02f, 1.5f), uniform(rng, 0.02f, 1.5f)), uniform(rng, -0.99f, 0.99f), 20.0f);
    const glm::dmat2 m = cellMap(dict, p);
    const glm::dmat2 covariance = sigmaD * sigmaD * m * glm::transpose(m);
    const double sx = p.alpha.x / std::sqrt(2.0);
    const double sy = p.alpha.y / std::sqrt(2.0);
    EXPECT_NEAR(covariance[0][0], sx * sx, 1e-5 * sx * sx) << "case " << i;
    EXPECT_NEAR(covariance[1][1], sy * sy, 1e-5 * sy * sy) << "case " << i;
    EXPECT_NEAR(covariance[1][0], p.rho * sx * sy, 1e-5 * sx * sy) << "case " << i;
    EXPECT_NEAR(covariance[0][1], covariance[1][0], 1e-6 * sx * sy);
    EXPECT_NEAR(1.0 / glm::determinant(m), kernel::glintScalingJacobian(dict, p),
                2e-5 * kernel::glintScalingJacobian(dict, p));
    const glm::vec2 slope(uniform(rng, -2.0f, 2.0f), uniform(rng, -2.0f, 2.0f));
    const glm::vec2 back = kernel::glintScaledSlope(dict, p, kernel::glintUnscaledSlope(dict, p, slope));
    // x comes back through slope.x - rho (alpha_x / alpha_y) slope.y, a difference of terms up to
    // 75 times |slope.y| here (alpha from 0.02 to 1.5): float rounding is relative to them.
    const float cancelled = std::abs(p.rho) * (p.alpha.x / p.alpha.y) * std::abs(slope.y);
    EXPECT_NEAR(back.x, slope.x, 1e-5f * (1.0f + std::abs(slope.x) + cancelled)) << "case " << i;
    EXPECT_NEAR(back.y, slope.y, 1e-5f * (1.0f + std::abs(slope.y))) << "case " << i;
  }
}

TEST(SlopeCorrelation, CorrelatedBeckmannIsTheGaussianOfItsCovariance) {
  Pcg32 rng(16, 3);
  for (int i = 0; i < 1000; ++i) {
    const glm::vec2 alpha(uniform(rng, 0.05f, 1.0f), uniform(rng, 0.05f, 1.0f));
    const float rho = uniform(rng, -0.99f, 0.99f);
    const glm::vec2 slope = glm::vec2(uniform(rng, -2.0f, 2.0f), uniform(rng, -2.0f, 2.0f)) * alpha;
    // The bivariate normal density written out in double, independently of the kernel's form.
    const double sx = alpha.x / std::sqrt(2.0), sy = alpha.y / std::sqrt(2.0);
    const double zx = slope.x / sx, zy = slope.y / sy;
    const double q = (zx * zx - 2.0 * rho * zx * zy + zy * zy) / (1.0 - rho * rho);
    const double expected = std::exp(-0.5 * q) / (2.0 * std::numbers::pi * sx * sy * std::sqrt(1.0 - rho * rho));
    // Relative 1e-4 where the density matters (above 1e-6 of its peak, where float's rounding of
    // the exponent's argument stays below that).
    const double floor = 1e-6 / (2.0 * std::numbers::pi * sx * sy * std::sqrt(1.0 - rho * rho));
    EXPECT_NEAR(kernel::glintBeckmannP22(slope, alpha, rho), expected, 2e-5 * expected + floor) << "case " << i;
    EXPECT_NEAR(kernel::glintGaussianSlopeP22(slope, kernel::glintBeckmannSlopeCovariance(alpha, rho)), expected,
                1e-4 * expected + floor)
        << "case " << i;
  }
  // And it integrates to 1 at a strong correlation.
  const glm::vec2 alpha(0.3f, 0.6f);
  EXPECT_NEAR(integrateOverSlopes([&](glm::vec2 s) { return kernel::glintBeckmannP22(s, alpha, -0.95f); }, 6.0f * alpha, 800),
              1.0, 1e-3);
}

TEST(SlopeCorrelationStat, MeanOverCellsConvergesToTheCorrelatedBeckmann) {
  // At moderate density each position shows glints; the mean of the P-NDF over 20000 random
  // positions must match the correlated Beckmann within 2% (as the uncorrelated model is tested,
  // GlintBrdfStat.MeanOverPositionsIsBeckmannAtModerateDensity), and must not match the
  // uncorrelated one where the correlation matters.
  const glm::vec2 alpha(0.3f, 0.5f);
  const float rho = 0.7f;
  const GlintParameters parameters = correlated(alpha, rho, 22.0f);
  const CookTorranceBsdf target(alpha, rho);
  const CookTorranceBsdf uncorrelated(alpha, 0.0f);
  for (glm::vec2 slopeOverAlpha : {glm::vec2(0.0f), glm::vec2(0.5f, 0.5f), glm::vec2(-0.4f, 0.6f)}) {
    const glm::vec3 m = glm::normalize(glm::vec3(-slopeOverAlpha * alpha, 1.0f));
    const double mean = meanNdfOverPositions(parameters, m, 20000, 5);
    EXPECT_NEAR(mean / target.ndf(m), 1.0, 0.02) << "slope/alpha " << slopeOverAlpha.x << "," << slopeOverAlpha.y;
    if (slopeOverAlpha != glm::vec2(0.0f)) {
      EXPECT_GT(std::abs(mean / uncorrelated.ndf(m) - 1.0), 0.1) << "the correlation must show";
    }
  }
}

TEST(SlopeCorrelationStat, CorrelatedPNdfIsNormalised) {
  Pcg32 rng(2021, 1);
  for (int i = 0; i < 60; ++i) {
    const GlintParameters p = correlated(glm::vec2(uniform(rng, 0.05f, 0.8f), uniform(rng, 0.05f, 0.8f)),
                                         uniform(rng, -0.99f, 0.99f), uniform(rng, 15.0f, 40.0f));
    const GlintBsdf bsdf(defaultDictionary(), p, randomFootprint(rng, 1e-5f, 3e-2f));
    const double integral = integrateOverSlopes([&](glm::vec2 s) { return bsdf.p22(s); },
                                                glintSlopeExtent(defaultDictionary(), p.alpha, p.rho), 300);
    EXPECT_NEAR(integral, 1.0, 5e-3) << "case " << i << " rho " << p.rho;
  }
}

TEST(SlopeCorrelation, OutOfRangeIsRejectedByName) {
  for (float rho : {-1.0f, 1.0f, 0.995f, std::nanf("")}) {
    GlintParameters p = defaultGlintParameters();
    p.rho = rho;
    try {
      validateGlintParameters(p);
      ADD_FAILURE() << "rho " << rho << " accepted";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("rho"), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW(CookTorranceBsdf(glm::vec2(0.3f), 1.5f), Error);
}

// ---- The mip chain ----------------------------------------------------------------------------

// The filtered marginal at a level of detail, as the walk reads it.
float filteredMarginal(const kernel::GlintDictionaryView& dict, int level, int distribution, float absSlope, float lod) {
  return kernel::glintFilteredMarginal(dict, kernel::glintMarginalFilter(dict, lod), level, distribution, absSlope);
}

// The integral over [-4 sigma_d, 4 sigma_d] of a level of the chain under the texel convention's
// interpolation: spacing (f_0 + 2 sum_k>0 f_k).
double mipIntegral(const Dictionary& d, int mip, int level, int distribution) {
  const int texels = d.parameters().texelsPerDistribution >> mip;
  double sum = d.mipTexel(mip, level, distribution, 0);
  for (int k = 1; k < texels; ++k) sum += 2.0 * d.mipTexel(mip, level, distribution, k);
  return sum * d.parameters().texelSpacing() * (1 << mip);
}

TEST(MipChain, HasOneLevelPerHalvingOfTheTexels) {
  EXPECT_EQ(defaultDictionary().numMips(), 7);  // 64, 32, ..., 1 texels
  EXPECT_EQ(defaultDictionary().mipRowLength(), 127);
  for (int k = 0; k < 64; ++k) EXPECT_EQ(defaultDictionary().mipTexel(0, 3, 5, k), defaultDictionary().texel(3, 5, k));
}

TEST(MipChain, EveryLevelPreservesTheIntegral) {
  const Dictionary& d = defaultDictionary();
  double worst = 0.0;
  for (int mip = 0; mip < d.numMips(); ++mip) {
    for (int level = 0; level < d.parameters().numLevels; level += 3) {
      for (int distribution = 0; distribution < d.parameters().numDistributions; distribution += 7) {
        const double integral = mipIntegral(d, mip, level, distribution);
        worst = std::max(worst, std::abs(integral - mipIntegral(d, 0, level, distribution)));
        // binary16 rounding moves an integral by about 1e-4 per level.
        ASSERT_NEAR(integral, mipIntegral(d, 0, level, distribution), 1e-3)
            << "mip " << mip << " level " << level << " distribution " << distribution;
      }
    }
  }
  std::printf("mip chain: largest integral change %.2e\n", worst);
}

TEST(MipChain, TexelsAreBoxAveragesOfTheMarginal) {
  // Texel k of mip m: the mean of the level-0 marginal over [(k - 1/2), (k + 1/2)] 2^m texels,
  // measured here by a 4096-point midpoint rule of Dictionary::marginal (the last texel also holds
  // what lies beyond its box, checked by the integral test above).
  const Dictionary& d = defaultDictionary();
  const double spacing = d.parameters().texelSpacing();
  for (int mip = 1; mip < d.numMips(); ++mip) {
    const int texels = d.parameters().texelsPerDistribution >> mip;
    const double width = spacing * (1 << mip);
    for (int level : {0, 4, 12}) {
      for (int distribution : {1, 77}) {
        for (int k = 0; k + 1 < texels; ++k) {
          const double low = (k - 0.5) * width;
          constexpr int kSamples = 4096;
          double sum = 0.0;
          for (int s = 0; s < kSamples; ++s) {
            sum += d.marginal(level, distribution, static_cast<float>(low + (s + 0.5) * width / kSamples));
          }
          const double expected = sum / kSamples;
          EXPECT_NEAR(d.mipTexel(mip, level, distribution, k), expected, 2e-3 * expected + 1e-3)
              << "mip " << mip << " level " << level << " distribution " << distribution << " texel " << k;
        }
      }
    }
  }
}

// The variance of an even density on [0, domain) from samples of its half: 2 integral x^2 p.
double halfVariance(const std::function<double(double)>& density, double domain) {
  constexpr int kSamples = 20000;
  double sum = 0.0;
  for (int s = 0; s < kSamples; ++s) {
    const double x = (s + 0.5) * domain / kSamples;
    sum += x * x * density(x);
  }
  return 2.0 * sum * domain / kSamples;
}

TEST(MipChain, LevelMWidensTheMarginalsByAQuarterOfItsSpacingSquared) {
  // glintMarginalLod picks the level whose widening (variance) equals the kernel's, assuming mip m
  // read with linear interpolation adds (2^m h)^2 / 4: a box of width 2^m h (1/12) and the
  // interpolation's hat (1/6). Measured on the mean of the added variance over all distributions
  // of a sparse and a dense level, within 10%.
  const kernel::GlintDictionaryView dict = dictionaryView();
  const double domain = kernel::glintDictionaryDomain(dict);
  const double spacing = domain / dict.texelsPerDistribution;
  for (int mip = 1; mip <= 4; ++mip) {
    for (int level : {2, 10}) {
      double added = 0.0;
      for (int distribution = 0; distribution < dict.numDistributions; ++distribution) {
        const auto at = [&](int lod) {
          return [&, lod](double x) {
            return static_cast<double>(filteredMarginal(dict, level, distribution, static_cast<float>(x),
                                                                     static_cast<float>(lod)));
          };
        };
        added += halfVariance(at(mip), domain) - halfVariance(at(0), domain);
      }
      added /= dict.numDistributions;
      const double expected = std::pow(spacing * (1 << mip), 2.0) / 4.0;
      EXPECT_NEAR(added / expected, 1.0, 0.1) << "mip " << mip << " level " << level;
    }
  }
}

// ---- Filtered marginals -----------------------------------------------------------------------

TEST(FilteredMarginal, AtLodZeroIsThe2020LookupBitForBit) {
  const kernel::GlintDictionaryView dict = dictionaryView();
  const float domain = kernel::glintDictionaryDomain(dict);
  Pcg32 rng(17, 1);
  for (int i = 0; i < 100000; ++i) {
    const int level = static_cast<int>(rng.nextBelow(16));
    const int distribution = static_cast<int>(rng.nextBelow(192));
    const float x = uniform(rng, 0.0f, domain * 0.99999f);
    ASSERT_EQ(filteredMarginal(dict, level, distribution, x, 0.0f),
              kernel::glintMarginal(dict, level, distribution, x))
        << "level " << level << " distribution " << distribution << " slope " << x;
  }
  // No kernel is level of detail 0, one far below a texel next to it.
  EXPECT_EQ(kernel::glintMarginalLod(dict, 0.0f), 0.0f);
  EXPECT_LT(kernel::glintMarginalLod(dict, 1e-12f), 1e-8f);
}

TEST(FilteredMarginal, BlendsTwoLevelsEachReadAtItsOwnSpacing) {
  // Between levels m and m + 1 the lookup is the blend of the two levels' own interpolations,
  // computed here from their texels alone (Dictionary::mipTexel; 0 from 4 sigma_d on). The texels
  // hold the next level interpolated at this level's positions, rounded to binary16: 2e-3.
  const Dictionary& d = defaultDictionary();
  const kernel::GlintDictionaryView dict = dictionaryView();
  const double spacing = d.parameters().texelSpacing();
  const auto interpolated = [&](int mip, int level, int distribution, double x) {
    const int texels = d.parameters().texelsPerDistribution >> mip;
    const double at = x / (spacing * (1 << mip));
    const int k = std::min(static_cast<int>(at), texels - 1);
    const double f = at - k;
    const double a = d.mipTexel(mip, level, distribution, k);
    const double b = k + 1 < texels ? d.mipTexel(mip, level, distribution, k + 1) : 0.0;
    return a + f * (b - a);
  };
  Pcg32 rng(29, 3);
  for (int i = 0; i < 20000; ++i) {
    const int level = static_cast<int>(rng.nextBelow(16));
    const int distribution = static_cast<int>(rng.nextBelow(192));
    const float x = uniform(rng, 0.0f, kernel::glintDictionaryDomain(dict) * 0.99999f);
    const float lod = uniform(rng, 0.0f, dict.numMips - 1.0f);
    const int mip = static_cast<int>(lod);
    const double blend = lod - mip;
    const double expected = (1.0 - blend) * interpolated(mip, level, distribution, x) +
                            (blend > 0.0 ? blend * interpolated(mip + 1, level, distribution, x) : 0.0);
    ASSERT_NEAR(filteredMarginal(dict, level, distribution, x, lod), expected, 2e-3 * expected + 1e-4)
        << "level " << level << " distribution " << distribution << " slope " << x << " lod " << lod;
  }
}

TEST(FilteredMarginal, IntegratesToOneAtEveryLevelOfDetail) {
  const kernel::GlintDictionaryView dict = dictionaryView();
  const double domain = kernel::glintDictionaryDomain(dict);
  for (float lod : {0.0f, 0.5f, 1.0f, 2.3f, 3.7f, 5.5f, 6.0f}) {
    for (int level : {0, 5, 15}) {
      for (int distribution : {0, 50, 191}) {
        constexpr int kSamples = 20000;
        double sum = 0.0;
        for (int s = 0; s < kSamples; ++s) {
          sum += filteredMarginal(dict, level, distribution, static_cast<float>((s + 0.5) * domain / kSamples), lod);
        }
        EXPECT_NEAR(2.0 * sum * domain / kSamples, 1.0, 5e-3) << "lod " << lod << " level " << level;
      }
    }
  }
}

TEST(FilteredMarginal, WiderKernelsWidenTheMarginalsByTheirVariance) {
  const kernel::GlintDictionaryView dict = dictionaryView();
  const float spacing = kernel::glintDictionaryDomain(dict) / dict.texelsPerDistribution;
  // The variance of mip m (m >= 1) is (2^m h)^2 / 4, h the texel spacing: such a kernel reads mip
  // m alone, a kernel between two of them the blend that matches its variance.
  for (int mip = 1; mip < 6; ++mip) {
    const float levelVariance = std::pow(2.0f, 2.0f * mip) * spacing * spacing / 4.0f;
    EXPECT_NEAR(kernel::glintMarginalLod(dict, levelVariance), float(mip), 1e-5f) << mip;
    EXPECT_NEAR(kernel::glintMarginalLod(dict, 2.5f * levelVariance), mip + 0.5f, 1e-5f) << mip;
  }
  EXPECT_NEAR(kernel::glintMarginalLod(dict, 0.5f * spacing * spacing), 0.5f, 1e-6f);
  EXPECT_EQ(kernel::glintMarginalLod(dict, 1e6f), 6.0f);  // clamped to the chain
  // The filter's widening, averaged over the distributions, grows with the level of detail, blend
  // included. Not each distribution's: resampling a level at its own spacing moves a lobe's mass to
  // the nearest texels, so one lobe's variance can fall by up to a texel's worth (measured: a
  // level-0 lobe at 0.25 falls from 0.066 to 0.052 between levels 2 and 3). Nor the peaks: a box
  // average merges a lobe near 0 with its mirror image across 0, as any box filter of an even
  // density does once the box spans both. docs/antialiasing.md says both.
  const double domain = kernel::glintDictionaryDomain(dict);
  for (int level : {0, 3, 8}) {
    double previous = -1.0;
    for (float lod = 0.0f; lod <= 6.0f; lod += 0.25f) {
      double variance = 0.0;
      for (int distribution = 0; distribution < 192; ++distribution) {
        variance += halfVariance(
            [&](double x) {
              return static_cast<double>(filteredMarginal(dict, level, distribution, static_cast<float>(x), lod));
            },
            domain);
      }
      EXPECT_GT(variance, previous) << "level " << level << " lod " << lod;
      previous = variance;
    }
  }
}

// ---- The filtered P-SDF -----------------------------------------------------------------------

glm::vec4 randomDerivatives(Pcg32& rng, float scale) {
  return glm::vec4(uniform(rng, -1.0f, 1.0f), uniform(rng, -1.0f, 1.0f), uniform(rng, -1.0f, 1.0f),
                   uniform(rng, -1.0f, 1.0f)) *
         scale;
}

TEST(GlintAntiAliasing, ZeroDerivativesGiveThe2020PSdfExactly) {
  // With no derivatives the walk is the 2020 one; with derivatives so small that every lookup is
  // at level 0 (a kernel of 1e-12 slope units) it runs the filtered path, which must give the
  // same sums, but for the smooth cells' Gaussian whose covariance the kernel moves by 1e-24.
  const kernel::GlintDictionaryView dict = dictionaryView();
  Pcg32 rng(18, 1);
  int glinty = 0;
  for (int i = 0; i < 3000; ++i) {
    GlintParameters p = correlated(glm::vec2(uniform(rng, 0.05f, 1.0f), uniform(rng, 0.05f, 1.0f)),
                                   rng.nextBelow(2) ? uniform(rng, -0.9f, 0.9f) : 0.0f, uniform(rng, 12.0f, 30.0f));
    const SurfaceFootprint f = randomFootprint(rng, 1e-5f, 3e-3f);
    const glm::vec2 slope = glm::vec2(uniform(rng, -1.5f, 1.5f), uniform(rng, -1.5f, 1.5f)) * p.alpha;
    const float unfiltered = kernel::glintP22(dict, p, f.uv, f.duvdx, f.duvdy, slope);
    ASSERT_EQ(kernel::glintFilteredP22(dict, p, f.uv, f.duvdx, f.duvdy, slope, glm::vec4(0.0f)), unfiltered);
    const float tiny = kernel::glintFilteredP22(dict, p, f.uv, f.duvdx, f.duvdy, slope, randomDerivatives(rng, 1e-12f));
    // 1e-5 relative, and 1e-6 of the Beckmann peak where the smooth cells' tail is rounded
    // differently by the Gaussian's covariance form.
    ASSERT_NEAR(tiny, unfiltered, 1e-5f * unfiltered + 1e-6f * kernel::glintBeckmannP22(glm::vec2(0.0f), p.alpha, p.rho))
        << "case " << i;
    const float smooth = kernel::glintBeckmannP22(slope, p.alpha, p.rho);
    glinty += std::abs(unfiltered - smooth) > 0.5f * smooth;
  }
  std::printf("%d of 3000 cases glinty (P22 off the Beckmann's by more than half)\n", glinty);
  EXPECT_GT(glinty, 1000);  // the comparison covers glints, not only smooth lobes
}

TEST(GlintAntiAliasingStat, FilteredPSdfIsNormalised) {
  // Within 0.5%, on a 500 x 500 grid over 1.5 times the unfiltered support (a 300 x 300 grid was
  // off by 5e-3 on case 5, which 1500 x 1500 puts at 1.4e-4).
  Pcg32 rng(18, 2);
  for (int i = 0; i < 30; ++i) {
    const GlintParameters p = correlated(glm::vec2(uniform(rng, 0.05f, 0.8f), uniform(rng, 0.05f, 0.8f)),
                                         uniform(rng, -0.9f, 0.9f), uniform(rng, 12.0f, 40.0f));
    const SurfaceFootprint f = randomFootprint(rng, 1e-5f, 3e-2f);
    const glm::vec4 derivatives = randomDerivatives(rng, 0.1f * std::pow(10.0f, uniform(rng, -2.0f, 0.5f)));
    const double integral = integrateOverSlopes(
        [&](glm::vec2 s) {
          return kernel::glintFilteredP22(defaultDictionary().view(), p, f.uv, f.duvdx, f.duvdy, s, derivatives);
        },
        glintSlopeExtent(defaultDictionary(), p.alpha, p.rho) * 1.5f, 500);
    EXPECT_NEAR(integral, 1.0, 5e-3) << "case " << i;
  }
}

TEST(GlintAntiAliasingStat, FilterApproachesThePixelAverage) {
  // The reference a pixel should show is the mean of the 2020 P-SDF over the pixel's box of half
  // vectors, slope(p) = s0 + dx p.x + dy p.y (32 x 32 stratified samples); the filtered P-SDF at s0
  // must be closer to it than the 2020 P-SDF at s0, over glinty pixels of several footprints.
  const kernel::GlintDictionaryView dict = dictionaryView();
  Pcg32 rng(18, 3);
  double errorNone = 0.0, errorFiltered = 0.0;
  for (int i = 0; i < 300; ++i) {
    const GlintParameters p = correlated(glm::vec2(uniform(rng, 0.1f, 0.5f)), 0.0f, uniform(rng, 14.0f, 24.0f));
    const SurfaceFootprint f = randomFootprint(rng, 1e-4f, 2e-3f);
    const glm::vec2 s0 = glm::vec2(uniform(rng, -1.0f, 1.0f), uniform(rng, -1.0f, 1.0f)) * p.alpha;
    // Derivatives up to 0.2 alpha a pixel: in the dictionary's space (slopes times alpha_d / alpha)
    // up to 0.1, a few lobe widths (0.02) and texels (0.022).
    const glm::vec4 d = randomDerivatives(rng, 0.2f * p.alpha.x);
    double reference = 0.0;
    constexpr int kStrata = 32;
    for (int a = 0; a < kStrata; ++a) {
      for (int b = 0; b < kStrata; ++b) {
        const float x = (a + 0.5f) / kStrata - 0.5f;
        const float y = (b + 0.5f) / kStrata - 0.5f;
        const glm::vec2 s = s0 + x * glm::vec2(d.x, d.y) + y * glm::vec2(d.z, d.w);
        reference += kernel::glintP22(dict, p, f.uv, f.duvdx, f.duvdy, s);
      }
    }
    reference /= kStrata * kStrata;
    const double none = kernel::glintP22(dict, p, f.uv, f.duvdx, f.duvdy, s0);
    const double filtered = kernel::glintFilteredP22(dict, p, f.uv, f.duvdx, f.duvdy, s0, d);
    errorNone += (none - reference) * (none - reference);
    errorFiltered += (filtered - reference) * (filtered - reference);
  }
  std::printf("pixel average: RMSE 2020 %.4f, filtered %.4f (ratio %.3f)\n", std::sqrt(errorNone / 300),
              std::sqrt(errorFiltered / 300), std::sqrt(errorFiltered / errorNone));
  EXPECT_LT(errorFiltered, 0.5 * errorNone);
}

TEST(GlintFootprint, HugeFootprintsAreTheSmoothLimitNotZero) {
  // A footprint of 1e20 uv units: its length squared overflows a float, which made the ellipse's
  // axes NaN and the P-SDF 0. Any footprint that large holds so many microfacets that every cell
  // is in the smooth limit: the Beckmann P22.
  const kernel::GlintDictionaryView dict = dictionaryView();
  const GlintParameters p = correlated(glm::vec2(0.3f), 0.0f, 20.0f);
  const glm::vec2 slope(0.05f, -0.1f);
  const float beckmann = kernel::glintBeckmannP22(slope, p.alpha, p.rho);
  for (glm::vec2 duvdx : {glm::vec2(1e20f, 0.0f), glm::vec2(3e38f, -3e38f), glm::vec2(2e6f, 1.0f)}) {
    const float value = kernel::glintP22(dict, p, glm::vec2(0.3f, 0.7f), duvdx, glm::vec2(0.0f, 1e-3f), slope);
    EXPECT_NEAR(value, beckmann, 1e-5f * beckmann) << duvdx.x;
  }
  // And with the huge derivative second, which the ellipse swaps to be its major axis.
  for (glm::vec2 duvdy : {glm::vec2(1e20f, 0.0f), glm::vec2(3e38f, -3e38f)}) {
    const float value = kernel::glintP22(dict, p, glm::vec2(0.3f, 0.7f), glm::vec2(0.0f, 1e-3f), duvdy, slope);
    EXPECT_NEAR(value, beckmann, 1e-5f * beckmann) << duvdy.x;
  }
}

TEST(GlintAntiAliasing, NoNanOrInfinityAtTheLimits) {
  const kernel::GlintDictionaryView dict = dictionaryView();
  Pcg32 rng(18, 4);
  for (float rho : {-0.99f, 0.0f, 0.99f}) {
    for (glm::vec2 slope : {glm::vec2(0.0f), glm::vec2(1e3f, -1e3f), glm::vec2(3.0f, 0.1f), glm::vec2(-1e-20f, 1e-20f)}) {
      for (glm::vec4 derivatives : {glm::vec4(0.0f), glm::vec4(1e20f, -1e20f, 1e20f, 1e20f), glm::vec4(1e-30f),
                                    glm::vec4(0.3f, 0.0f, 0.0f, 0.0f), glm::vec4(3e38f)}) {
        for (float duv : {0.0f, 1e-4f, 10.0f}) {
          const GlintParameters p = correlated(glm::vec2(0.01f, 2.0f), rho, 18.0f);
          const glm::vec2 uv(uniform(rng, 0.0f, 1.0f), uniform(rng, 0.0f, 1.0f));
          const float value = kernel::glintFilteredP22(dict, p, uv, glm::vec2(duv, 0.0f), glm::vec2(0.0f, duv * 0.3f), slope,
                                                       derivatives);
          EXPECT_TRUE(std::isfinite(value) && value >= 0.0f)
              << "rho " << rho << " slope " << slope.x << " derivatives " << derivatives.x << " duv " << duv << ": "
              << value;
        }
      }
    }
  }
}

// ---- Normal-map filtering ---------------------------------------------------------------------

// A normal map of size x size whose tangent-space normal at texel (x, y) is `normal(x, y)`.
scene::Texture normalTexture(int size, const std::function<glm::vec3(int, int)>& normal) {
  scene::Texture t{"test normals", size, size, std::vector<std::uint8_t>(static_cast<std::size_t>(size) * size * 4, 255), false, {}};
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      const glm::vec3 n = glm::normalize(normal(x, y));
      for (int c = 0; c < 3; ++c) {
        t.rgba[4 * (static_cast<std::size_t>(y) * size + x) + static_cast<std::size_t>(c)] =
            static_cast<std::uint8_t>(std::lround((n[c] * 0.5f + 0.5f) * 255.0f));
      }
    }
  }
  return t;
}

TEST(NormalMapFiltering, ConstantNormalMapChangesNothing) {
  // One tilted normal everywhere: no covariance at any footprint, so the roughness stays exactly,
  // and the mean normal is the texel's normal as the unfiltered shader decodes it.
  const scene::Texture t = normalTexture(8, [](int, int) { return glm::vec3(0.3f, -0.2f, 1.0f); });
  const scene::NormalMapMoments m = scene::normalMapMoments(t, 1.0f);
  const trace::MipTexture first(m.width, m.height, m.first), second(m.width, m.height, m.second);
  for (float footprint : {0.01f, 0.2f, 1.0f, 5.0f}) {
    const glm::vec2 dx(footprint, 0.0f), dy(0.0f, footprint);
    const glm::vec3 a = first.sample(glm::vec2(0.3f, 0.6f), dx, dy);
    const glm::vec3 b = second.sample(glm::vec2(0.3f, 0.6f), dx, dy);
    const glm::vec3 covariance = kernel::glintLeanSlopeCovariance(a, b, first.levelOfDetail(dx, dy));
    EXPECT_LE(std::abs(covariance.x) + std::abs(covariance.y) + std::abs(covariance.z), 1e-6f) << footprint;
    const glm::vec3 alphaRho = kernel::glintLeanCombinedRoughness(glm::vec2(0.05f, 0.3f), 0.2f, glm::vec3(0.0f));
    EXPECT_EQ(alphaRho, glm::vec3(0.05f, 0.3f, 0.2f));
    glm::vec3 decoded;
    for (int c = 0; c < 3; ++c) decoded[c] = static_cast<float>(t.rgba[static_cast<std::size_t>(c)]) / 255.0f * 2.0f - 1.0f;
    const glm::vec3 mean = kernel::glintLeanMeanNormal(a);
    EXPECT_NEAR(glm::dot(mean, glm::normalize(decoded)), 1.0f, 1e-6f) << footprint;
  }
}

TEST(NormalMapFiltering, MomentMipsAreBoxAveragesWithNonNegativeVariance) {
  // The arctic snow's normal map: at every level of the moments' chain, every texel's variances
  // E[s^2] - E[s]^2 are non-negative, and the mean variance grows with the level (the law of total
  // variance: a coarser texel adds the spread of its four children's means).
  const scene::Scene arctic = scene::makeBuiltinScene("arctic");
  const scene::Material* snow = nullptr;
  for (const scene::Material& material : arctic.materials) {
    if (material.normalTexture >= 0 && material.glint.enabled) snow = &material;
  }
  ASSERT_NE(snow, nullptr);
  const scene::NormalMapMoments m =
      scene::normalMapMoments(arctic.textures[static_cast<std::size_t>(snow->normalTexture)], snow->normalScale);
  const trace::MipTexture first(m.width, m.height, m.first), second(m.width, m.height, m.second);
  double previous = -1.0;
  for (int level = 0; level < first.levelCount(); ++level) {
    const int size = std::max(1, m.width >> level);
    double meanVariance = 0.0;
    for (int y = 0; y < size; ++y) {
      for (int x = 0; x < size; ++x) {
        const glm::vec2 uv((x + 0.5f) / size, (y + 0.5f) / size);
        const glm::vec3 a = first.bilinear(level, uv), b = second.bilinear(level, uv);
        const float vx = a.z - a.x * a.x, vy = b.x - a.y * a.y;
        ASSERT_GE(vx, -1e-6f) << "level " << level;
        ASSERT_GE(vy, -1e-6f) << "level " << level;
        meanVariance += (vx + vy) / (static_cast<double>(size) * size);
      }
    }
    EXPECT_GE(meanVariance, previous - 1e-7) << "level " << level;
    previous = meanVariance;
  }
  EXPECT_GT(previous, 1e-3);  // the map has slopes to filter
}

TEST(NormalMapFiltering, RidgeKeepsItsVarianceAlongOneAxis) {
  // Ridges along v: slopes vary in x only. The covariance keeps x's variance and none in y, and
  // only alpha_x widens (the authors' shader drops both when either is small).
  const scene::Texture t = normalTexture(16, [](int x, int) { return glm::vec3(x % 2 ? 0.4f : -0.4f, 0.0f, 1.0f); });
  const scene::NormalMapMoments m = scene::normalMapMoments(t, 1.0f);
  const trace::MipTexture first(m.width, m.height, m.first), second(m.width, m.height, m.second);
  const glm::vec2 dx(0.25f, 0.0f), dy(0.0f, 0.25f);  // 4 texels: level 2
  const glm::vec3 covariance = kernel::glintLeanSlopeCovariance(first.sample({0.5f, 0.5f}, dx, dy),
                                                           second.sample({0.5f, 0.5f}, dx, dy), first.levelOfDetail(dx, dy));
  const float slope = 0.4f / std::sqrt(1.0f - 0.0f);  // |n.x / n.z| of the decoded texels, about 0.4
  EXPECT_NEAR(covariance.x, slope * slope, 0.02f);
  EXPECT_NEAR(covariance.z, 0.0f, 1e-5f);
  EXPECT_NEAR(covariance.y, 0.0f, 1e-5f);
  const glm::vec3 combined = kernel::glintLeanCombinedRoughness(glm::vec2(0.1f), 0.0f, covariance);
  EXPECT_GT(combined.x, 0.5f);
  EXPECT_NEAR(combined.y, 0.1f, 1e-5f);
}

TEST(NormalMapFiltering, MagnifiedFootprintsAddNoRoughness) {
  // Below a texel the covariance scales with the footprint's area in texels, 4^lambda.
  const glm::vec3 first(0.1f, 0.0f, 0.02f), second(0.01f, 0.0f, 0.0f);
  const glm::vec3 at0 = kernel::glintLeanSlopeCovariance(first, second, 0.0f);
  EXPECT_NEAR(kernel::glintLeanSlopeCovariance(first, second, -1.0f).x, 0.25f * at0.x, 1e-7f);
  EXPECT_NEAR(kernel::glintLeanSlopeCovariance(first, second, -3.0f).z, at0.z / 64.0f, 1e-7f);
  EXPECT_EQ(kernel::glintLeanSlopeCovariance(first, second, 2.0f), at0);
  EXPECT_LT(kernel::glintLeanSlopeCovariance(first, second, -128.0f).x, 1e-30f);
}

TEST(NormalMapFiltering, CombinedRoughnessAddsTheCovariances) {
  // Rebuilding the covariance from the combined (alpha, rho) gives Sigma_material + Sigma_map.
  const glm::vec2 alpha(0.2f, 0.35f);
  const float rho = -0.3f;
  const glm::vec3 map(0.01f, 0.004f, 0.02f);
  const glm::vec3 combined = kernel::glintLeanCombinedRoughness(alpha, rho, map);
  const glm::vec3 rebuilt = kernel::glintBeckmannSlopeCovariance(glm::vec2(combined), combined.z);
  const glm::vec3 expected = kernel::glintBeckmannSlopeCovariance(alpha, rho) + map;
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(rebuilt[c], expected[c], 1e-6f) << c;
}

}  // namespace
}  // namespace glint
