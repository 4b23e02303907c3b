// The dictionary of multi-level 1D slope distributions (method.md section 1, docs/dictionary.md):
// L levels x N distributions x R texels, each texel a binary16 value of an even density over the
// slope domain [-4 sigma_d, 4 sigma_d], of which only [0, 4 sigma_d) is stored.
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "glint/kernel/prelude.h"

namespace glint {

// How the lobe means of the distributions are drawn (docs/dictionary.md, "Lobe placement").
enum class LobePlacement : std::uint32_t {
  Independent = 0,  // each distribution draws its own means (the paper's generator)
  Stratified = 1,   // every level's lobes, over all distributions, stratify the target
  Imported = 2,     // read from another generator's files (the authors' EXR dictionary)
};

const char* toString(LobePlacement placement);
LobePlacement lobePlacementFromString(const std::string& name);  // throws Error

struct DictionaryParameters {
  int numLevels = 16;               // L; level l has 2^l lobes per distribution
  int numDistributions = 192;       // N
  int texelsPerDistribution = 64;   // R
  float alpha = 0.5f;               // alpha_d: target slope std sigma_d = alpha_d / sqrt(2)
  float lobeStd = 0.02f;            // s: standard deviation of each lobe
  std::uint64_t seed = 1;
  LobePlacement placement = LobePlacement::Stratified;

  float sigma() const;        // sigma_d
  float slopeDomain() const;  // 4 sigma_d: the stored half-domain
  float texelSpacing() const; // 4 sigma_d / R: texel k holds the density at slope k * spacing
  // Throws Error naming the first field out of its documented range.
  void validate() const;
};

// What a dictionary file holds (docs/dictionary.md, "File format"): the L levels, or the L levels
// and then the L - 1 tree levels (docs/dictionary.md, "Tree levels").
enum class DictionaryFileTables { Levels, LevelsAndTreeLevels };

class Dictionary {
 public:
  // `values` holds L * N * R densities, [level][distribution][texel]; each is rounded to binary16.
  Dictionary(const DictionaryParameters& parameters, std::span<const float> values);

  const DictionaryParameters& parameters() const { return parameters_; }
  kernel::GlintDictionaryView view() const;

  float texel(int level, int distribution, int texel) const;
  // The marginal density at any slope, with the kernel's interpolation; 0 outside the domain.
  float marginal(int level, int distribution, float slope) const;

  // The L levels' texels, as a version-1 file holds them (the tree levels after them are derived).
  std::span<const std::uint16_t> halfTexels() const {
    return std::span<const std::uint16_t>(halves_).first(static_cast<std::size_t>(parameters_.numLevels) *
                                                         parameters_.numDistributions * parameters_.texelsPerDistribution);
  }
  // Every table the kernel reads: the L levels, then the L - 1 tree levels that the tree LOD
  // construction reads (kernel glintTreeTableLevel, docs/method.md 2.8), built from level 0 at
  // construction, rounded to binary16 like the rest. texel() and marginal() take table levels.
  int numTables() const { return numTables(parameters_.numLevels); }
  static int numTables(int numLevels) { return 2 * numLevels - 1; }
  // The texels as the GPU's dictionary buffer holds them (glintDictionaryTexelPair in the shaders):
  // texel k of a distribution is the pair (p[k], p[k+1]), with p[R] = 0 (the marginal falls to 0 at
  // 4 sigma_d), so that an interpolation costs one fetch instead of two; two binary16 values a texel.
  std::vector<std::uint16_t> halfTexelPairs() const;
  std::span<const float> texels() const { return values_; }

  // The mip chain that anti-aliasing filters the marginals with (docs/dictionary.md, "Mip chain"),
  // made from the texels at construction: 1 + (the number of times 2 divides R) levels, level m of
  // R / 2^m box averages 2^m texels wide. mipTexel is texel k of level m (level 0: texel());
  // filteredTexels the kernel's layout (prelude.h, GlintDictionaryView), four binary16 values a texel.
  int numMips() const { return numMips_; }
  int mipRowLength() const { return mipRowLength_; }
  float mipTexel(int mip, int level, int distribution, int texel) const;
  std::span<const std::uint16_t> filteredHalfTexels() const { return filteredHalves_; }  // for GPU upload

  // The cumulative tables that glints under extended lights integrate the marginals with
  // (docs/dictionary.md, "Cumulative tables"; kernel glintDictionaryCumulativeTexel): for every
  // table and texel k, (C[k], M[k], p[k], p[k+1]): the integrals of the interpolated marginal and
  // of slope times it from slope 0 to texel k's slope, summed in double from the binary16 texels and
  // kept as 32-bit floats (differences of binary16 sums would lose a narrow region's mass), then
  // texel k's pair, so that one read serves an integral; four a texel.
  std::span<const float> cumulativeTexels() const { return cumulative_; }

  // The versioned binary file (docs/dictionary.md, "File format"): the L levels (version 1), or with
  // the tree levels after them (version 2) for hosts that upload the file as it is. Loading reads
  // both, and refuses stored tree levels that are not the ones level 0 makes.
  std::vector<std::byte> serialise(DictionaryFileTables tables = DictionaryFileTables::Levels) const;
  static Dictionary deserialise(std::span<const std::byte> bytes, const std::string& name);
  // Returns the file's size in bytes.
  std::size_t save(const std::filesystem::path& path, DictionaryFileTables tables = DictionaryFileTables::Levels) const;
  static Dictionary load(const std::filesystem::path& path);
  // The authors' published EXR dictionary is read by glint::image (glint/dictionary_exr.h), which
  // has the EXR decoder that this library does without.

 private:
  DictionaryParameters parameters_;
  std::vector<std::uint16_t> halves_;
  std::vector<float> values_;  // halves_ converted back: what the kernel reads on the CPU
  int numMips_ = 1;
  int mipRowLength_ = 0;
  std::vector<std::uint16_t> filteredHalves_;
  std::vector<float> filteredValues_;  // filteredHalves_ converted back
  std::vector<float> cumulative_;

  void checkNormalised() const;
  void appendTreeLevels();
  void buildMipChain();
  void buildCumulativeTables();
};

// Generates a dictionary (method.md section 1) in parallel with oneTBB. The result depends only on
// the parameters, never on the number of threads.
Dictionary generateDictionary(const DictionaryParameters& parameters);

// The lobe means |mu| of every distribution, in the order they are added: level l uses the first
// 2^l of them, which is what makes the levels nested.
std::vector<std::vector<double>> generateLobeMeans(const DictionaryParameters& parameters);

// Measured properties of a dictionary, per level (docs/dictionary.md, "Statistics").
struct LevelStatistics {
  double minIntegral, maxIntegral;  // of the marginals over [-4 sigma_d, 4 sigma_d]
  double minStd, meanStd, maxStd;   // standard deviations of the marginals
  double meanMarginalL1;            // L1 distance of the mean marginal to Normal(0, sigma_d^2 + s^2)
};
std::vector<LevelStatistics> computeStatistics(const Dictionary& dictionary);
// The limit every level tends to: sqrt(sigma_d^2 + s^2).
double targetStd(const DictionaryParameters& parameters);

}  // namespace glint
