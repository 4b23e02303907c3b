// The cost tiers (`--quality`, docs/cli.md "Cost tiers"): each tier is the documented preset of the
// footprint policy, anti-aliasing and shadow cascades; the commands take it, an option given beside it
// wins, and a bad tier is one line naming --quality.
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "gl/renderer.h"
#include "test_support.h"

namespace glint {
namespace {

using namespace glint::test;

// The rows of docs/cli.md's tier table: | `name` | `footprint` | `anti-aliasing` | cascades | ...
struct DocumentedTier {
  std::string name, footprint, antiAliasing;
  int cascades;
};

std::vector<DocumentedTier> documentedTiers() {
  const std::string document = slurp(std::filesystem::path(GLINT_SOURCE_DIR) / "docs" / "cli.md");
  const std::regex row(R"(^\| `(low|medium|high|exact)` \| `([^`]+)` \| `([^`]+)` \| (\d) \|)");
  std::vector<DocumentedTier> tiers;
  std::istringstream lines(document);
  std::string line;
  while (std::getline(lines, line)) {
    std::smatch match;
    if (std::regex_search(line, match, row)) tiers.push_back({match[1], match[2], match[3], std::stoi(match[4])});
  }
  return tiers;
}

TEST(QualityTiers, PresetsAreTheDocumentedSettings) {
  const std::vector<DocumentedTier> documented = documentedTiers();
  const std::vector<gl::QualityPreset>& presets = gl::qualityPresets();
  ASSERT_EQ(documented.size(), presets.size()) << "docs/cli.md's tier table has another number of rows";
  for (std::size_t i = 0; i < presets.size(); ++i) {
    SCOPED_TRACE(presets[i].name);
    EXPECT_EQ(documented[i].name, presets[i].name);
    // The footprint as the policy parser names it, so that the documented spelling is a valid policy.
    EXPECT_EQ(documented[i].footprint, footprintPolicyName(footprintPolicyFromString(presets[i].footprint)));
    EXPECT_EQ(documented[i].antiAliasing, gl::toString(presets[i].antiAliasing));
    EXPECT_EQ(documented[i].cascades, presets[i].shadowCascades);
  }
  // exact is what a frame draws without options.
  const gl::QualityPreset& exact = gl::qualityPreset("exact");
  const gl::FrameSettings defaults;
  EXPECT_EQ(footprintPolicyName(footprintPolicyFromString(exact.footprint)), footprintPolicyName(defaults.footprintPolicy));
  EXPECT_EQ(exact.antiAliasing, defaults.antiAliasing);
  EXPECT_EQ(exact.shadowCascades, defaults.shadowCascades);
}

TEST(QualityCli, BadTiersGiveOneLineNamingTheOption) {
  const auto folder = temporaryFolder("quality_cli");
  for (const std::string command : {"render sphere --size 16x16 -o x.png", "bench sphere --size 16x16 --frames 1 --warmup 0",
                                    "aa-error sphere --size 16x16 --reference 1 --sequence 2", "view sphere --frames 1"}) {
    for (const std::string tier : {"ultra", "Low", "2", "''"}) {
      const RunResult result = runGlint(folder, command + " --quality " + tier);
      expectOneLineError(result, "--quality");
      if (tier != "''") EXPECT_NE(result.err.find(tier), std::string::npos) << command << " --quality " << tier;
    }
  }
  EXPECT_FALSE(std::filesystem::exists(folder / "x.png"));
  // A tier given twice would be measured, and reported, twice.
  expectOneLineError(runGlint(folder, "aa-error sphere --size 16x16 --reference 1 --sequence 2 --quality low --quality low"),
                     "--quality 'low' is given twice");
}

TEST(QualityCli, ATierSetsItsSettingsAndOptionsGivenWin) {
  const auto folder = temporaryFolder("quality_bench");
  const std::string bench = "bench sphere --size 16x16 --frames 1 --warmup 0 --json --quality low";
  for (const auto& [extra, footprint, antiAliasing, cascades] :
       std::vector<std::tuple<std::string, std::string, std::string, int>>{
           {"", "", "", 0}, {" --aa ggaa", "", "ggaa", 0}, {" --footprint exact", "exact", "", 0},
           {" --shadow-cascades 3", "", "", 3}}) {
    SCOPED_TRACE(extra);
    const RunResult result = runGlint(folder, bench + extra);
    ASSERT_EQ(result.exitCode, 0) << result.err;
    const nlohmann::json report = nlohmann::json::parse(result.out);
    const gl::QualityPreset& low = gl::qualityPreset("low");
    EXPECT_EQ(report["quality"], "low");
    EXPECT_EQ(report["footprint"], footprint.empty() ? footprintPolicyName(footprintPolicyFromString(low.footprint)) : footprint);
    EXPECT_EQ(report["anti_aliasing"], antiAliasing.empty() ? gl::toString(low.antiAliasing) : antiAliasing);
    EXPECT_EQ(report["shadow_cascades"], cascades == 0 ? low.shadowCascades : cascades);
  }
  // render says what it drew.
  const RunResult render = runGlint(folder, "render sphere --size 16x16 -o low.png --quality low");
  ASSERT_EQ(render.exitCode, 0) << render.err;
  EXPECT_NE(render.err.find("anti-aliasing none"), std::string::npos) << render.err;
  EXPECT_NE(render.err.find("footprint " + footprintPolicyName(footprintPolicyFromString(gl::qualityPreset("low").footprint))),
            std::string::npos)
      << render.err;
}

TEST(QualityCli, AaErrorMeasuresEveryTierAgainstThePapersReference) {
  const auto folder = temporaryFolder("quality_aa_error");
  const RunResult result = runGlint(folder, "aa-error sphere --size 32x32 --reference 2 --sequence 2 --json "
                                            "--quality low --quality exact");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  const nlohmann::json scene = nlohmann::json::parse(result.out)["scenes"][0];
  // exact is the paper's footprint anti-aliased with four cascades: the scene's own ggaa+lean figures.
  EXPECT_EQ(scene["qualities"]["exact"], scene["ggaa+lean"]);
  // low walks other cells without the filter: other figures.
  EXPECT_NE(scene["qualities"]["low"]["relative_rmse"], scene["qualities"]["exact"]["relative_rmse"]);
  EXPECT_GT(scene["qualities"]["low"]["relative_flicker"].get<double>(), 0.0);
}

}  // namespace
}  // namespace glint
