// The multiple-scattering compensation (kernel/multiple_scattering.h, Kulla & Conty 2017; docs/method.md,
// "Multiple scattering"): its tables are what glint computes, and with it the white furnace is 1.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <optional>

#include <gtest/gtest.h>

#include "glint/albedo_table_generator.h"
#include "glint/kernel/multiple_scattering.h"
#include "test_support.h"

namespace glint {
namespace {

using namespace glint::test;

constexpr int kTargets[] = {kernel::GLINT_NDF_BECKMANN, kernel::GLINT_NDF_GGX};
constexpr int kMaskings[] = {kernel::GLINT_MASKING_VCAVITY, kernel::GLINT_MASKING_SMITH};

TEST(MultipleScattering, TablesAreWhatGlintComputes) {
  // 48 random nodes of the committed tables (kernel/albedo_tables.h) against glint's quadrature
  // (singleScatteringAlbedo), to the half step of the 16-bit values the header holds (7.7e-6) and the
  // quadrature's own 2e-6; and each E_avg against 2 integral
  // of E mu dmu of the kernel's own lookup (directionalAlbedo), by 4096 midpoints.
  Pcg32 rng(17, 3);
  for (int k = 0; k < 48; ++k) {
    const int table = static_cast<int>(rng.nextBelow(4));
    const int i = 1 + static_cast<int>(rng.nextBelow(kernel::GLINT_ALBEDO_ALPHA_NODES - 1));
    const int j = static_cast<int>(rng.nextBelow(kernel::GLINT_ALBEDO_MU_NODES));
    const double y = static_cast<double>(i) / (kernel::GLINT_ALBEDO_ALPHA_NODES - 1);
    const double x = static_cast<double>(j) / (kernel::GLINT_ALBEDO_MU_NODES - 1);
    const double expected =
        std::min(1.0, singleScatteringAlbedo(table / 2, table % 2, kernel::GLINT_ALBEDO_MAX_ALPHA * y * y, std::max(x * x, 1e-4)));
    const int node = (table * kernel::GLINT_ALBEDO_ALPHA_NODES + i) * kernel::GLINT_ALBEDO_MU_NODES + j;
    EXPECT_NEAR(GLINT_ALBEDO_TABLE_NODE(kernel::GLINT_ALBEDO_WORDS, node), expected, 0.5 / 65535.0 + 2e-6)
        << "table " << table << " alpha node " << i << " mu node " << j;
  }
  for (int ndf : kTargets) {
    for (int masking : kMaskings) {
      for (float alpha : {0.05f, 0.3f, 1.0f, 2.0f}) {
        double sum = 0.0;
        for (int k = 0; k < 4096; ++k) {
          const float mu = (static_cast<float>(k) + 0.5f) / 4096.0f;
          sum += kernel::glintDirectionalAlbedo(ndf, masking, alpha, mu) * mu;
        }
        EXPECT_NEAR(kernel::glintAverageAlbedo(ndf, masking, alpha), 2.0 * sum / 4096.0, 2e-4) << ndf << masking << alpha;
      }
    }
  }
}

TEST(MultipleScatteringCli, AlbedoTablesWritesTheKernelsHeader) {
  // `glint albedo-tables` computes every node again and writes the header: byte for byte the
  // repository's (so the committed tables are what glint computes, all 4224 values).
  const std::filesystem::path folder = temporaryFolder("albedo_tables");
  const RunResult run = runGlint(folder, "albedo-tables -o tables.h");
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const std::string written = slurp(folder / "tables.h");
  ASSERT_FALSE(written.empty());
  EXPECT_TRUE(written == slurp(std::filesystem::path(GLINT_SOURCE_DIR) / "src/glint/kernel/albedo_tables.h"))
      << "src/glint/kernel/albedo_tables.h differs from what glint albedo-tables writes";
}

// The directional albedo with F = 1 of a single-scattering BRDF `single` plus, when the target has
// it, the compensation lobe: the microfacet part over the half-vector slope plane
// (integrateOverWholeSlopePlane out to `reach` alpha, cells x cells; dwi = 4 (wo.m) m.z^3 ds), the
// lobe (smooth) by a 256 x 256 midpoint grid over the hemisphere in (cos theta, phi).
double furnace(const std::function<float(glm::vec3, glm::vec3)>& single, glm::vec2 alpha, glm::vec3 wo,
               const MicrofacetTarget& target, int cells, float reach) {
  const double microfacets = integrateOverWholeSlopePlane(
      [&](glm::vec2 s) {
        const glm::vec3 m = glm::normalize(glm::vec3(-s.x, -s.y, 1.0f));
        const float woDotM = glm::dot(wo, m);
        if (woDotM <= 0.0f) return 0.0;
        const glm::vec3 wi = 2.0f * woDotM * m - wo;
        if (wi.z <= 0.0f) return 0.0;
        return double(single(wo, wi)) * wi.z * 4.0 * woDotM * std::pow(double(m.z), 3.0);
      },
      alpha, cells, reach);
  if (!target.multipleScattering) return microfacets;
  double lobe = 0.0;
  constexpr int kCells = 256;
  for (int a = 0; a < kCells; ++a) {
    const float mu = (static_cast<float>(a) + 0.5f) / kCells;
    for (int b = 0; b < kCells; ++b) {
      const float phi = (static_cast<float>(b) + 0.5f) / kCells * 6.2831853f;
      const float sine = std::sqrt(1.0f - mu * mu);
      const glm::vec3 wi(sine * std::cos(phi), sine * std::sin(phi), mu);
      lobe += double(kernel::glintMultipleScatteringReflectance(target.ndf, target.masking, alpha, wo, wi)) * mu;
    }
  }
  return microfacets + lobe * (2.0 * M_PI / (kCells * kCells));
}

TEST(MultipleScatteringStat, CookTorranceWhiteFurnaceIsOneWithCompensation) {
  // F = 1, no absorption: with the compensation the albedo is 1 within 1% (the albedo tables'
  // interpolation error, measured 0.25% at worst; the loss it compensates is tens of percent at
  // alpha 1)
  // at every view angle from 0 to 88 degrees, for alpha 0.05 to 1, both targets, both maskings.
  // Without it the loss is printed (docs/method.md, "Multiple scattering").
  double worst = 0.0;
  for (int ndf : kTargets) {
    for (int masking : kMaskings) {
      for (float alpha : {0.05f, 0.1f, 0.2f, 0.35f, 0.5f, 0.75f, 1.0f}) {
        std::printf("furnace %-8s %-8s alpha %.2f:", ndf == kernel::GLINT_NDF_GGX ? "ggx" : "beckmann",
                    masking == kernel::GLINT_MASKING_SMITH ? "smith" : "v-cavity", alpha);
        for (float degrees : {0.0f, 30.0f, 60.0f, 75.0f, 85.0f, 88.0f}) {
          const glm::vec3 wo = directionAt(glm::radians(degrees), 0.3f);
          const glm::vec2 a(alpha);
          const CookTorranceBsdf bsdf(a, 0.0f, Fresnel::none(), Spectrum(1.0f), MicrofacetTarget{ndf, masking, false});
          const auto single = [&](glm::vec3 o, glm::vec3 i) { return bsdf.f(o, i).x; };
          const double without = furnace(single, a, wo, MicrofacetTarget{ndf, masking, false}, 500, 1e4f);
          const double with = furnace(single, a, wo, MicrofacetTarget{ndf, masking, true}, 500, 1e4f);
          std::printf(" %2.0f deg %.4f -> %.4f", degrees, without, with);
          worst = std::max(worst, std::abs(with - 1.0));
          EXPECT_NEAR(with, 1.0, 0.01) << "ndf " << ndf << " masking " << masking << " alpha " << alpha << " at "
                                       << degrees << " degrees";
        }
        std::printf("\n");
      }
    }
  }
  std::printf("compensated white furnace: largest deviation from 1: %.4f\n", worst);
}

TEST(MultipleScatteringStat, GlintWhiteFurnaceAveragedOverPositionsIsOneWithCompensation) {
  // The glint BRDF with GGX, Smith and the compensation (log density 22, footprints of 1e-3 uv,
  // glints): its albedo averaged over positions is 1 within 1% (as CookTorranceWhiteFurnace...;
  // the Monte Carlo mean's standard error is printed and stays under 0.3%), at four
  // view angles and three roughnesses, as the mean P-NDF is the target's. Measured as the mean
  // Monte Carlo weight f cos / pdf of 2 x 10^5 samples of sample(), each at its own random position
  // (empty samples count 0): the mean over positions and directions of the albedo. Without the
  // compensation the same mean is the target's single-scattering albedo, printed beside it.
  constexpr int kSamples = 200000;
  for (float alpha : {0.1f, 0.4f, 1.0f}) {
    for (float degrees : {0.0f, 45.0f, 70.0f, 85.0f}) {
      const glm::vec3 wo = directionAt(glm::radians(degrees), 0.9f);
      double means[2];
      double standardError = 0.0;
      for (int compensated = 0; compensated < 2; ++compensated) {
        GlintParameters parameters = defaultGlintParameters();
        parameters.alpha = glm::vec2(alpha);
        parameters.logDensity = 22.0f;
        parameters.ndf = kernel::GLINT_NDF_GGX;
        parameters.masking = kernel::GLINT_MASKING_SMITH;
        parameters.multipleScattering = compensated == 1;
        Pcg32 rng(31, static_cast<std::uint64_t>(alpha * 100.0f + degrees));
        double sum = 0.0;
        double sum2 = 0.0;
        for (int i = 0; i < kSamples; ++i) {
          SurfaceFootprint footprint;
          footprint.uv = uniformPair(rng, glm::vec2(0.0f), glm::vec2(1.0f));
          footprint.duvdx = glm::vec2(1e-3f, 0.0f);
          footprint.duvdy = glm::vec2(0.0f, 1e-3f);
          const float uChoice = uniform(rng, 0.0f, 1.0f);
          const glm::vec2 u = uniformPair(rng, glm::vec2(0.0f), glm::vec2(1.0f));
          const std::optional<BsdfSample> s = GlintBsdf(defaultDictionary(), parameters, footprint).sample(wo, uChoice, u);
          const double w = s ? s->weight.x : 0.0;
          sum += w;
          sum2 += w * w;
        }
        means[compensated] = sum / kSamples;
        standardError = std::sqrt(std::max(0.0, sum2 / kSamples - means[compensated] * means[compensated]) / kSamples);
      }
      std::printf("glint furnace alpha %.2f at %2.0f degrees, mean over positions: %.4f without, %.4f +- %.4f with "
                  "the compensation\n", alpha, degrees, means[0], means[1], standardError);
      EXPECT_NEAR(means[1], 1.0, 0.01) << "alpha " << alpha << " at " << degrees << " degrees";
      EXPECT_LT(standardError, 0.003);  // so that the 1% means something
    }
  }
}

}  // namespace
}  // namespace glint
