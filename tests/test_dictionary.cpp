// The dictionary: the paper's properties (normalisation, limit, nesting), our stratification,
// determinism, the file format and its failure modes, and the authors' EXR dictionary.
#include <algorithm>
#include <cmath>
#include <fstream>

#include <gtest/gtest.h>
#include <tbb/task_arena.h>
#include <tinyexr.h>

#include "glint/dictionary_exr.h"
#include "glint/error.h"
#include "glint/file_io.h"
#include "glint/half.h"
#include "test_support.h"

namespace glint {
namespace {

using namespace glint::test;

// Every marginal of every level integrates to 1 within 1e-3: binary16 rounding of 64 texels moves
// an integral by about 1e-4, and an unnormalised level (a missing 1/N, a wrong texel width) is off
// by far more. The quadrature is a 64-samples-per-texel
// midpoint rule over the interpolated marginal, independent of the generator's trapezoid sum.
void expectNormalised(const Dictionary& dictionary) {
  const auto levels = computeStatistics(dictionary);
  for (std::size_t l = 0; l < levels.size(); ++l) {
    EXPECT_NEAR(levels[l].minIntegral, 1.0, 1e-3) << "level " << l;
    EXPECT_NEAR(levels[l].maxIntegral, 1.0, 1e-3) << "level " << l;
  }
}

TEST(DictionaryStat, EveryMarginalIntegratesToOne) { expectNormalised(defaultDictionary()); }

TEST(DictionaryStat, IndependentPlacementIntegratesToOne) {
  DictionaryParameters parameters;
  parameters.placement = LobePlacement::Independent;
  expectNormalised(generateDictionary(parameters));
}

TEST(DictionaryStat, AuthorsDictionaryUnderOurInterpolation) {
  // Not a property we require of the authors' data, but what users should know
  // (docs/dictionary.md): under our interpolation (linear, falling to 0 at 4 sigma_d) the
  // authors' marginals integrate to 0.9932..1.0003. The few below 0.999 have a lobe crossing the
  // domain's end, whose mass beyond 4 sigma_d their normalisation counts and the table drops.
  if (!authorsDictionary()) GTEST_SKIP() << "needs ../shared/reference/dict_16_192_64_0p5_0p02 (the authors' published dictionary, from their code release; not in the repository)";
  for (const LevelStatistics& level : computeStatistics(*authorsDictionary())) {
    EXPECT_GT(level.minIntegral, 0.99);
    EXPECT_LT(level.maxIntegral, 1.001);
  }
}

TEST(DictionaryStat, FinestLevelHasTheLimitStandardDeviation) {
  // As l grows, p_l tends to Normal(0, sigma_d^2 + s^2). At the finest level (32768 lobes each)
  // the mean standard deviation over the 192 marginals must be within 1%: 192 marginals of
  // 32768 lobes each average their sampling errors (below) down to 0.03%, so 1% leaves room only
  // for the binary16 texels and the tabulation's width, not for a wrong lobe width. One marginal alone is a random sample of 32768 lobes: its std has a relative
  // sampling error of 1/sqrt(2 * 32768) = 0.39%, so each must be within 4 such errors (1.6%).
  const Dictionary& dictionary = defaultDictionary();
  const double target = targetStd(dictionary.parameters());
  const LevelStatistics finest = computeStatistics(dictionary).back();
  EXPECT_NEAR(finest.meanStd / target, 1.0, 0.01);
  EXPECT_NEAR(finest.minStd / target, 1.0, 0.016);
  EXPECT_NEAR(finest.maxStd / target, 1.0, 0.016);
}

// Nesting, checked on the tabulated data: 2^(l+1) p_{l+1} sums every lobe of 2^l p_l plus new
// ones, so it dominates it texel by texel, up to two effects: (a) each level is normalised on its
// own, and a lobe that falls past 4 sigma_d loses mass and shifts a level's normalisation by up to
// 2^-l (measured worst case: 0.32%), hence 1% relative; (b) binary16 stores values under 6.1e-5
// as subnormals with an absolute step of 6e-8, hence two such steps scaled by 2^(l+1).
int nestingViolations(const Dictionary& d, int distributionShift) {
  const DictionaryParameters& p = d.parameters();
  int violations = 0;
  for (int l = 0; l + 1 < p.numLevels; ++l) {
    const double slack = std::ldexp(2.4e-7, l + 1);
    for (int n = 0; n < p.numDistributions; ++n) {
      const int m = (n + distributionShift) % p.numDistributions;
      for (int k = 0; k < p.texelsPerDistribution; ++k) {
        const double coarse = std::ldexp(d.texel(l, n, k), l);
        const double fine = std::ldexp(d.texel(l + 1, m, k), l + 1);
        if (fine < coarse * (1.0 - 1e-2) - slack) ++violations;
      }
    }
  }
  return violations;
}

TEST(Dictionary, LevelsAreNested) {
  EXPECT_EQ(nestingViolations(defaultDictionary(), 0), 0);
  // The check can fail: pairing each level with the next level of ANOTHER distribution breaks it.
  EXPECT_GT(nestingViolations(defaultDictionary(), 1), 1000);
}

TEST(Dictionary, LobeMeansOfLevelLArePrefixesOfLevelLPlusOne) {
  DictionaryParameters parameters;
  parameters.numLevels = 8;
  parameters.numDistributions = 6;
  const auto means = generateLobeMeans(parameters);
  ASSERT_EQ(means.size(), 6u);
  for (const auto& distribution : means) ASSERT_EQ(distribution.size(), 128u);
  // Generating fewer levels gives the same first lobes: the levels are prefixes of one sequence.
  parameters.numLevels = 5;
  const auto fewer = generateLobeMeans(parameters);
  for (std::size_t n = 0; n < 6; ++n) {
    for (std::size_t k = 0; k < 16; ++k) EXPECT_EQ(fewer[n][k], means[n][k]);
  }
}

TEST(DictionaryStat, StratifiedLobesMakeEveryLevelUnbiased) {
  // method.md: the mean of a level's marginals is what the spatial average of the glint NDF tends
  // to. The authors' dictionary is 0.19 (L1) from the limit at level 0; stratified placement must
  // bring levels 0 to 4 under 0.03 and beat independent placement at each.
  DictionaryParameters independentParameters;
  independentParameters.placement = LobePlacement::Independent;
  const auto stratified = computeStatistics(defaultDictionary());
  const auto independent = computeStatistics(generateDictionary(independentParameters));
  for (int l = 0; l <= 4; ++l) {
    EXPECT_LT(stratified[l].meanMarginalL1, 0.03) << "level " << l;
    EXPECT_LT(stratified[l].meanMarginalL1, independent[l].meanMarginalL1) << "level " << l;
  }
  if (authorsDictionary()) {
    const auto authors = computeStatistics(*authorsDictionary());
    EXPECT_GT(authors[0].meanMarginalL1, 0.15);  // the bias measured on the authors' dictionary (0.199 at level 0, docs/dictionary.md)
  }
}

TEST(Dictionary, TexelConventionAndInterpolation) {
  // Texel k holds the density at slope k * 4 sigma_d / R; between texels the marginal is linear;
  // it falls to zero at 4 sigma_d and is even.
  const Dictionary& d = defaultDictionary();
  const float spacing = d.parameters().texelSpacing();
  for (int k : {0, 5, 31, 63}) {  // k * spacing lands within float rounding of texel k
    EXPECT_NEAR(d.marginal(7, 3, k * spacing), d.texel(7, 3, k), 4e-6f * d.texel(7, 3, k));
  }
  EXPECT_NEAR(d.marginal(7, 3, 5.5f * spacing), 0.5f * (d.texel(7, 3, 5) + d.texel(7, 3, 6)), 1e-5f);
  EXPECT_NEAR(d.marginal(7, 3, 63.5f * spacing), 0.5f * d.texel(7, 3, 63), 1e-5f);
  EXPECT_FLOAT_EQ(d.marginal(7, 3, -5.0f * spacing), d.marginal(7, 3, 5.0f * spacing));
  EXPECT_EQ(d.marginal(7, 3, d.parameters().slopeDomain()), 0.0f);
}

// The tree levels that the tree LOD construction reads (kernel glintTreeTableLevel, method.md 2.8).
// Each level's partners are a permutation, for any N: every distribution of the level below is
// some distribution's partner once; and tree level k of i holds level 0's distributions i to
// i + 2^k - 1 (mod N), each once while 2^k <= N and each floor(2^k / N) or one more times beyond
// (followed down the partners, as the tables are built).
TEST(Dictionary, TreePartnersArePermutationsAndLevelsAreWindows) {
  for (int n : {1, 2, 3, 7, 64, 192, 1000, 3001, 4096}) {
    kernel::GlintDictionaryView dict{};
    dict.numDistributions = n;
    for (int k = 1; k < 16; ++k) {
      std::vector<int> seen(static_cast<std::size_t>(n), 0);
      for (int i = 0; i < n; ++i) {
        const int partner = kernel::glintTreePartner(dict, k, i);
        ASSERT_TRUE(partner >= 0 && partner < n) << n << " " << k << " " << i;
        ++seen[static_cast<std::size_t>(partner)];
      }
      EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), n) << "N " << n << " level " << k;
    }
    for (int k : {0, 3, 7, 8, 12, 15}) {
      for (int i : {0, n / 2, n - 1}) {
        // The level-0 distributions under (k, i), with multiplicity: the partners' tree, leaf by leaf.
        std::vector<int> count(static_cast<std::size_t>(n), 0);
        std::vector<std::pair<int, int>> stack{{k, i}};
        while (!stack.empty()) {
          const auto [level, distribution] = stack.back();
          stack.pop_back();
          if (level == 0) {
            ++count[static_cast<std::size_t>(distribution)];
            continue;
          }
          stack.push_back({level - 1, distribution});
          stack.push_back({level - 1, kernel::glintTreePartner(dict, level, distribution)});
        }
        const long long lobes = 1LL << k;
        for (int m = 0; m < n; ++m) {
          const long long offset = ((m - i) % n + n) % n;  // m's place in the window from i
          const long long expected = lobes / n + (offset < lobes % n ? 1 : 0);
          ASSERT_EQ(count[static_cast<std::size_t>(m)], expected) << "N " << n << " level " << k << " i " << i << " m " << m;
        }
      }
    }
  }
}

// Tree level k of i is the mean of tree level k - 1 of i and of its partner, to the binary16
// rounding of the stored table (half an ulp, at most 2^-11 of the value); so every tree level's mean
// marginal over the distributions is level 0's, within that rounding accumulated over the levels
// (2^-11 a level, of the largest texel); and every table integrates to the mean of its halves'
// integrals within that rounding (2^-11), so to 1 within 1e-3 (level 0's are within 2e-4).
TEST(Dictionary, TreeLevelsAreMeansOfPairsWithLevelZerosMean) {
  const Dictionary& d = defaultDictionary();
  const kernel::GlintDictionaryView dict = d.view();
  const int n = dict.numDistributions, r = dict.texelsPerDistribution;
  ASSERT_EQ(d.numTables(), 2 * dict.numLevels - 1);
  ASSERT_EQ(d.texels().size(), static_cast<std::size_t>(d.numTables()) * n * r);
  std::vector<double> levelZeroMean(static_cast<std::size_t>(r), 0.0);
  double largest = 0.0;
  for (int i = 0; i < n; ++i) {
    for (int t = 0; t < r; ++t) {
      levelZeroMean[static_cast<std::size_t>(t)] += d.texel(0, i, t) / n;
      largest = std::max(largest, static_cast<double>(d.texel(0, i, t)));
    }
  }
  const double spacing = d.parameters().texelSpacing();
  const auto integral = [&](int table, int i) {
    double sum = 0.0;
    for (int t = 0; t < r; ++t) sum += (t == 0 ? 1.0 : 2.0) * d.texel(table, i, t) * spacing;
    return sum;
  };
  for (int k = 1; k < dict.numLevels; ++k) {
    const int table = kernel::glintTreeTableLevel(dict, k), below = kernel::glintTreeTableLevel(dict, k - 1);
    ASSERT_EQ(table, dict.numLevels - 1 + k);
    std::vector<double> mean(static_cast<std::size_t>(r), 0.0);
    for (int i = 0; i < n; ++i) {
      const int partner = kernel::glintTreePartner(dict, k, i);
      for (int t = 0; t < r; ++t) {
        const double expected = 0.5 * (d.texel(below, i, t) + d.texel(below, partner, t));
        ASSERT_NEAR(d.texel(table, i, t), expected, std::ldexp(expected, -11) + 1e-7) << k << " " << i << " " << t;
        mean[static_cast<std::size_t>(t)] += d.texel(table, i, t) / n;
      }
      const double halves = 0.5 * (integral(below, i) + integral(below, partner));
      ASSERT_NEAR(integral(table, i), halves, std::ldexp(halves, -11)) << "tree level " << k << " distribution " << i;
      ASSERT_NEAR(integral(table, i), 1.0, 1e-3) << "tree level " << k << " distribution " << i;
    }
    for (int t = 0; t < r; ++t) {
      ASSERT_NEAR(mean[static_cast<std::size_t>(t)], levelZeroMean[static_cast<std::size_t>(t)], k * std::ldexp(largest, -11))
          << "tree level " << k << " texel " << t;
    }
  }
}

// The GPU's pair buffer: texel k of a distribution is (p[k], p[k+1]), the last one (p[R - 1], 0),
// the texels of the right level and distribution, as texel() reads them.
TEST(Dictionary, TexelPairsHoldEachTexelAndItsNeighbour) {
  const Dictionary& d = defaultDictionary();
  const DictionaryParameters& p = d.parameters();
  const std::vector<std::uint16_t> pairs = d.halfTexelPairs();
  ASSERT_EQ(pairs.size(), 2u * static_cast<std::size_t>(d.numTables() * p.numDistributions * p.texelsPerDistribution));
  for (int level : {0, 7, p.numLevels - 1, p.numLevels, d.numTables() - 1}) {  // the tree levels too
    for (int distribution : {0, 3, p.numDistributions - 1}) {
      for (int k = 0; k < p.texelsPerDistribution; ++k) {
        const std::size_t texel = static_cast<std::size_t>((level * p.numDistributions + distribution) * p.texelsPerDistribution + k);
        const float next = k + 1 < p.texelsPerDistribution ? d.texel(level, distribution, k + 1) : 0.0f;
        ASSERT_EQ(halfToFloat(pairs[2 * texel]), d.texel(level, distribution, k)) << level << " " << distribution << " " << k;
        ASSERT_EQ(halfToFloat(pairs[2 * texel + 1]), next) << level << " " << distribution << " " << k;
      }
    }
  }
}

TEST(Dictionary, GenerationIsIdenticalOnOneAndTwoThreads) {
  const std::vector<std::byte> many = defaultDictionary().serialise();
  tbb::task_arena single(1);
  const std::vector<std::byte> one = single.execute([] { return generateDictionary(DictionaryParameters{}).serialise(); });
  EXPECT_TRUE(one == many);
  DictionaryParameters otherSeed;
  otherSeed.seed = 2;
  EXPECT_FALSE(generateDictionary(otherSeed).serialise() == many);  // the seed matters
}

TEST(Dictionary, FileRoundTripIsExact) {
  const auto folder = temporaryFolder("roundtrip");
  defaultDictionary().save(folder / "d.gdict");
  const Dictionary loaded = Dictionary::load(folder / "d.gdict");
  EXPECT_TRUE(loaded.serialise() == defaultDictionary().serialise());
  EXPECT_EQ(loaded.parameters().seed, 1u);
  EXPECT_EQ(loaded.parameters().placement, LobePlacement::Stratified);
  EXPECT_EQ(std::filesystem::file_size(folder / "d.gdict"), 64u + 16u * 192u * 64u * 2u);  // 384 KiB payload
}

// Loading `bytes` must throw an Error whose one-line message names the file and contains `problem`.
void expectRejected(const std::vector<std::byte>& bytes, const std::string& problem) {
  try {
    Dictionary::deserialise(bytes, "broken.gdict");
    ADD_FAILURE() << "accepted a file that should fail with '" << problem << "'";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("broken.gdict"), std::string::npos) << message;
    EXPECT_NE(message.find(problem), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

TEST(Dictionary, DamagedFilesAreRejectedWithTheirProblem) {
  const std::vector<std::byte> good = defaultDictionary().serialise();
  auto damaged = [&](std::size_t offset, std::byte value) {
    std::vector<std::byte> bytes = good;
    bytes[offset] = value;
    return bytes;
  };
  expectRejected({}, "truncated");
  expectRejected({good.begin(), good.begin() + 40}, "truncated");
  expectRejected({good.begin(), good.end() - 1}, "truncated");
  std::vector<std::byte> longer = good;
  longer.push_back(std::byte{0});
  expectRejected(longer, "trailing data");
  expectRejected(damaged(0, std::byte{'X'}), "bad magic");
  expectRejected(damaged(8, std::byte{3}), "unsupported dictionary format version 3");
  expectRejected(damaged(17, std::byte{1}), "corrupt header");
  expectRejected(damaged(1000, good[1000] ^ std::byte{0x10}), "corrupt payload");
}

// `glint dict --tree-levels` (format version 2): the L levels as version 1 stores them, then the
// tree levels as the kernel reads them; loading gives the same dictionary, and a stored tree level
// that is not the one level 0 makes is refused by name (a host uploading the file would draw it).
TEST(Dictionary, TreeLevelFilesHoldTheTreeLevelsAndLoadBack) {
  DictionaryParameters p;
  p.numLevels = 4;
  p.numDistributions = 8;
  p.texelsPerDistribution = 16;
  const Dictionary d = generateDictionary(p);
  const std::vector<std::byte> levels = d.serialise();
  const std::vector<std::byte> withTree = d.serialise(DictionaryFileTables::LevelsAndTreeLevels);
  const std::size_t tableTexels = 8 * 16;
  ASSERT_EQ(withTree.size(), 64u + 2u * 7u * tableTexels);  // 4 levels and 3 tree levels
  EXPECT_EQ(withTree[8], std::byte{2});
  EXPECT_EQ(levels[8], std::byte{1});
  EXPECT_TRUE(std::equal(levels.begin() + 64, levels.end(), withTree.begin() + 64));
  auto storedHalf = [&](std::size_t i) {
    return static_cast<std::uint16_t>(static_cast<unsigned>(withTree[64 + 2 * i]) | static_cast<unsigned>(withTree[65 + 2 * i]) << 8);
  };
  for (int table = p.numLevels; table < d.numTables(); ++table) {
    for (int distribution = 0; distribution < p.numDistributions; ++distribution) {
      for (int k = 0; k < p.texelsPerDistribution; ++k) {
        const std::size_t i = (static_cast<std::size_t>(table) * p.numDistributions + distribution) * p.texelsPerDistribution + k;
        ASSERT_EQ(halfToFloat(storedHalf(i)), d.texel(table, distribution, k)) << table << " " << distribution << " " << k;
      }
    }
  }
  const Dictionary loaded = Dictionary::deserialise(withTree, "tree.gdict");
  EXPECT_TRUE(loaded.serialise() == levels);
  EXPECT_TRUE(loaded.serialise(DictionaryFileTables::LevelsAndTreeLevels) == withTree);

  // Tree level 2 (table 5), distribution 3, texel 0 with its lowest bit flipped, the checksums remade.
  std::vector<std::byte> tampered = withTree;
  const std::size_t texel = 64 + 2 * ((5 * 8 + 3) * 16);
  tampered[texel] ^= std::byte{1};
  auto putU32 = [&](std::size_t at, std::uint32_t value) {
    for (int b = 0; b < 4; ++b) tampered[at + b] = static_cast<std::byte>(value >> (8 * b));
  };
  auto text = [&](std::size_t from, std::size_t to) {
    return std::string_view(reinterpret_cast<const char*>(tampered.data()) + from, to - from);
  };
  putU32(56, crc32Ieee(text(64, tampered.size())));
  putU32(60, crc32Ieee(text(0, 60)));
  expectRejected(tampered, "tree level 2, distribution 3 is not the mean its level 0 makes");
  // A version-2 header over a version-1 payload: the size says what is missing.
  std::vector<std::byte> relabelled = levels;
  relabelled[8] = std::byte{2};
  tampered = relabelled;
  putU32(60, crc32Ieee(text(0, 60)));
  expectRejected(tampered, "payload bytes, the parameters need " + std::to_string(2 * 7 * tableTexels));
}

TEST(Dictionary, InvalidParametersAreRejectedByName) {
  auto expectInvalid = [](DictionaryParameters p, const std::string& field) {
    try {
      p.validate();
      ADD_FAILURE() << field << " accepted";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    }
  };
  DictionaryParameters p;
  p.numLevels = 17;
  expectInvalid(p, "levels");
  p = {};
  p.alpha = std::nanf("");
  expectInvalid(p, "alpha");
  p = {};
  p.lobeStd = -1.0f;
  expectInvalid(p, "lobe-std");
  p = {};
  p.texelsPerDistribution = 1;
  expectInvalid(p, "texels");
}

TEST(Dictionary, AuthorsExrChannelsMapToDistributions) {
  if (!authorsDictionary()) GTEST_SKIP() << "needs ../shared/reference/dict_16_192_64_0p5_0p02 (the authors' published dictionary, from their code release; not in the repository)";
  // Distributions 3t + {0, 1, 2} of level l are the R, G, B channels of file _<t>_<l>.exr.
  const auto file = authorsDictionaryFolder() / "dict_16_192_64_0p5_0p02_0005_0007.exr";
  float* rgba = nullptr;
  int width = 0;
  int height = 0;
  ASSERT_EQ(LoadEXR(&rgba, &width, &height, file.c_str(), nullptr), TINYEXR_SUCCESS);
  for (int channel = 0; channel < 3; ++channel) {
    for (int k = 0; k < 64; k += 9) {
      EXPECT_EQ(authorsDictionary()->texel(7, 15 + channel, k), rgba[4 * k + channel]);
    }
  }
  std::free(rgba);
  EXPECT_EQ(authorsDictionary()->parameters().placement, LobePlacement::Imported);
  EXPECT_FLOAT_EQ(authorsDictionary()->parameters().lobeStd, 0.02f);
}

TEST(Dictionary, BrokenExrFoldersNameTheFile) {
  if (!authorsDictionary()) GTEST_SKIP() << "needs ../shared/reference/dict_16_192_64_0p5_0p02 (the authors' published dictionary, from their code release; not in the repository)";
  const auto folder = temporaryFolder("exr") / "dict_16_192_64_0p5_0p02";
  std::filesystem::copy(authorsDictionaryFolder(), folder);
  const auto victim = folder / "dict_16_192_64_0p5_0p02_0010_0003.exr";
  std::filesystem::remove(victim);
  try {
    loadAuthorsExrDictionary(folder);
    ADD_FAILURE() << "a missing file went unnoticed";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(victim.filename().string()), std::string::npos) << e.what();
  }
  std::ofstream(victim) << "not an EXR";
  EXPECT_THROW(loadAuthorsExrDictionary(folder), Error);
  EXPECT_THROW(loadAuthorsExrDictionary(temporaryFolder("dict_bad_name")), Error);
}

TEST(DictionaryErrors, MarginalsThatAreNotDensitiesAreRefused) {
  // All-zero texels (every glint black) or values scaled by mistake: each marginal must integrate
  // to 1 (within 1%) under the texel convention. The generated dictionary does (within 2e-4).
  DictionaryParameters parameters;
  parameters.numLevels = 2;
  parameters.numDistributions = 3;
  const Dictionary good = generateDictionary(parameters);
  std::vector<float> values;
  for (int level = 0; level < 2; ++level) {
    for (int distribution = 0; distribution < 3; ++distribution) {
      for (int k = 0; k < parameters.texelsPerDistribution; ++k) values.push_back(good.texel(level, distribution, k));
    }
  }
  EXPECT_NO_THROW(Dictionary(parameters, values));
  const auto messageOf = [&](const std::vector<float>& texels) {
    try {
      Dictionary(parameters, texels);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(messageOf(std::vector<float>(values.size(), 0.0f)),
            "dictionary: distribution 0 of level 0 integrates to 0, expected 1 (each marginal is a density)");
  std::vector<float> scaled = values;
  for (std::size_t i = 4 * parameters.texelsPerDistribution; i < 5 * parameters.texelsPerDistribution; ++i) scaled[i] *= 1.1f;
  EXPECT_NE(messageOf(scaled).find("distribution 1 of level 1 integrates to 1.09"), std::string::npos) << messageOf(scaled);
}

}  // namespace
}  // namespace glint
