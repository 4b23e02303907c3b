// Footprint policies (kernel::GlintFootprintPolicy, glintPixelFootprint; docs/antialiasing.md,
// "Footprint policies"): exact is the paper's footprint bit for bit; cells=K bounds the walk that
// the P-SDF and the sampler take (counted with the walk's own steps, glintWalkStart/Step), without
// changing the microfacets seen; every policy keeps the P-NDF normalised and the convergence to
// Cook-Torrance; the command line refuses bad policies in one line.
#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "glint/error.h"
#include "test_support.h"

namespace glint {
namespace {

using namespace glint::test;

constexpr int kLevels = 16;  // the default dictionary's L

FootprintPolicy policyOf(const std::string& text) { return footprintPolicyFromString(text); }

// The steps the walk of one level takes: the loop of glintLevelP22 and of the sampler.
int walkSteps(const kernel::GlintFootprint& footprint, glm::vec2 uv, int level) {
  const kernel::GlintCellGrid grid = kernel::glintCellGrid(footprint, kernel::glintWrapUv(uv, kLevels), kLevels, level);
  int steps = 0;
  for (kernel::GlintCellWalk walk = kernel::glintWalkStart(grid); kernel::glintWalkGoing(grid, walk);
       walk = kernel::glintWalkStep(grid, walk)) {
    ++steps;
  }
  return steps;
}

// The most steps of the levels the P-SDF walks: floor(lod), and the next one when it is blended in.
int mostStepsOfTheWalkedLevels(const kernel::GlintFootprint& footprint, glm::vec2 uv) {
  if (footprint.degenerate) return 0;
  const int level = kernel::glintLodLevel(footprint);
  int most = walkSteps(footprint, uv, level);
  if (kernel::glintLodBlend(footprint) > 0.0f) most = std::max(most, walkSteps(footprint, uv, level + 1));
  return most;
}

// Random pixel footprints for the budget: randomFootprint's (sheared, from magnified to minified),
// and thin ellipses of anisotropy up to 10^4 at any orientation, as a grazing plane gives, at uv up
// to a few periods (walk coordinates up to 2^16 cells).
SurfaceFootprint budgetFootprint(Pcg32& rng) {
  if (rng.nextBelow(2) == 0) {
    SurfaceFootprint footprint = randomFootprint(rng, 1e-6f, 1.0f);
    footprint.uv = footprint.uv * 5.0f - 2.0f;
    return footprint;
  }
  const float major = std::exp(uniform(rng, std::log(1e-5f), std::log(2.0f)));
  const float anisotropy = std::exp(uniform(rng, 0.0f, std::log(1e4f)));
  const std::pair<glm::vec2, glm::vec2> axes =
      turnedDerivatives(major, major / anisotropy, uniform(rng, 0.0f, 6.2831853f), uniform(rng, 0.0f, 6.2831853f));
  SurfaceFootprint footprint;
  footprint.uv = uniformPair(rng, glm::vec2(-2.0f), glm::vec2(3.0f));
  footprint.duvdx = axes.first;
  footprint.duvdy = axes.second;
  return footprint;
}

TEST(FootprintPolicy, CellsBoundEveryWalkedLevel) {
  // 20000 random footprints, random K, material anisotropy, density and the other words of the
  // policy: the walk of each level the P-SDF blends in takes at most K steps (a step per cell, and
  // one per line that misses the ellipse). The same footprints under the exact policy exceed K
  // (the test sees walks that are too long), and the bound glintWalkBound holds at every level.
  Pcg32 rng(2112, 1);
  int exceededByExact = 0;
  int raised = 0;
  int shrunk = 0;
  double worstFraction = 0.0;
  double meanFraction = 0.0;
  constexpr int kFootprints = 20000;
  for (int i = 0; i < kFootprints; ++i) {
    const SurfaceFootprint surface = budgetFootprint(rng);
    GlintParameters parameters = defaultGlintParameters();
    parameters.alpha = uniformPair(rng, glm::vec2(0.05f), glm::vec2(1.0f));
    parameters.logDensity = uniform(rng, 10.0f, 45.0f);
    parameters.maxAnisotropy = uniform(rng, 1.0f, 64.0f);
    const int cells = std::array<int, 5>{12, 16, 24, 48, 100}[rng.nextBelow(5)];
    parameters.footprintPolicy.maxCells = static_cast<float>(cells);
    if (rng.nextBelow(4) == 0) parameters.footprintPolicy.maxAnisotropy = uniform(rng, 1.0f, 16.0f);
    if (rng.nextBelow(4) == 0) parameters.footprintPolicy.minBlend = uniform(rng, 0.0f, 1.0f);
    const kernel::GlintFootprint footprint =
        kernel::glintPixelFootprint(surface.duvdx, surface.duvdy, parameters, kLevels);
    const int steps = mostStepsOfTheWalkedLevels(footprint, surface.uv);
    ASSERT_LE(steps, cells) << "case " << i << " lod " << footprint.lod;
    worstFraction = std::max(worstFraction, double(steps) / cells);
    meanFraction += double(steps) / cells / kFootprints;

    GlintParameters exact = parameters;
    exact.footprintPolicy = exactFootprintPolicy();
    const kernel::GlintFootprint paper = kernel::glintPixelFootprint(surface.duvdx, surface.duvdy, exact, kLevels);
    exceededByExact += mostStepsOfTheWalkedLevels(paper, surface.uv) > cells;
    raised += footprint.lod != paper.lod;
    shrunk += footprint.logDensity != paper.logDensity;
    // The bound itself, at a random level at or above the exact footprint's.
    if (!paper.degenerate) {
      const int level = std::min(kLevels - 1, kernel::glintLodLevel(paper) + static_cast<int>(rng.nextBelow(4)));
      EXPECT_LE(walkSteps(paper, surface.uv, level), kernel::glintWalkBound(paper, std::exp2(float(kLevels - 1 - level))))
          << "case " << i << " level " << level;
    }
  }
  EXPECT_GT(exceededByExact, kFootprints / 10);
  EXPECT_GT(raised, kFootprints / 4);
  EXPECT_GT(shrunk, 10);  // the top-level branch is exercised
  EXPECT_GT(worstFraction, 0.7);  // the bound is not vacuous
  RecordProperty("exceeded_by_exact", exceededByExact);
  RecordProperty("mean_steps_over_k", std::to_string(meanFraction));
  RecordProperty("worst_steps_over_k", std::to_string(worstFraction));
}

TEST(FootprintPolicy, ExactIsThePapersFootprintBitForBit) {
  // The zero policy, and an anisotropy clamp at or above the material's, leave glintFootprint's
  // ellipse, LOD and density exactly as they are.
  Pcg32 rng(2112, 2);
  for (int i = 0; i < 5000; ++i) {
    const SurfaceFootprint surface = budgetFootprint(rng);
    GlintParameters parameters = defaultGlintParameters();
    parameters.logDensity = uniform(rng, 10.0f, 45.0f);
    parameters.maxAnisotropy = uniform(rng, 1.0f, 64.0f);
    const kernel::GlintFootprint paper =
        kernel::glintFootprint(surface.duvdx, surface.duvdy, parameters.maxAnisotropy, parameters.logDensity, kLevels);
    for (float aniso : {0.0f, parameters.maxAnisotropy, 64.0f}) {
      parameters.footprintPolicy.maxAnisotropy = aniso;
      const kernel::GlintFootprint policy = kernel::glintPixelFootprint(surface.duvdx, surface.duvdy, parameters, kLevels);
      ASSERT_EQ(policy.majorAxis, paper.majorAxis) << "case " << i;
      ASSERT_EQ(policy.minorAxis, paper.minorAxis) << "case " << i;
      ASSERT_EQ(policy.lod, paper.lod) << "case " << i;
      ASSERT_EQ(policy.logDensity, paper.logDensity) << "case " << i;
      ASSERT_EQ(policy.degenerate, paper.degenerate) << "case " << i;
    }
  }
}

TEST(FootprintPolicy, EachWordDoesWhatItSays) {
  Pcg32 rng(2112, 3);
  int anisotropic = 0;
  int dropped = 0;
  int kept = 0;
  for (int i = 0; i < 5000; ++i) {
    const SurfaceFootprint surface = budgetFootprint(rng);
    GlintParameters parameters = defaultGlintParameters();
    parameters.logDensity = uniform(rng, 10.0f, 45.0f);
    const kernel::GlintFootprint paper = kernel::glintPixelFootprint(surface.duvdx, surface.duvdy, parameters, kLevels);
    if (paper.degenerate) continue;
    // aniso=A: the minor axis at least the major one over A (float rounding: 1e-5).
    GlintParameters clamped = parameters;
    clamped.footprintPolicy = policyOf("aniso=2.5");
    const kernel::GlintFootprint aniso = kernel::glintPixelFootprint(surface.duvdx, surface.duvdy, clamped, kLevels);
    EXPECT_LE(glm::length(aniso.majorAxis) / glm::length(aniso.minorAxis), 2.5f * (1.0f + 1e-5f)) << "case " << i;
    anisotropic += glm::length(paper.majorAxis) > 2.6f * glm::length(paper.minorAxis);
    // drop=W: the LOD goes down to its level exactly when the next level's weight is below W.
    GlintParameters dropping = parameters;
    dropping.footprintPolicy = policyOf("drop=0.3");
    const kernel::GlintFootprint drop = kernel::glintPixelFootprint(surface.duvdx, surface.duvdy, dropping, kLevels);
    const float blend = paper.lod - std::floor(paper.lod);
    EXPECT_EQ(drop.lod, blend < 0.3f ? std::floor(paper.lod) : paper.lod) << "case " << i;
    dropped += blend > 0.0f && blend < 0.3f;
    kept += blend >= 0.3f;
    // cells=K: the LOD only rises; below the top level the ellipse and the density stay (larger
    // cells hold more microfacets each); at the top level it shrinks, and the microfacets it holds,
    // area times e^D, stay within float rounding.
    GlintParameters bounded = parameters;
    bounded.footprintPolicy = policyOf("cells=16");
    const kernel::GlintFootprint cells = kernel::glintPixelFootprint(surface.duvdx, surface.duvdy, bounded, kLevels);
    EXPECT_GE(cells.lod, paper.lod);
    EXPECT_LE(cells.lod, float(kLevels - 1));
    const auto area = [](const kernel::GlintFootprint& f) {
      return double(glm::length(f.majorAxis)) * double(glm::length(f.minorAxis));
    };
    const double seen = std::log(area(cells)) + cells.logDensity;
    EXPECT_NEAR(seen, std::log(area(paper)) + paper.logDensity, 1e-4) << "case " << i;
    if (cells.lod < float(kLevels - 1)) EXPECT_EQ(cells.logDensity, paper.logDensity) << "case " << i;
  }
  EXPECT_GT(anisotropic, 1000);
  EXPECT_GT(dropped, 500);
  EXPECT_GT(kept, 500);
}

// The policies whose P-SDF is checked below: each word alone, and together.
const std::vector<std::string>& testedPolicies() {
  static const std::vector<std::string> policies = {"aniso=4", "cells=12", "cells=24,drop=0.5", "drop=0.05",
                                                    "aniso=2,cells=16,drop=0.9"};
  return policies;
}

TEST(FootprintPolicyStat, PNdfIsNormalisedUnderEveryPolicy) {
  // As GlintBrdfStat.PNdfIsNormalisedForEveryFootprint, under each policy: the integral of P22_P
  // over the slope plane is 1 within 0.5% (the quadrature's own error is below 0.02%), on 60 random
  // footprints each, from magnified to anisotropic and minified.
  for (const std::string& policy : testedPolicies()) {
    Pcg32 rng(2112, 4);
    double worst = 0.0;
    for (int i = 0; i < 60; ++i) {
      GlintParameters parameters = defaultGlintParameters();
      parameters.alpha = uniformPair(rng, glm::vec2(0.05f), glm::vec2(1.0f));
      parameters.logDensity = uniform(rng, 15.0f, 40.0f);
      parameters.footprintPolicy = policyOf(policy);
      const SurfaceFootprint footprint = i % 2 ? randomFootprint(rng, 1e-5f, 3e-2f) : budgetFootprint(rng);
      const GlintBsdf bsdf(defaultDictionary(), parameters, footprint);
      const double integral = integrateOverSlopes([&](glm::vec2 slope) { return bsdf.p22(slope); },
                                                  glintSlopeExtent(defaultDictionary(), parameters.alpha), 200);
      worst = std::max(worst, std::abs(integral - 1.0));
      EXPECT_NEAR(integral, 1.0, 5e-3) << policy << ", case " << i;
    }
    RecordProperty("worst_deviation_" + policy, std::to_string(worst));
  }
}

TEST(FootprintPolicy, ConvergesToCookTorranceAtVeryHighDensityUnderEveryPolicy) {
  // As GlintBrdf.ConvergesToCookTorrancePointwiseAtVeryHighDensity: at log density 80 every cell is
  // in the smooth limit, at any level the policy walks, so glint is Cook-Torrance within 1e-4.
  for (const std::string& policy : testedPolicies()) {
    Pcg32 rng(2112, 5);
    for (int i = 0; i < 500; ++i) {
      GlintParameters parameters = defaultGlintParameters();
      parameters.alpha = uniformPair(rng, glm::vec2(0.05f), glm::vec2(1.0f));
      parameters.logDensity = 80.0f;
      parameters.footprintPolicy = policyOf(policy);
      const SurfaceFootprint footprint = budgetFootprint(rng);
      const glm::vec3 wo = directionAt(uniform(rng, 0.0f, 1.5f), uniform(rng, 0.0f, 6.28f));
      const glm::vec3 wi = directionAt(uniform(rng, 0.0f, 1.5f), uniform(rng, 0.0f, 6.28f));
      const float glint = GlintBsdf(defaultDictionary(), parameters, footprint).f(wo, wi).x;
      const float reference = CookTorranceBsdf(parameters.alpha, parameters.rho).f(wo, wi).x;
      ASSERT_NEAR(glint, reference, 1e-4f * reference) << policy << ", case " << i;
    }
  }
}

TEST(FootprintPolicy, PolicyStringsAreReadAndNamed) {
  EXPECT_EQ(footprintPolicyName(policyOf("exact")), "exact");
  EXPECT_EQ(footprintPolicyName(policyOf("drop=0.5,cells=24")), "cells=24,drop=0.5");
  const FootprintPolicy all = policyOf("aniso=4,cells=24,drop=0.05");
  EXPECT_EQ(all.maxAnisotropy, 4.0f);
  EXPECT_EQ(all.maxCells, 24.0f);
  EXPECT_EQ(all.minBlend, 0.05f);
  EXPECT_EQ(footprintPolicyName(all), "aniso=4,cells=24,drop=0.05");
  for (const char* bad : {"", "cells=0", "cells=11", "cells=24.5", "aniso=0.5", "aniso=65", "drop=-0.1", "drop=1.5",
                          "cells=nan", "drop=inf", "cells=", "cells", "fast", "exact,cells=24", "cells=24,",
                          "cells=24,cells=30", "aniso=4x"}) {
    EXPECT_NE(errorOf([&] { policyOf(bad); }).find("footprint policy"), std::string::npos) << bad;
  }
  // A policy out of range is refused by the BSDF too, by name.
  GlintParameters parameters = defaultGlintParameters();
  parameters.footprintPolicy.maxCells = 3.0f;
  EXPECT_NE(errorOf([&] { validateGlintParameters(parameters); }).find("footprint policy cells"), std::string::npos);
}

TEST(FootprintPolicyCli, BadPoliciesGiveOneLineNamingTheOption) {
  const auto folder = temporaryFolder("footprint_cli");
  for (const std::string command : {"render sphere --size 16x16 -o x.png", "trace sphere --size 8x8 --spp 1 -o x.exr",
                                    "bench sphere --size 16x16 --frames 1 --warmup 0",
                                    "aa-error sphere --size 16x16 --reference 1 --sequence 2", "view sphere --frames 1"}) {
    for (const std::string policy : {"cells=0", "aniso=0.9", "drop=2", "sharp", "cells=nan"}) {
      const RunResult result = runGlint(folder, command + " --footprint " + policy);
      expectOneLineError(result, "--footprint");
      EXPECT_NE(result.err.find(policy), std::string::npos) << command << " --footprint " << policy;
    }
  }
  expectOneLineError(runGlint(folder, "render sphere --size 16x16 -o x.png --footprint exact --footprint cells=24"),
                     "--footprint");
  EXPECT_FALSE(std::filesystem::exists(folder / "x.png"));
  EXPECT_FALSE(std::filesystem::exists(folder / "x.exr"));
}

TEST(FootprintPolicyCli, BenchTimesEveryPolicyInTheSameRun) {
  const auto folder = temporaryFolder("footprint_bench");
  const RunResult result = runGlint(folder, "bench sphere --size 16x16 --frames 1 --warmup 0 --json --footprint exact "
                                            "--footprint cells=24,drop=0.5");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  const nlohmann::json report = nlohmann::json::parse(result.out);
  EXPECT_EQ(report["footprint"], "exact");
  const auto& scene = report["scenes"][0];
  EXPECT_TRUE(scene.contains("glint[cells=24,drop=0.5]"));
  EXPECT_GT(scene["ratio_glint[cells=24,drop=0.5]_cook-torrance"].get<double>(), 0.0);
}

TEST(FootprintPolicyCli, AaErrorMeasuresEveryPolicyAgainstOneReference) {
  const auto folder = temporaryFolder("footprint_aa_error");
  const RunResult result = runGlint(folder, "aa-error sphere --size 32x32 --reference 2 --sequence 2 --json "
                                            "--footprint exact --footprint cells=12");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  const nlohmann::json report = nlohmann::json::parse(result.out);
  const auto& footprints = report["scenes"][0]["footprints"];
  for (const char* policy : {"exact", "cells=12"}) {
    for (const char* mode : {"none", "ggaa", "ggaa+lean"}) {
      EXPECT_GT(footprints[policy][mode]["relative_rmse"].get<double>(), 0.0) << policy << " " << mode;
    }
  }
  // The first policy's figures are also the scene's own (the report without --footprint).
  EXPECT_EQ(report["scenes"][0]["none"], footprints["exact"]["none"]);
  // Another footprint shows other glints: its error differs.
  EXPECT_NE(footprints["cells=12"]["none"]["relative_rmse"], footprints["exact"]["none"]["relative_rmse"]);
}

TEST(FootprintPolicyCli, AaErrorJudgesEachPolicyAgainstItsOwnReferenceOnRequest) {
  const auto folder = temporaryFolder("footprint_aa_error_same");
  const std::string command = "aa-error grazing-rough --size 32x32 --reference 4 --sequence 2 --json --footprint exact "
                              "--footprint cells=12 --reference-footprint ";
  const RunResult paper = runGlint(folder, command + "paper");
  const RunResult same = runGlint(folder, command + "same");
  ASSERT_EQ(paper.exitCode, 0) << paper.err;
  ASSERT_EQ(same.exitCode, 0) << same.err;
  const nlohmann::json paperReport = nlohmann::json::parse(paper.out);
  const nlohmann::json sameReport = nlohmann::json::parse(same.out);
  EXPECT_EQ(paperReport["reference_footprint"], "paper");
  EXPECT_EQ(sameReport["reference_footprint"], "same");
  const auto& byPaper = paperReport["scenes"][0]["footprints"];
  const auto& byOwn = sameReport["scenes"][0]["footprints"];
  // The paper's footprint is its own reference: its figures do not change.
  EXPECT_EQ(byOwn["exact"]["ggaa+lean"], byPaper["exact"]["ggaa+lean"]);
  ASSERT_TRUE(byOwn["cells=12"].contains("reference_mean"));
  // The 2020 model's frame against its own reference, which shows its own glints, against the
  // paper's, which shows another realisation of them (0.46 times the error, measured).
  EXPECT_LT(byOwn["cells=12"]["none"]["relative_rmse"].get<double>(),
            0.8 * byPaper["cells=12"]["none"]["relative_rmse"].get<double>());
  for (const char* mode : {"none", "ggaa", "ggaa+lean"}) {
    EXPECT_NE(byOwn["cells=12"][mode]["relative_rmse"], byPaper["cells=12"][mode]["relative_rmse"]) << mode;
    // The flicker does not depend on the reference.
    EXPECT_EQ(byOwn["cells=12"][mode]["relative_flicker"], byPaper["cells=12"][mode]["relative_flicker"]) << mode;
  }
  expectOneLineError(runGlint(folder, command + "own"), "--reference-footprint");
}

}  // namespace
}  // namespace glint
