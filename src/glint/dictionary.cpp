#include "glint/dictionary.h"

#include <bit>
#include <cmath>
#include <cstring>
#include <optional>
#include <sstream>

#include <zlib.h>

#include "glint/error.h"
#include "glint/file_io.h"
#include "glint/half.h"
#include "glint/kernel/glint_brdf.h"

namespace glint {

namespace {

constexpr char kMagic[8] = {'G', 'L', 'I', 'N', 'T', 'D', 'I', 'C'};
// Version 1 holds the L levels; version 2 the L levels, then the L - 1 tree levels (docs/dictionary.md,
// "File format"), for hosts that upload the file as it is and cannot build the tree levels.
constexpr std::uint32_t kFormatVersionLevels = 1;
constexpr std::uint32_t kFormatVersionWithTreeLevels = 2;
constexpr std::uint32_t kHeaderBytes = 64;
constexpr std::uint32_t kTexelFormatBinary16 = 1;

std::string formatFloat(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

template <typename T>
void requireInRange(const char* field, T value, T low, T high) {
  if (!(value >= low && value <= high)) {  // also rejects NaN
    throw Error("dictionary parameter " + std::string(field) + " must be in [" + formatFloat(low) + ", " +
                formatFloat(high) + "], got " + formatFloat(value));
  }
}

std::uint32_t crc32Of(std::span<const std::byte> bytes) {
  return static_cast<std::uint32_t>(
      crc32(0L, reinterpret_cast<const Bytef*>(bytes.data()), static_cast<uInt>(bytes.size())));
}

// Little-endian field access, independent of the host's byte order.
void putU32(std::byte* at, std::uint32_t value) {
  for (int i = 0; i < 4; ++i) at[i] = static_cast<std::byte>((value >> (8 * i)) & 0xFFu);
}
void putU64(std::byte* at, std::uint64_t value) {
  for (int i = 0; i < 8; ++i) at[i] = static_cast<std::byte>((value >> (8 * i)) & 0xFFu);
}
std::uint32_t getU32(const std::byte* at) {
  std::uint32_t value = 0;
  for (int i = 0; i < 4; ++i) value |= static_cast<std::uint32_t>(at[i]) << (8 * i);
  return value;
}
std::uint64_t getU64(const std::byte* at) {
  std::uint64_t value = 0;
  for (int i = 0; i < 8; ++i) value |= static_cast<std::uint64_t>(at[i]) << (8 * i);
  return value;
}

}  // namespace

const char* toString(LobePlacement placement) {
  switch (placement) {
    case LobePlacement::Independent: return "independent";
    case LobePlacement::Stratified: return "stratified";
    case LobePlacement::Imported: return "imported";
  }
  return "unknown";
}

LobePlacement lobePlacementFromString(const std::string& name) {
  if (name == "independent") return LobePlacement::Independent;
  if (name == "stratified") return LobePlacement::Stratified;
  throw Error("lobe placement must be 'stratified' or 'independent', got '" + name + "'");
}

float DictionaryParameters::sigma() const { return alpha / std::sqrt(2.0f); }
float DictionaryParameters::slopeDomain() const { return 4.0f * sigma(); }
float DictionaryParameters::texelSpacing() const { return slopeDomain() / static_cast<float>(texelsPerDistribution); }

void DictionaryParameters::validate() const {
  // 16 levels at most: the kernel's 32-bit cell seed holds 2^16 level-0 cells per axis
  // (kernel/glint_parameters.h, GLINT_CELL_INDEX_MASK), and its level draw has room for 16 thresholds.
  requireInRange("levels", numLevels, 1, kernel::GLINT_MAX_DICTIONARY_LEVELS);
  // Distributions are picked from 16-bit hash halves (kernel/glint_cell.h, glintCellDistributions).
  requireInRange("distributions", numDistributions, 1, 4096);
  requireInRange("texels", texelsPerDistribution, 2, 4096);
  requireInRange("alpha", alpha, 0.01f, 2.0f);
  requireInRange("lobe-std", lobeStd, 1e-4f, 1.0f);
  const double lobes = std::ldexp(static_cast<double>(numDistributions), numLevels - 1);
  if (lobes > 1 << 25) {
    throw Error("dictionary parameters: distributions x 2^(levels-1) = " + formatFloat(lobes) +
                " lobes, more than the supported 2^25");
  }
  if (placement != LobePlacement::Independent && placement != LobePlacement::Stratified &&
      placement != LobePlacement::Imported) {
    throw Error("dictionary parameter placement has unknown value " +
                std::to_string(static_cast<std::uint32_t>(placement)));
  }
}

Dictionary::Dictionary(const DictionaryParameters& parameters, std::span<const float> values)
    : parameters_(parameters) {
  parameters_.validate();
  const std::size_t expected = static_cast<std::size_t>(parameters.numLevels) * parameters.numDistributions *
                               parameters.texelsPerDistribution;
  if (values.size() != expected) {
    throw Error("dictionary: " + std::to_string(values.size()) + " texels given, " + std::to_string(expected) +
                " expected");
  }
  halves_.resize(expected);
  values_.resize(expected);
  for (std::size_t i = 0; i < expected; ++i) {
    if (!(std::isfinite(values[i]) && values[i] >= 0.0f)) {
      throw Error("dictionary: texel " + std::to_string(i) + " is " + formatFloat(values[i]) +
                  ", expected a finite non-negative density");
    }
    halves_[i] = floatToHalf(values[i]);
    values_[i] = halfToFloat(halves_[i]);
  }
  checkNormalised();
  appendTreeLevels();
  buildMipChain();
  buildCumulativeTables();
}

// Tree level k >= 1 of distribution i is the mean of tree level k - 1 of i and of its partner
// (kernel glintTreePartner; tree level 0 is level 0), stored after the L levels at table level
// L - 1 + k (glintTreeTableLevel) and rounded to binary16 as the GPU holds them. Only the tree LOD
// construction reads them (docs/method.md 2.8).
void Dictionary::appendTreeLevels() {
  const std::size_t n = static_cast<std::size_t>(parameters_.numDistributions);
  const std::size_t r = static_cast<std::size_t>(parameters_.texelsPerDistribution);
  const int levels = parameters_.numLevels;
  const std::size_t tables = static_cast<std::size_t>(numTables());
  halves_.resize(tables * n * r);
  values_.resize(tables * n * r);
  const kernel::GlintDictionaryView dict = view();
  for (int k = 1; k < levels; ++k) {
    const std::size_t below = static_cast<std::size_t>(kernel::glintTreeTableLevel(dict, k - 1));
    const std::size_t at = static_cast<std::size_t>(kernel::glintTreeTableLevel(dict, k));
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t partner = static_cast<std::size_t>(kernel::glintTreePartner(dict, k, static_cast<int>(i)));
      const float* a = values_.data() + (below * n + i) * r;
      const float* b = values_.data() + (below * n + partner) * r;
      for (std::size_t t = 0; t < r; ++t) {
        const std::size_t out = (at * n + i) * r + t;
        halves_[out] = floatToHalf(0.5f * (a[t] + b[t]));
        values_[out] = halfToFloat(halves_[out]);
      }
    }
  }
}

// Every marginal is a density: under the texel convention (docs/dictionary.md) it integrates to
// h (p[0] + 2 sum_k>0 p[k]) over [-4 sigma_d, 4 sigma_d]. glint's and the authors' dictionaries
// integrate to 1 within 2e-4 (binary16 rounding); a file of zeros, or of values scaled by mistake,
// would render black or wrong without a word, so anything beyond 1% is refused.
void Dictionary::checkNormalised() const {
  const int texels = parameters_.texelsPerDistribution;
  const double spacing = parameters_.texelSpacing();
  for (int level = 0; level < parameters_.numLevels; ++level) {
    for (int distribution = 0; distribution < parameters_.numDistributions; ++distribution) {
      const float* v = values_.data() + (static_cast<std::size_t>(level) * parameters_.numDistributions + distribution) *
                                            static_cast<std::size_t>(texels);
      double sum = v[0];
      for (int k = 1; k < texels; ++k) sum += 2.0 * v[k];
      const double integral = sum * spacing;
      if (!(std::abs(integral - 1.0) <= 0.01)) {
        throw Error("dictionary: distribution " + std::to_string(distribution) + " of level " + std::to_string(level) +
                    " integrates to " + formatFloat(static_cast<float>(integral)) +
                    ", expected 1 (each marginal is a density)");
      }
    }
  }
}

// Level m of the chain samples, at texel spacing 2^m h (h = 4 sigma_d / R), the box average of
// width 2^m h of the level-0 marginal (piecewise linear between its texels, even, 0 from
// 4 sigma_d on): f_m[k] = mean of p over [(k - 1/2), (k + 1/2)] 2^m h, the box at k = 0 taking
// both sides of the even marginal. The mass beyond the last texel's box, which the texel
// convention cannot hold (the marginal falls to 0 at 4 sigma_d), goes to the last texel, so that
// every level integrates, under the kernel's interpolation, exactly as level 0 does.
void Dictionary::buildMipChain() {
  const int texels = parameters_.texelsPerDistribution;
  numMips_ = 1 + std::countr_zero(static_cast<unsigned>(texels));
  mipRowLength_ = kernel::glintMipOffset(texels, numMips_);
  const std::size_t rows = values_.size() / static_cast<std::size_t>(texels);  // the tree levels' too
  std::vector<std::vector<double>> mips(static_cast<std::size_t>(numMips_));
  filteredHalves_.assign(rows * static_cast<std::size_t>(mipRowLength_) * 4, 0);
  filteredValues_.assign(filteredHalves_.size(), 0.0f);
  std::vector<double> cumulative(static_cast<std::size_t>(texels) + 1);
  for (std::size_t row = 0; row < rows; ++row) {
    const float* v = values_.data() + row * static_cast<std::size_t>(texels);
    auto value = [&](int k) { return k < texels ? static_cast<double>(v[k]) : 0.0; };
    // C(u) = integral of p over [0, u], u in level-0 texels: exact for the piecewise-linear marginal.
    cumulative[0] = 0.0;
    for (int k = 0; k < texels; ++k) cumulative[k + 1] = cumulative[k] + 0.5 * (value(k) + value(k + 1));
    auto integral = [&](double u) {
      if (u >= texels) return cumulative[static_cast<std::size_t>(texels)];
      const int k = static_cast<int>(u);
      const double t = u - k;
      return cumulative[static_cast<std::size_t>(k)] + value(k) * t + 0.5 * (value(k + 1) - value(k)) * t * t;
    };
    for (int m = 0; m < numMips_; ++m) {
      const int count = texels >> m;
      const double width = static_cast<double>(1 << m);
      std::vector<double>& f = mips[static_cast<std::size_t>(m)];
      f.assign(static_cast<std::size_t>(count) + 1, 0.0);  // f[count] = 0: the convention's fall to 0
      if (m == 0) {
        for (int k = 0; k < count; ++k) f[static_cast<std::size_t>(k)] = value(k);
      } else {
        for (int k = 0; k < count; ++k) {
          const double low = (k - 0.5) * width;
          const double high = (k + 0.5) * width;
          const double mass = k == 0 ? 2.0 * integral(high) : integral(high) - integral(low);
          f[static_cast<std::size_t>(k)] = mass / width;
        }
        // The rest of the half beyond the last box; the last texel counts twice (both sides) in
        // the even marginal's integral, once when it is also the first.
        const double rest = integral(texels) - integral((count - 0.5) * width);
        f[static_cast<std::size_t>(count - 1)] += (count == 1 ? 2.0 : 1.0) * rest / width;
      }
    }
    // Level m + 1 interpolated at level m's texel j, 2^m h j: its texels lie at even j, so an odd j
    // is the mean of its two neighbours. Within a texel of level m both levels are then linear, and
    // one fraction serves both.
    auto nextAt = [&](int m, int j) {
      const std::vector<double>& next = mips[static_cast<std::size_t>(m) + 1];
      const auto half = static_cast<std::size_t>(j / 2);
      return j % 2 == 0 ? next[half] : 0.5 * (next[half] + next[half + 1]);
    };
    for (int m = 0; m < numMips_; ++m) {
      const std::vector<double>& fine = mips[static_cast<std::size_t>(m)];
      const bool last = m + 1 == numMips_;
      for (int k = 0; k < (texels >> m); ++k) {
        const std::size_t at =
            4 * (row * static_cast<std::size_t>(mipRowLength_) + static_cast<std::size_t>(kernel::glintMipOffset(texels, m) + k));
        const double quad[4] = {fine[static_cast<std::size_t>(k)], fine[static_cast<std::size_t>(k) + 1],
                                last ? 0.0 : nextAt(m, k), last ? 0.0 : nextAt(m, k + 1)};
        for (int c = 0; c < 4; ++c) {
          // Level 0's own values are halves already; the others are rounded as the GPU holds them.
          filteredHalves_[at + static_cast<std::size_t>(c)] = floatToHalf(static_cast<float>(quad[c]));
          filteredValues_[at + static_cast<std::size_t>(c)] = halfToFloat(filteredHalves_[at + static_cast<std::size_t>(c)]);
        }
      }
    }
  }
}

float Dictionary::mipTexel(int mip, int level, int distribution, int texel) const {
  return kernel::glintDictionaryFilteredTexels(view(), level, distribution,
                                               kernel::glintMipOffset(parameters_.texelsPerDistribution, mip) + texel)
      .x;
}

void Dictionary::buildCumulativeTables() {
  // The integrals of the kernel's linear interpolation (glintMarginal): texel k spans slopes
  // [k, k + 1] spacing, its density p[k] + (p[k + 1] - p[k]) s at s in [0, 1], falling to 0 past
  // the last texel. Each texel's share of the integral of p and of slope times p, in double.
  const std::size_t texels = static_cast<std::size_t>(parameters_.texelsPerDistribution);
  const double spacing = static_cast<double>(kernel::glintDictionaryDomain(view())) / static_cast<double>(texels);
  cumulative_.assign(4 * values_.size(), 0.0f);
  for (std::size_t row = 0; row < values_.size() / texels; ++row) {
    const float* p = values_.data() + row * texels;
    double mass = 0.0;
    double moment = 0.0;
    for (std::size_t k = 0; k < texels; ++k) {
      const float next = k + 1 < texels ? p[k + 1] : 0.0f;
      float* texel = cumulative_.data() + 4 * (row * texels + k);
      texel[0] = static_cast<float>(mass);
      texel[1] = static_cast<float>(moment);
      texel[2] = p[k];  // the pair, as glintDictionaryTexelPair reads it
      texel[3] = next;
      const double a = p[k];
      const double rise = static_cast<double>(next) - a;
      mass += spacing * (a + 0.5 * rise);
      moment += spacing * spacing * (static_cast<double>(k) * (a + 0.5 * rise) + 0.5 * a + rise / 3.0);
    }
  }
}

kernel::GlintDictionaryView Dictionary::view() const {
  return {values_.data(),   parameters_.numLevels, parameters_.numDistributions, parameters_.texelsPerDistribution,
          parameters_.alpha, filteredValues_.data(), numMips_, mipRowLength_, cumulative_.data()};
}

std::vector<std::uint16_t> Dictionary::halfTexelPairs() const {
  const std::size_t texels = static_cast<std::size_t>(parameters_.texelsPerDistribution);
  std::vector<std::uint16_t> pairs(2 * halves_.size());
  for (std::size_t i = 0; i < halves_.size(); ++i) {
    const bool lastOfDistribution = (i + 1) % texels == 0;
    pairs[2 * i] = halves_[i];
    pairs[2 * i + 1] = lastOfDistribution ? std::uint16_t{0} : halves_[i + 1];  // binary16 +0
  }
  return pairs;
}

float Dictionary::texel(int level, int distribution, int texel) const {
  return kernel::glintDictionaryTexel(view(), level, distribution, texel);
}

float Dictionary::marginal(int level, int distribution, float slope) const {
  const float absSlope = std::abs(slope);
  if (!(absSlope < parameters_.slopeDomain())) {
    return 0.0f;
  }
  return kernel::glintMarginal(view(), level, distribution, absSlope);
}

std::vector<std::byte> Dictionary::serialise(DictionaryFileTables tables) const {
  const bool withTree = tables == DictionaryFileTables::LevelsAndTreeLevels;
  // The tree levels are derived from level 0: stored only where asked, for hosts that cannot build them.
  const std::span<const std::uint16_t> stored = withTree ? std::span<const std::uint16_t>(halves_) : halfTexels();
  const std::size_t payloadBytes = stored.size() * 2;
  std::vector<std::byte> bytes(kHeaderBytes + payloadBytes);
  std::byte* payload = bytes.data() + kHeaderBytes;
  for (std::size_t i = 0; i < stored.size(); ++i) {
    payload[2 * i] = static_cast<std::byte>(stored[i] & 0xFFu);
    payload[2 * i + 1] = static_cast<std::byte>(stored[i] >> 8);
  }
  std::byte* header = bytes.data();
  std::memcpy(header, kMagic, sizeof kMagic);
  putU32(header + 8, withTree ? kFormatVersionWithTreeLevels : kFormatVersionLevels);
  putU32(header + 12, kHeaderBytes);
  putU32(header + 16, static_cast<std::uint32_t>(parameters_.numLevels));
  putU32(header + 20, static_cast<std::uint32_t>(parameters_.numDistributions));
  putU32(header + 24, static_cast<std::uint32_t>(parameters_.texelsPerDistribution));
  putU32(header + 28, std::bit_cast<std::uint32_t>(parameters_.alpha));
  putU32(header + 32, std::bit_cast<std::uint32_t>(parameters_.lobeStd));
  putU32(header + 36, static_cast<std::uint32_t>(parameters_.placement));
  putU64(header + 40, parameters_.seed);
  putU32(header + 48, kTexelFormatBinary16);
  putU32(header + 52, static_cast<std::uint32_t>(payloadBytes));
  putU32(header + 56, crc32Of({payload, payloadBytes}));
  putU32(header + 60, crc32Of({header, 60}));
  return bytes;
}

Dictionary Dictionary::deserialise(std::span<const std::byte> bytes, const std::string& name) {
  auto fail = [&](const std::string& problem) { return Error(name + ": " + problem); };
  if (bytes.size() < kHeaderBytes) {
    throw fail("truncated: " + std::to_string(bytes.size()) + " bytes, a dictionary header needs " +
               std::to_string(kHeaderBytes));
  }
  const std::byte* header = bytes.data();
  if (std::memcmp(header, kMagic, sizeof kMagic) != 0) {
    throw fail("not a glint dictionary (bad magic)");
  }
  const std::uint32_t version = getU32(header + 8);
  if (version != kFormatVersionLevels && version != kFormatVersionWithTreeLevels) {
    throw fail("unsupported dictionary format version " + std::to_string(version) + " (this build reads " +
               std::to_string(kFormatVersionLevels) + " and " + std::to_string(kFormatVersionWithTreeLevels) + ")");
  }
  if (getU32(header + 60) != crc32Of({header, 60})) {
    throw fail("corrupt header (checksum mismatch)");
  }
  if (getU32(header + 12) != kHeaderBytes || getU32(header + 48) != kTexelFormatBinary16) {
    throw fail("unsupported header size or texel format");
  }
  DictionaryParameters parameters;
  parameters.numLevels = static_cast<int>(getU32(header + 16));
  parameters.numDistributions = static_cast<int>(getU32(header + 20));
  parameters.texelsPerDistribution = static_cast<int>(getU32(header + 24));
  parameters.alpha = std::bit_cast<float>(getU32(header + 28));
  parameters.lobeStd = std::bit_cast<float>(getU32(header + 32));
  parameters.placement = static_cast<LobePlacement>(getU32(header + 36));
  parameters.seed = getU64(header + 40);
  try {
    parameters.validate();
  } catch (const Error& e) {
    throw fail(e.what());
  }
  const std::size_t tableTexels = static_cast<std::size_t>(parameters.numDistributions) * parameters.texelsPerDistribution;
  const std::size_t levelTexels = static_cast<std::size_t>(parameters.numLevels) * tableTexels;
  const int tables = version == kFormatVersionWithTreeLevels ? numTables(parameters.numLevels) : parameters.numLevels;
  const std::size_t storedTexels = static_cast<std::size_t>(tables) * tableTexels;
  const std::size_t payloadBytes = getU32(header + 52);
  if (payloadBytes != 2 * storedTexels) {
    throw fail("header says " + std::to_string(payloadBytes) + " payload bytes, the parameters need " +
               std::to_string(2 * storedTexels));
  }
  if (bytes.size() != kHeaderBytes + payloadBytes) {
    throw fail((bytes.size() < kHeaderBytes + payloadBytes ? "truncated: " : "trailing data: ") +
               std::to_string(bytes.size()) + " bytes, expected " + std::to_string(kHeaderBytes + payloadBytes));
  }
  const std::span<const std::byte> payload = bytes.subspan(kHeaderBytes);
  if (getU32(header + 56) != crc32Of(payload)) {
    throw fail("corrupt payload (checksum mismatch)");
  }
  auto storedHalf = [&](std::size_t i) {
    return static_cast<std::uint16_t>(static_cast<unsigned>(payload[2 * i]) | static_cast<unsigned>(payload[2 * i + 1]) << 8);
  };
  std::vector<float> values(levelTexels);
  for (std::size_t i = 0; i < levelTexels; ++i) values[i] = halfToFloat(storedHalf(i));
  std::optional<Dictionary> dictionary;
  try {
    dictionary.emplace(parameters, values);
  } catch (const Error& e) {
    throw fail(e.what());
  }
  // Stored tree levels must be the ones level 0 makes: a host that uploads the file as it is draws
  // them, glint draws its own, and the two would differ without a word.
  for (std::size_t i = levelTexels; i < storedTexels; ++i) {
    if (storedHalf(i) != dictionary->halves_[i]) {
      const std::size_t table = i / tableTexels;  // tree level k is table L - 1 + k
      const std::size_t distribution = i % tableTexels / static_cast<std::size_t>(parameters.texelsPerDistribution);
      throw fail("tree level " + std::to_string(table + 1 - static_cast<std::size_t>(parameters.numLevels)) +
                 ", distribution " + std::to_string(distribution) +
                 " is not the mean its level 0 makes (docs/dictionary.md, \"Tree levels\")");
    }
  }
  return std::move(*dictionary);
}

std::size_t Dictionary::save(const std::filesystem::path& path, DictionaryFileTables tables) const {
  const std::vector<std::byte> bytes = serialise(tables);
  writeFileAtomically(path, bytes);
  return bytes.size();
}

Dictionary Dictionary::load(const std::filesystem::path& path) {
  return deserialise(readFile(path), path.string());
}

double targetStd(const DictionaryParameters& parameters) {
  const double sigma = parameters.sigma();
  return std::sqrt(sigma * sigma + static_cast<double>(parameters.lobeStd) * parameters.lobeStd);
}

std::vector<LevelStatistics> computeStatistics(const Dictionary& dictionary) {
  // Midpoint quadrature of the interpolated marginal, 64 samples per texel over the whole domain:
  // independent of the trapezoid sum the generator normalises with.
  const DictionaryParameters& p = dictionary.parameters();
  const int samples = 64 * p.texelsPerDistribution;
  const double domain = p.slopeDomain();
  const double step = 2.0 * domain / (2 * samples);
  const double target = targetStd(p);
  std::vector<LevelStatistics> levels;
  for (int level = 0; level < p.numLevels; ++level) {
    LevelStatistics stats{1e30, -1e30, 1e30, 0.0, -1e30, 0.0};
    std::vector<double> mean(static_cast<std::size_t>(2 * samples), 0.0);
    for (int n = 0; n < p.numDistributions; ++n) {
      double integral = 0.0;
      double second = 0.0;
      for (int i = 0; i < 2 * samples; ++i) {
        const double x = -domain + (i + 0.5) * step;
        const double density = dictionary.marginal(level, n, static_cast<float>(x));
        integral += density * step;
        second += x * x * density * step;
        mean[static_cast<std::size_t>(i)] += density / p.numDistributions;
      }
      const double std = std::sqrt(second / integral);
      stats.minIntegral = std::min(stats.minIntegral, integral);
      stats.maxIntegral = std::max(stats.maxIntegral, integral);
      stats.minStd = std::min(stats.minStd, std);
      stats.maxStd = std::max(stats.maxStd, std);
      stats.meanStd += std / p.numDistributions;
    }
    for (int i = 0; i < 2 * samples; ++i) {
      const double x = -domain + (i + 0.5) * step;
      const double normal = std::exp(-0.5 * x * x / (target * target)) / (target * std::sqrt(2.0 * M_PI));
      stats.meanMarginalL1 += std::abs(mean[static_cast<std::size_t>(i)] - normal) * step;
    }
    levels.push_back(stats);
  }
  return levels;
}

}  // namespace glint
