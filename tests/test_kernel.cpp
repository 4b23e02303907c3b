// Unit tests of the kernel's building blocks against independent references.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <string>

#include <gtest/gtest.h>

#include "glint/half.h"
#include "glint/kernel/glint_brdf.h"
#include "glint/kernel/lights.h"
#include "glint/pcg.h"
#include "test_support.h"

namespace glint {
namespace {

using namespace glint::test;

TEST(Half, EveryFiniteHalfRoundTrips) {
  for (std::uint32_t h = 0; h < 0x10000u; ++h) {
    const auto half = static_cast<std::uint16_t>(h);
    if ((half & 0x7C00u) == 0x7C00u) continue;  // infinities and NaNs
    ASSERT_EQ(floatToHalf(halfToFloat(half)), half) << "half 0x" << std::hex << h;
  }
}

TEST(Half, RoundsToTheNearestHalf) {
  // The chosen half must be at least as close as both of its neighbours.
  Pcg32 rng(7, 0);
  for (int i = 0; i < 200000; ++i) {
    const float value = std::ldexp(static_cast<float>(rng.nextOpenUnit()), static_cast<int>(rng.nextBelow(40)) - 26);
    const std::uint16_t half = floatToHalf(value);
    const float error = std::abs(halfToFloat(half) - value);
    ASSERT_LE(error, std::abs(halfToFloat(static_cast<std::uint16_t>(half + 1)) - value)) << value;
    if (half > 0) {
      ASSERT_LE(error, std::abs(halfToFloat(static_cast<std::uint16_t>(half - 1)) - value)) << value;
    }
  }
  EXPECT_EQ(floatToHalf(1.0f), 0x3C00u);
  EXPECT_EQ(floatToHalf(65504.0f), 0x7BFFu);
  EXPECT_EQ(floatToHalf(1e6f), 0x7C00u);
}

TEST(SpotLight, FallsOffBetweenItsConesAsTheGltfExtensionSays) {
  // KHR_lights_punctual: full intensity within the inner cone, none beyond the outer one, and in
  // between the square of the cosine's linear ramp, (cos a - cos outer) / (cos inner - cos outer),
  // evaluated here in double from the angle a between the axis and the direction to the point.
  const double inner = 0.3;
  const double outer = 0.7;
  const glm::vec2 cone = kernel::glintSpotConeScaleOffset(float(inner), float(outer));
  const glm::vec3 axis = glm::normalize(glm::vec3(0.2f, -1.0f, 0.1f));
  // Directions at angle a from the axis, turned about a perpendicular.
  const glm::vec3 side = glm::normalize(glm::cross(axis, glm::vec3(1, 0, 0)));
  double worst = 0.0;
  for (int k = 0; k <= 100; ++k) {
    const double a = 1.0 * k / 100;
    const glm::vec3 away = float(std::cos(a)) * axis + float(std::sin(a)) * side;  // from the light to the point
    const float got = kernel::glintSpotAttenuation(axis, -away, cone);
    const double ramp = std::clamp((std::cos(a) - std::cos(outer)) / (std::cos(inner) - std::cos(outer)), 0.0, 1.0);
    worst = std::max(worst, std::abs(got - ramp * ramp));
    if (a < inner) EXPECT_EQ(got, 1.0f) << a;
    if (a > outer) EXPECT_EQ(got, 0.0f) << a;
  }
  EXPECT_LT(worst, 1e-5);  // float cosines of angles within the ramp
  // A light without a cone, (0, 1), sends its full intensity every way.
  EXPECT_EQ(kernel::glintSpotAttenuation(axis, axis, glm::vec2(0.0f, 1.0f)), 1.0f);
}

TEST(LightRange, WindowsTheInverseSquareLawAsTheGltfExtensionSays) {
  // KHR_lights_punctual's recommended window for a light's range r: max(min(1 - (d / r)^4, 1), 0),
  // here in double from the distance d.
  const double range = 2.5;
  double worst = 0.0;
  for (int k = 0; k <= 120; ++k) {
    const double d = 3.0 * k / 120;
    const float got = kernel::glintRangeWindow(float(d * d), float(1.0 / range));
    const double window = std::max(std::min(1.0 - std::pow(d / range, 4.0), 1.0), 0.0);
    worst = std::max(worst, std::abs(got - window));
    if (d >= range) EXPECT_EQ(got, 0.0f) << d;
  }
  EXPECT_LT(worst, 1e-6);
  EXPECT_EQ(kernel::glintRangeWindow(0.0f, float(1.0 / range)), 1.0f);
  // Half way to the range, 15/16 of the light is left.
  EXPECT_NEAR(kernel::glintRangeWindow(float(0.25 * range * range), float(1.0 / range)), 15.0 / 16, 1e-6);
  // Without a range (inverse 0) nothing is taken off, however far.
  EXPECT_EQ(kernel::glintRangeWindow(1e12f, 0.0f), 1.0f);
}

TEST(NormalQuantile, MatchesBisectionOfTheNormalCdf) {
  // Reference: bisection of Phi(x) = erfc(-x / sqrt 2) / 2 to 1e-15. Acklam's stated relative
  // error in x is 1.15e-9; allow 1.2e-9 relative (plus 1e-15 near x = 0).
  for (double p : {1e-12, 1e-9, 1e-6, 1e-3, 0.02, 0.1, 0.3, 0.5, 0.7, 0.9, 0.98, 0.999, 0.999999}) {
    double low = -10.0;
    double high = 10.0;
    while (high - low > 1e-15) {
      const double mid = 0.5 * (low + high);
      (0.5 * std::erfc(-mid / std::sqrt(2.0)) < p ? low : high) = mid;
    }
    const double reference = 0.5 * (low + high);
    EXPECT_NEAR(normalQuantile(p), reference, 1.2e-9 * std::abs(reference) + 1e-15) << "p = " << p;
  }
}

TEST(Erfinv, InvertsErfInSinglePrecision) {
  // Giles' single-precision approximation: relative error well below 1e-5 in x everywhere.
  for (int i = -999; i <= 999; ++i) {
    const double y = i / 1000.0 * 0.999999;
    const double x = kernel::glintErfinvApprox(static_cast<float>(y));
    EXPECT_NEAR(std::erf(x), y, 2e-6 * std::abs(y) + 1e-7) << "y = " << y;
  }
}

TEST(NormalCdf, MatchesErfcInSinglePrecision) {
  // What matters for the level thresholds (glintLevelDraw) is the absolute error: a cell's level
  // differs from the exact draw only when its u lies between the exact and the computed threshold,
  // so the absolute error bounds that probability. The erfc fit's fractional error is 1.2e-7;
  // near Phi = 1/2 that and the float rounding of 1 - tail (spacing 6e-8) give about 1.7e-7,
  // so the bound is 2e-7. The far lower tail must keep its relative precision as well: there the
  // float argument of exp (x^2 up to 32) limits it to about 1e-5.
  double worstAbsolute = 0.0;
  double worstTailRelative = 0.0;
  for (int i = -8000; i <= 8000; ++i) {
    const float z = static_cast<float>(i / 1000.0);
    const double exact = 0.5 * std::erfc(-static_cast<double>(z) / std::sqrt(2.0));
    const double approx = kernel::glintNormalCdf(z);
    worstAbsolute = std::max(worstAbsolute, std::abs(approx - exact));
    if (z < -3.0f) worstTailRelative = std::max(worstTailRelative, std::abs(approx / exact - 1.0));
  }
  EXPECT_LT(worstAbsolute, 2e-7);
  EXPECT_LT(worstTailRelative, 1e-5);
  std::printf("glintNormalCdf: worst absolute error %.2e, worst relative error below z = -3 %.2e\n", worstAbsolute,
              worstTailRelative);
}

TEST(Hash, Pcg4dLanesAreUniformAndIndependent) {
  // 2^16 cells, 32 bins per lane: chi-square with 31 degrees of freedom stays below 61.1 with
  // probability 0.999 for a uniform hash; the lanes' pairwise correlations are within 4 standard
  // errors (4 / sqrt(2^16) = 0.016) of zero. Fixed inputs, so the outcome is deterministic.
  constexpr int kCells = 256;
  constexpr int kBins = 32;
  int histogram[4][kBins] = {};
  std::vector<glm::vec4> draws;
  for (int t = 0; t < kCells; ++t) {
    for (int s = 0; s < kCells; ++s) {
      const glm::uvec4 h = kernel::glintPcg4d(glm::uvec4(s, t, 0u, 0u));
      glm::vec4 u;
      for (int lane = 0; lane < 4; ++lane) {
        u[lane] = kernel::glintHashToUnitOpen(h[lane]);
        ++histogram[lane][static_cast<int>(u[lane] * kBins)];
      }
      draws.push_back(u);
    }
  }
  const double expected = double(kCells) * kCells / kBins;
  for (int lane = 0; lane < 4; ++lane) {
    double chi2 = 0.0;
    for (int b = 0; b < kBins; ++b) chi2 += std::pow(histogram[lane][b] - expected, 2) / expected;
    EXPECT_LT(chi2, 61.1) << "lane " << lane;
  }
  for (int a = 0; a < 4; ++a) {
    for (int b = a + 1; b < 4; ++b) {
      double covariance = 0.0;
      for (const auto& u : draws) covariance += (u[a] - 0.5) * (u[b] - 0.5);
      const double correlation = covariance / draws.size() * 12.0;
      EXPECT_LT(std::abs(correlation), 0.016) << "lanes " << a << ", " << b;
    }
  }
}

TEST(Hash, NeighbouringCellsDrawDifferentNumbers) {
  std::set<std::uint32_t> seen;
  for (std::uint32_t t = 0; t < 128; ++t) {
    for (std::uint32_t s = 0; s < 128; ++s) seen.insert(kernel::glintPcg4d(glm::uvec4(s, t, 0u, 0u)).z);
  }
  EXPECT_GT(seen.size(), 128u * 128u - 4u);  // 32-bit outputs: a birthday collision is possible, rare
}

TEST(Beckmann, SlopeDistributionIntegratesToOne) {
  for (glm::vec2 alpha : {glm::vec2(0.1f), glm::vec2(0.5f), glm::vec2(0.05f, 0.8f)}) {
    const double integral = integrateOverSlopes(
        [&](glm::vec2 slope) { return kernel::glintBeckmannP22(slope, alpha, 0.0f); }, 6.0f * alpha, 400);
    EXPECT_NEAR(integral, 1.0, 1e-5);
  }
}

TEST(Beckmann, NdfIsProjectedAreaNormalised) {
  // Integral of D(m) cos(theta_m) over the hemisphere, in spherical coordinates: a different
  // parameterisation from the slope-space test above.
  const glm::vec2 alpha(0.3f, 0.6f);
  double integral = 0.0;
  constexpr int kTheta = 2000;
  constexpr int kPhi = 400;
  for (int i = 0; i < kTheta; ++i) {
    const double theta = (i + 0.5) / kTheta * (M_PI / 2);
    for (int j = 0; j < kPhi; ++j) {
      const double phi = (j + 0.5) / kPhi * 2 * M_PI;
      const glm::vec3 m = directionAt(static_cast<float>(theta), static_cast<float>(phi));
      const double d = kernel::glintNdfFromP22(kernel::glintBeckmannP22(kernel::glintSlopeFromNormal(m), alpha, 0.0f), m.z);
      integral += d * m.z * std::sin(theta) * (M_PI / 2 / kTheta) * (2 * M_PI / kPhi);
    }
  }
  EXPECT_NEAR(integral, 1.0, 1e-3);
}

TEST(Fresnel, SchlickEndpoints) {
  const glm::vec3 f0(0.04f, 0.5f, 0.9f);
  const glm::vec3 normal = kernel::glintFresnelSchlick(f0, 1.0f);
  const glm::vec3 grazing = kernel::glintFresnelSchlick(f0, 0.0f);
  for (int c = 0; c < 3; ++c) {
    EXPECT_FLOAT_EQ(normal[c], f0[c]);
    EXPECT_FLOAT_EQ(grazing[c], 1.0f);
  }
}

TEST(Fresnel, ConductorMatchesClosedForms) {
  // Normal incidence: ((n-1)^2 + k^2) / ((n+1)^2 + k^2). With k = 0 at any angle: the dielectric
  // Fresnel equations through Snell's law.
  const glm::vec3 eta(0.2f, 1.1f, 1.5f);
  const glm::vec3 k(3.9f, 2.4f, 0.0f);
  const glm::vec3 normal = kernel::glintFresnelConductor(eta, k, 1.0f);
  for (int c = 0; c < 3; ++c) {
    const double n = eta[c];
    const double kk = k[c];
    EXPECT_NEAR(normal[c], ((n - 1) * (n - 1) + kk * kk) / ((n + 1) * (n + 1) + kk * kk), 1e-5);
  }
  for (double cosI : {0.95, 0.7, 0.4, 0.1}) {
    const double n = 1.5;
    const double sinT = std::sqrt(1 - cosI * cosI) / n;
    const double cosT = std::sqrt(1 - sinT * sinT);
    const double rs = (cosI - n * cosT) / (cosI + n * cosT);
    const double rp = (n * cosI - cosT) / (n * cosI + cosT);
    const float value = kernel::glintFresnelConductor(glm::vec3(1.5f), glm::vec3(0.0f), static_cast<float>(cosI)).x;
    EXPECT_NEAR(value, 0.5 * (rs * rs + rp * rp), 1e-5) << "cos " << cosI;
  }
}

TEST(VCavity, MaskingIsOneAtNormalViewAndFallsAtGrazing) {
  const glm::vec3 m = glm::normalize(glm::vec3(0.3f, 0.0f, 1.0f));
  EXPECT_FLOAT_EQ(kernel::glintVCavityG1(glm::vec3(0, 0, 1), m), 1.0f);
  const glm::vec3 grazing = directionAt(1.5f, 3.14159f);
  const float expected = 2.0f * m.z * grazing.z / glm::dot(grazing, m);
  EXPECT_LT(expected, 1.0f);
  EXPECT_FLOAT_EQ(kernel::glintVCavityG1(grazing, m), expected);
}

TEST(Footprint, AnisotropyIsClampedByWideningTheMinorAxis) {
  const auto fp = kernel::glintFootprint(glm::vec2(0.01f, 0.0f), glm::vec2(0.0f, 0.0001f), 8.0f, 27.0f, 16);
  EXPECT_FLOAT_EQ(glm::length(fp.majorAxis), 0.01f);
  EXPECT_FLOAT_EQ(glm::length(fp.minorAxis), 0.01f / 8.0f);
  EXPECT_FALSE(fp.degenerate);
}

TEST(Footprint, LevelOfDetailIsTheMinorAxisInCells) {
  // A minor axis of one cell of level l (2^(l - 15) uv units) selects level l exactly.
  for (int level = 0; level < 16; ++level) {
    const float cell = std::ldexp(1.0f, level - 15);
    const auto fp = kernel::glintFootprint(glm::vec2(cell, 0.0f), glm::vec2(0.0f, cell), 8.0f, 27.0f, 16);
    EXPECT_FLOAT_EQ(fp.lod, static_cast<float>(level));
  }
  const auto tiny = kernel::glintFootprint(glm::vec2(1e-7f, 0.0f), glm::vec2(0.0f, 1e-7f), 8.0f, 27.0f, 16);
  EXPECT_FLOAT_EQ(tiny.lod, 0.0f);
}

TEST(Footprint, LargeFootprintsKeepTheirMicrofacetCount) {
  // Minor axis 4 uv units: shrunk to 1, and the 16x area goes into the density (ln 16).
  const auto fp = kernel::glintFootprint(glm::vec2(4.0f, 0.0f), glm::vec2(0.0f, 4.0f), 8.0f, 20.0f, 16);
  EXPECT_FLOAT_EQ(fp.lod, 15.0f);
  EXPECT_NEAR(fp.logDensity, 20.0f + std::log(16.0f), 1e-5f);
  EXPECT_FLOAT_EQ(glm::length(fp.minorAxis), 1.0f);
}

TEST(Footprint, AxesAreTheEllipsesWhicheverWayTheScreenAxesTurn) {
  // The footprint ellipse duvdx cos t + duvdy sin t does not depend on which way the screen axes
  // turn, so neither may its axes, their clamp or the LOD. Taking the shorter derivative as the
  // minor axis (pbrt-v3) overestimated it by up to anisotropy / sqrt 2 at 45 degrees.
  for (float anisotropy : {1.0f, 2.0f, 10.2f, 50.0f, 1e4f}) {
    for (float uvAngle : {0.0f, 0.5f}) {
      const float major = 0.02f;
      const float minor = major / anisotropy;
      const auto aligned = turnedDerivatives(major, minor, uvAngle, 0.0f);
      const auto reference = kernel::glintFootprint(aligned.first, aligned.second, 8.0f, 27.0f, 16);
      const float clampedMinor = std::max(minor, major / 8.0f);
      for (float degrees : {10.0f, 22.5f, 45.0f, 67.5f, 80.0f, 135.0f}) {
        const auto [duvdx, duvdy] = turnedDerivatives(major, minor, uvAngle, glm::radians(degrees));
        const auto fp = kernel::glintFootprint(duvdx, duvdy, 8.0f, 27.0f, 16);
        const std::string where = "anisotropy " + std::to_string(anisotropy) + ", screen turned " +
                                  std::to_string(degrees) + " degrees";
        EXPECT_NEAR(glm::length(fp.majorAxis), major, 1e-5f * major) << where;
        EXPECT_NEAR(glm::length(fp.minorAxis), clampedMinor, 1e-4f * clampedMinor) << where;
        EXPECT_NEAR(glm::dot(fp.majorAxis, fp.minorAxis), 0.0f, 1e-6f * major * clampedMinor) << where;
        // The major axis lies along the uv direction uvAngle (either sign); a circle has none.
        const glm::vec2 along(std::cos(uvAngle), std::sin(uvAngle));
        if (anisotropy > 1.0f) EXPECT_NEAR(std::abs(glm::dot(fp.majorAxis, along)), major, 1e-5f * major) << where;
        EXPECT_NEAR(fp.lod, reference.lod, 1e-4f) << where;
        EXPECT_NEAR(fp.lod, 15.0f + std::log2(clampedMinor), 1e-4f) << where;
        EXPECT_FALSE(fp.degenerate) << where;
      }
    }
  }
}

TEST(Footprint, UvSpherePoleFootprintHasTheMinorAxisAcrossTheRing) {
  // The built-in sphere's first ring of triangles around its pole (128 x 64 segments, uv =
  // (phi / 2 pi, theta / pi) x 4), seen by `glint render sphere --camera top` at 1024x1024: u's
  // derivative 0.0418 uv per pixel around the ring, 10.2 = 1 / (2 sin(pi / 64)) times v's,
  // 0.0041, along the meridian (measured with the tracer's ray differentials). Where the meridian
  // runs at 45 degrees to the screen axes, both derivatives are 0.0297 uv long; taking one as the
  // minor axis chose cells 7.2 times longer than the pixel along the meridian (LOD 9.93 instead
  // of 7.42): the starburst of radial streaks. The ellipse's own minor axis, clamped to 8:1, picks
  // cells of about a pixel, and the walk stays as cheap as for the same ellipse seen square on.
  const float around = 0.0418f;
  const float along = 0.0041f;
  const float clampedMinor = around / 8.0f;  // 0.0052 > 0.0041: the clamp widens it by 1.27
  const auto square = turnedDerivatives(around, along, 0.0f, 0.0f);
  const auto squareFootprint = kernel::glintFootprint(square.first, square.second, 8.0f, 13.0f, 16);
  auto cellsWalked = [](const kernel::GlintFootprint& fp, int level) {
    const kernel::GlintCellGrid grid = kernel::glintCellGrid(fp, glm::vec2(0.37f, 0.81f), 16, level);
    int cells = 0;
    for (int t = grid.t0; t <= grid.t1; ++t) {
      const glm::ivec2 row = kernel::glintCellRow(grid, t);
      for (int s = row.x; s <= row.y; ++s) cells += kernel::glintCellWeight(grid, s, t) > 0.0f ? 1 : 0;
    }
    return cells;
  };
  for (float degrees : {0.0f, 22.5f, 45.0f, 60.0f}) {
    const auto [duvdx, duvdy] = turnedDerivatives(around, along, 0.0f, glm::radians(degrees));
    const auto fp = kernel::glintFootprint(duvdx, duvdy, 8.0f, 13.0f, 16);
    ASSERT_FALSE(fp.degenerate) << degrees;
    const float majorLength = glm::length(fp.majorAxis);
    const float minorLength = glm::length(fp.minorAxis);
    EXPECT_TRUE(std::isfinite(majorLength) && std::isfinite(minorLength) && std::isfinite(fp.lod)) << degrees;
    EXPECT_LE(majorLength / minorLength, 8.0f * 1.0001f) << degrees;
    EXPECT_NEAR(fp.lod, 15.0f + std::log2(clampedMinor), 1e-4f) << degrees;  // 7.42
    EXPECT_FLOAT_EQ(fp.logDensity, 13.0f) << degrees;
    const int level = kernel::glintLodLevel(fp);
    for (int l = level; l <= level + 1; ++l) {
      const int cells = cellsWalked(fp, l);
      const int squareCells = cellsWalked(squareFootprint, l);
      EXPECT_LE(std::abs(cells - squareCells), 2) << degrees << " degrees, level " << l << ": " << cells << " cells";
      EXPECT_LE(cells, 64) << degrees << " degrees, level " << l;
    }
  }
}

TEST(Footprint, ZeroAreaIsDegenerate) {
  EXPECT_TRUE(kernel::glintFootprint(glm::vec2(0.01f, 0.0f), glm::vec2(0.0f), 8.0f, 27.0f, 16).degenerate);
}

}  // namespace
}  // namespace glint
