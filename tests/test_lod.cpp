// The consistent level-of-detail construction (kernel glintLodCell, glintBlockMarginal;
// docs/method.md 2.7): an own cell's P22 is the mean of its four children's, which the paper's
// construction does not give; the P-NDF stays normalised and converges to the smooth target.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "glint/microfacet_sampling.h"
#include "test_support.h"

namespace glint {
namespace {

using namespace glint::test;

// One cell's P22 at a slope: what glintLevelP22 adds for it, by the kernel's per-cell functions.
double cellP22(kernel::GlintDictionaryView dict, const GlintParameters& p, const kernel::GlintCell& cell,
               glm::vec2 slope) {
  if (cell.smoothLimit) return kernel::glintTargetP22(p.ndf, slope, p.alpha, p.rho);
  if (cell.ggxTail) return kernel::glintStudentTailSlopeP22(slope, kernel::glintBeckmannSlopeCovariance(p.alpha, p.rho));
  if (!cell.readsDictionary) return 0.0;
  const glm::vec2 unscaled = kernel::glintUnscaledSlope(dict, p, slope) * cell.unscale;
  return static_cast<double>(kernel::glintCellMarginals(dict, cell.dictionaryLevel,
                                                        kernel::glintCellDistributions(dict, cell.hash), cell.complement,
                                                        kernel::glintCellRotation(cell.hash), unscaled)) *
         cell.scalePrecision * kernel::glintScalingJacobian(dict, p);
}

// The cell (x, y) of `level` as the P-SDF's walk draws it.
kernel::GlintCell drawnCell(kernel::GlintDictionaryView dict, const GlintParameters& p, int x, int y, int level) {
  const kernel::GlintLevelDraw draw = kernel::glintLevelDraw(dict, p, p.logDensity, level);
  const kernel::GlintLevelDraw parentDraw = kernel::glintNextLevelDraw(dict, p, p.logDensity, level, draw);
  return kernel::glintLodCell(dict, p, draw, parentDraw, x, y, level);
}

// A slope where a dictionary cell reflects: one of its own, drawn from its marginals (the
// sampler's inversion), rotated and scaled back as microfacet_sampling.cpp does.
glm::vec2 slopeOfCell(kernel::GlintDictionaryView dict, const GlintParameters& p, const kernel::GlintCell& cell,
                      Pcg32& rng) {
  const glm::ivec2 distributions = kernel::glintCellDistributions(dict, cell.hash);
  const float x = sampling::sampleDictionaryMarginal(dict, cell.dictionaryLevel, distributions.x, cell.complement.x,
                                                     static_cast<float>(rng.nextOpenUnit()));
  const float y = sampling::sampleDictionaryMarginal(dict, cell.dictionaryLevel, distributions.y, cell.complement.y,
                                                     static_cast<float>(rng.nextOpenUnit()));
  const glm::vec2 rotation = kernel::glintCellRotation(cell.hash);
  const glm::vec2 rotated(rotation.x * x - rotation.y * y, rotation.y * x + rotation.x * y);
  return kernel::glintScaledSlope(dict, p, rotated / cell.unscale);
}

TEST(ConsistentLod, OwnCellIsTheMeanOfItsFourChildren) {
  // Random own cells (the top level's, and those the tree does not make blocks) at random levels,
  // positions (negative and past the period too), roughnesses, correlations, both targets, relative
  // areas and density randomisations, so random dictionary levels, distributions and rotations; at
  // slopes drawn from the coarse cell itself and at random ones. In consistent mode the mean of the
  // four children's P22 is the coarse cell's to float rounding (2e-6 of the values' magnitude); in
  // the paper's the children's own draws make it differ (by more than 1% at most of the slopes
  // where the coarse cell reflects).
  const kernel::GlintDictionaryView dict = defaultDictionary().view();
  Pcg32 rng(2107, 1);
  int compared = 0, coarseReflects = 0, paperDiffers = 0, blocksSeen = 0;
  double worst = 0.0;
  for (int i = 0; i < 20000 && compared < 4000; ++i) {
    GlintParameters p = defaultGlintParameters();
    p.alpha = glm::vec2(uniform(rng, 0.05f, 1.0f), uniform(rng, 0.05f, 1.0f));
    p.rho = rng.nextBelow(3) == 0 ? uniform(rng, -0.9f, 0.9f) : 0.0f;
    p.ndf = static_cast<int>(rng.nextBelow(2));
    p.relativeArea = rng.nextBelow(3) == 0 ? uniform(rng, 0.2f, 1.0f) : 1.0f;
    p.densityRandomisation = uniform(rng, 0.0f, 3.0f);
    p.patternSeed = rng.next();
    p.logDensity = uniform(rng, 8.0f, 40.0f);
    p.lod = kernel::GLINT_LOD_CONSISTENT;
    const int level = 1 + static_cast<int>(rng.nextBelow(static_cast<std::uint32_t>(dict.numLevels - 1)));
    const int across = 1 << (16 - level);  // the level's cells in one period
    const int x = static_cast<int>(rng.nextBelow(static_cast<std::uint32_t>(3 * across))) - across;
    const int y = static_cast<int>(rng.nextBelow(static_cast<std::uint32_t>(3 * across))) - across;
    if (kernel::glintCellIsBlock(x, y, level, dict.numLevels)) continue;  // its children draw their own
    const kernel::GlintCell coarse = drawnCell(dict, p, x, y, level);
    if (coarse.smoothLimit || (coarse.readsDictionary && coarse.dictionaryLevel == 0)) continue;  // no blocks
    ++compared;
    for (int k = 0; k < 4; ++k) {
      const glm::vec2 slope = coarse.readsDictionary && k < 3
                                  ? slopeOfCell(dict, p, coarse, rng)
                                  : glm::vec2(uniform(rng, -2.0f, 2.0f), uniform(rng, -2.0f, 2.0f)) * p.alpha;
      const double expected = cellP22(dict, p, coarse, slope);
      double mean = 0.0, magnitude = std::abs(expected), paperMean = 0.0;
      GlintParameters paper = p;
      paper.lod = kernel::GLINT_LOD_PAPER;
      for (int child = 0; child < 4; ++child) {
        const int cx = 2 * x + (child & 1), cy = 2 * y + (child >> 1);
        const kernel::GlintCell fine = drawnCell(dict, p, cx, cy, level - 1);
        blocksSeen += fine.complement.x | fine.complement.y;
        const double value = cellP22(dict, p, fine, slope);
        mean += 0.25 * value;
        magnitude += std::abs(value);
        paperMean += 0.25 * cellP22(dict, paper, drawnCell(dict, paper, cx, cy, level - 1), slope);
      }
      const double tolerance = 2e-6 * magnitude + 1e-30;
      worst = std::max(worst, std::abs(mean - expected) / std::max(magnitude, 1e-30));
      ASSERT_NEAR(mean, expected, tolerance) << "cell " << x << "," << y << " level " << level << " dictionary level "
                                             << coarse.dictionaryLevel << " slope " << slope.x << "," << slope.y;
      if (expected > 1e-3) {
        ++coarseReflects;
        paperDiffers += std::abs(paperMean - expected) > 0.01 * expected;
      }
    }
  }
  std::printf("%d own cells, %d slopes where they reflect, %d child blocks; worst |mean - coarse| / magnitude %.2e; "
              "paper's children differ at %d of those slopes\n",
              compared, coarseReflects, blocksSeen, worst, paperDiffers);
  EXPECT_EQ(compared, 4000);
  EXPECT_GT(coarseReflects, 4000);
  EXPECT_GT(blocksSeen, 4000);  // the complement blocks are exercised, not only first children
  EXPECT_GT(paperDiffers, coarseReflects * 8 / 10);
}

TEST(ConsistentLod, FourSeventhsOfTheCellsAreOwn) {
  // own(top) and own(j) = not (not first child and own(j + 1)): deep in the tree the share of own
  // cells p satisfies p = 1 - (3/4) p, 4/7. Over a 512 x 512 window of level 0 within 1%; the top
  // level's cells are all own; a first child is never a block.
  const int levels = defaultDictionary().view().numLevels;
  int own = 0;
  for (int y = 0; y < 512; ++y) {
    for (int x = 0; x < 512; ++x) {
      own += kernel::glintCellIsBlock(x + 1000, y + 3000, 0, levels) ? 0 : 1;
      if ((x & 1) == 0 && (y & 1) == 0) ASSERT_FALSE(kernel::glintCellIsBlock(x + 1000, y + 3000, 0, levels));
    }
  }
  EXPECT_NEAR(own / (512.0 * 512.0), 4.0 / 7.0, 0.01);
  for (int x = -2; x < 4; ++x) EXPECT_FALSE(kernel::glintCellIsBlock(x, 1, levels - 1, levels));
}

TEST(ConsistentLod, ComplementMarginalsIntegrateToOne) {
  // 2 p_{l+1} - p_l integrates to 2 - 1 under the texel convention, within the tables' own 1e-3.
  const Dictionary& dictionary = defaultDictionary();
  const kernel::GlintDictionaryView dict = dictionary.view();
  const double domain = dictionary.parameters().slopeDomain();
  for (int level = 0; level + 1 < dict.numLevels; level += 3) {
    for (int distribution : {0, 50, 191}) {
      constexpr int kSteps = 4000;
      double integral = 0.0;
      for (int k = 0; k < kSteps; ++k) {
        const float x = static_cast<float>((k + 0.5) * domain / kSteps);
        integral += 2.0 * kernel::glintBlockMarginal(dict, level, distribution, 1, x) * domain / kSteps;
      }
      EXPECT_NEAR(integral, 1.0, 1e-3) << "level " << level << " distribution " << distribution;
    }
  }
}

// Slope-space grid as GlintBrdfStat's (test_glint_brdf.cpp): 200 x 200 midpoints over the support.
double p22Integral(const GlintBsdf& bsdf, glm::vec2 alpha) {
  return integrateOverSlopes([&](glm::vec2 slope) { return bsdf.p22(slope); },
                             glintSlopeExtent(defaultDictionary(), alpha), 200);
}

TEST(ConsistentLodStat, PNdfIsNormalisedForEveryFootprint) {
  // As GlintBrdfStat.PNdfIsNormalisedForEveryFootprint, in consistent mode: with MRA = 1 the
  // integral of P22_P over the slope plane is 1 within 0.5% for every footprint, both targets'
  // Beckmann (the GGX tail reaches past the grid).
  Pcg32 rng(2107, 2);
  double worst = 0.0;
  for (int i = 0; i < 120; ++i) {
    GlintParameters p = defaultGlintParameters();
    p.alpha = glm::vec2(uniform(rng, 0.05f, 1.0f), uniform(rng, 0.05f, 1.0f));
    p.logDensity = uniform(rng, 12.0f, 40.0f);
    p.lod = kernel::GLINT_LOD_CONSISTENT;
    const SurfaceFootprint footprint = randomFootprint(rng, 1e-5f, 3e-2f);
    const double integral = p22Integral(GlintBsdf(defaultDictionary(), p, footprint), p.alpha);
    worst = std::max(worst, std::abs(integral - 1.0));
    EXPECT_NEAR(integral, 1.0, 5e-3) << "case " << i << " log density " << p.logDensity;
  }
  RecordProperty("worst_deviation", std::to_string(worst));
}

TEST(ConsistentLodStat, MeanOverPositionsIsTheTargetAndDenseLayersConvergeToIt) {
  // The blocks' complements average to the target over the distributions as the levels do (the
  // stratified dictionary's levels all have the target's mean), so the mean of D_P over 20000
  // positions matches Beckmann within 2% at moderate density, as the paper's construction
  // (GlintBrdfStat.MeanOverPositionsIsBeckmannAtModerateDensity). As the density grows each
  // position's P-NDF converges to Beckmann's: at slopes within 1.5 alpha, the largest deviation
  // over 300 positions is under 6% at log density 42 (dictionary levels 14 to 16) and under 3% at
  // 46, as the paper's construction's (printed beside it).
  const glm::vec2 alpha(0.3f, 0.5f);
  GlintParameters p = defaultGlintParameters();
  p.alpha = alpha;
  p.logDensity = 22.0f;
  p.lod = kernel::GLINT_LOD_CONSISTENT;
  const CookTorranceBsdf beckmann(alpha);
  for (glm::vec2 slopeOverAlpha : {glm::vec2(0.0f), glm::vec2(0.3f, -0.2f), glm::vec2(-0.6f, 0.5f)}) {
    const glm::vec3 m = glm::normalize(glm::vec3(-slopeOverAlpha * alpha, 1.0f));
    EXPECT_NEAR(meanNdfOverPositions(p, m, 20000, 4) / beckmann.ndf(m), 1.0, 0.02)
        << "slope/alpha " << slopeOverAlpha.x << "," << slopeOverAlpha.y;
  }
  GlintParameters paper = p;
  paper.lod = kernel::GLINT_LOD_PAPER;
  Pcg32 rng(2107, 3);
  for (const auto& [logDensity, bound] : {std::pair{42.0f, 0.06}, std::pair{46.0f, 0.03}}) {
    p.logDensity = paper.logDensity = logDensity;
    double worst = 0.0, paperWorst = 0.0;
    for (int i = 0; i < 300; ++i) {
      const SurfaceFootprint footprint = randomFootprint(rng, 1e-4f, 1e-3f);
      const glm::vec2 slope = glm::vec2(uniform(rng, -1.5f, 1.5f), uniform(rng, -1.5f, 1.5f)) * alpha;
      const glm::vec3 m = glm::normalize(glm::vec3(-slope, 1.0f));
      const auto deviation = [&](const GlintParameters& parameters) {
        const GlintBsdf bsdf(defaultDictionary(), parameters, footprint);
        return std::abs(kernel::glintNdfFromP22(bsdf.p22(slope), m.z) / beckmann.ndf(m) - 1.0);
      };
      worst = std::max(worst, deviation(p));
      paperWorst = std::max(paperWorst, deviation(paper));
    }
    std::printf("log density %.0f: largest |D_P / Beckmann - 1| over 300 positions %.4f (paper's construction %.4f)\n",
                logDensity, worst, paperWorst);
    EXPECT_LT(worst, bound) << "log density " << logDensity;
  }
}

// `glint lod-consistency` (docs/antialiasing.md, "Level-of-detail consistency") measures both
// constructions on the same frames: the consistent one's children share their parent's rotation,
// so its glint directions are more aligned than the paper's independent cells (measured 0.67
// against 0.43 in 2 x 2 windows on this sphere; independent angles give 0.43); each figure is a
// share or a range of the layer's energy. A bad --lod is one line naming it.
TEST(LodConsistencyCli, MeasuresBothConstructionsOnTheSameFrames) {
  const auto folder = temporaryFolder("lod_consistency_cli");
  const RunResult result = runGlint(folder, "lod-consistency sphere --size 32x32 --frames 4 --json");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  const nlohmann::json modes = nlohmann::json::parse(result.out)["scenes"][0]["modes"];
  ASSERT_TRUE(modes.contains("paper") && modes.contains("consistent")) << modes.dump();
  for (const char* mode : {"paper", "consistent"}) {
    SCOPED_TRACE(mode);
    const nlohmann::json& m = modes[mode];
    EXPECT_EQ(m["drift"].size(), 4u);
    EXPECT_EQ(m["reference_drift"].size(), 4u);
    for (const char* share : {"persistence", "reference_persistence"}) {
      EXPECT_GT(m[share].get<double>(), 0.0) << share;
      EXPECT_LE(m[share].get<double>(), 1.0) << share;
    }
    EXPECT_GE(m["popping"].get<double>(), 0.0);
    EXPECT_GT(m["relative_rmse"].get<double>(), 0.0);
  }
  EXPECT_GT(modes["consistent"]["alignment_2x2"].get<double>(), modes["paper"]["alignment_2x2"].get<double>() + 0.1);

  const RunResult bad = runGlint(folder, "lod-consistency sphere --size 32x32 --frames 4 --lod fast");
  EXPECT_NE(bad.exitCode, 0);
  EXPECT_EQ(bad.err, "glint: error: --lod must be \"paper\" or \"consistent\", got \"fast\"\n");
}

}  // namespace
}  // namespace glint
