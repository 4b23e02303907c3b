// glint-lod-oracle: how far could any consistent level-of-detail construction go? (docs/antialiasing.md,
// "Level-of-detail consistency", "A bound").
//
// On an idealised dolly (a fronto-parallel glint plane under an orthographic camera, one half-vector
// slope everywhere, the footprint doubling twice over 16 frames: a zoom, with nothing else changing),
// it measures the same figures as `glint lod-consistency` (persistence, change, popping beyond the
// reference's, RMSE) for three constructions of the P-SDF's levels:
//   paper       the 2020 model (kernel glintP22Set, GLINT_LOD_PAPER);
//   consistent  glint's four-blocks construction (GLINT_LOD_CONSISTENT);
//   oracle      every cell of a level above a base level b is the exact mean of its 4^(l-b)
//               descendants at b, each drawn as the 2020 model draws its cells: a hierarchy that
//               is consistent at every cell and every level, as a binary-tree dictionary would
//               make it (docs/antialiasing.md), evaluated by brute force. b lies below every
//               footprint of the sequence, the reference's samples included.
// Each against a reference of its own: the same construction at M x M jittered samples a pixel.
// The glint layer is the P22 above the smooth target's at the slope (its positive part).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <thread>
#include <vector>

#include "glint/bsdf.h"
#include "glint/dictionary.h"

namespace {

using namespace glint;

struct Setup {
  const char* name;
  float logDensity;
  float pixelMid;  // the pixel's size in uv at the middle frame
};

constexpr int kSize = 96;         // pixels across
constexpr int kFrames = 16;
constexpr int kSamples = 4;       // the reference's samples across a pixel
constexpr int kBlock = 4;
const glm::vec2 kSlope(0.2f, 0.1f);

double growth(int t) { return std::exp2(2.0 * (static_cast<double>(t) / (kFrames - 1) - 0.5)); }

float hashUnit(unsigned a, unsigned b, unsigned c, unsigned d) {
  return kernel::glintHashToUnitOpen(kernel::glintPcg4d(glm::uvec4(a, b, c, d)).x);
}

// One cell's P22 at the slope, as glintLevelP22 sums it.
double cellP22(kernel::GlintDictionaryView dict, const GlintParameters& p, const kernel::GlintCell& cell) {
  if (cell.smoothLimit) return kernel::glintTargetP22(p.ndf, kSlope, p.alpha, p.rho);
  if (!cell.readsDictionary) return 0.0;
  const glm::vec2 unscaled = kernel::glintUnscaledSlope(dict, p, kSlope);
  return static_cast<double>(kernel::glintCellMarginals(dict, cell.dictionaryLevel,
                                                        kernel::glintCellDistributions(dict, cell.hash), cell.complement,
                                                        kernel::glintCellRotation(cell.hash), unscaled)) *
         kernel::glintScalingJacobian(dict, p);
}

// The oracle's P-SDF: the 2020 model's footprint, levels and EWA weights, each cell the mean of its
// descendants at the base level.
double oracleP22(kernel::GlintDictionaryView dict, const GlintParameters& p, int base, glm::vec2 uv, float size) {
  const kernel::GlintFootprint footprint =
      kernel::glintPixelFootprint(glm::vec2(size, 0.0f), glm::vec2(0.0f, size), p, dict.numLevels);
  const glm::vec2 wrapped = kernel::glintWrapUv(uv, dict.numLevels);
  const int level = kernel::glintLodLevel(footprint);
  const float blend = kernel::glintLodBlend(footprint);
  const kernel::GlintLevelDraw baseDraw = kernel::glintLevelDraw(dict, p, footprint.logDensity, base);
  const auto levelP22 = [&](int l) {
    if (l < base) std::abort();  // the base must lie below every footprint
    const kernel::GlintCellGrid grid = kernel::glintCellGrid(footprint, wrapped, dict.numLevels, l);
    const int side = 1 << (l - base);
    double sum = 0.0, weights = 0.0;
    for (kernel::GlintCellWalk walk = kernel::glintWalkStart(grid); kernel::glintWalkGoing(grid, walk);
         walk = kernel::glintWalkStep(grid, walk)) {
      const float weight = kernel::glintWalkWeight(grid, walk);
      if (!(weight > 0.0f)) continue;
      const glm::ivec2 cell = kernel::glintCellAt(grid, walk.s, walk.t);
      double mean = 0.0;
      for (int j = 0; j < side; ++j) {
        for (int i = 0; i < side; ++i) {
          mean += cellP22(dict, p, kernel::glintCell(dict, p, baseDraw, cell.x * side + i, cell.y * side + j, base));
        }
      }
      sum += weight * mean / (static_cast<double>(side) * side);
      weights += weight;
    }
    return weights > 0.0 ? sum / weights : 0.0;
  };
  double value = (1.0 - blend) * levelP22(level);
  if (blend > 0.0f) value += blend * levelP22(level + 1);
  return value;
}

double modelP22(kernel::GlintDictionaryView dict, const GlintParameters& p, const std::string& mode, int base,
                glm::vec2 uv, float size) {
  if (mode == "oracle") return oracleP22(dict, p, base, uv, size);
  GlintParameters q = p;
  q.lod = mode == "consistent" ? kernel::GLINT_LOD_CONSISTENT : kernel::GLINT_LOD_PAPER;
  return kernel::glintP22(dict, q, uv, glm::vec2(size, 0.0f), glm::vec2(0.0f, size), kSlope);
}

using Frame = std::vector<double>;

// Frame t's glint layer (its positive part), at one sample a pixel or the reference's M x M.
Frame render(kernel::GlintDictionaryView dict, const GlintParameters& p, const std::string& mode, int base,
             const Setup& setup, int t, bool reference) {
  const float pixel = static_cast<float>(setup.pixelMid * growth(t));
  const double smooth = kernel::glintTargetP22(p.ndf, kSlope, p.alpha, p.rho);
  const glm::vec2 centre(0.37f, 0.61f);
  Frame frame(static_cast<std::size_t>(kSize) * kSize);
  const auto rows = [&](int first, int step) {
    for (int y = first; y < kSize; y += step) {
      for (int x = 0; x < kSize; ++x) {
        const glm::vec2 at = centre + pixel * glm::vec2(x + 0.5f - 0.5f * kSize, y + 0.5f - 0.5f * kSize);
        double value = 0.0;
        if (!reference) {
          value = modelP22(dict, p, mode, base, at, pixel);
        } else {
          for (int j = 0; j < kSamples; ++j) {
            for (int i = 0; i < kSamples; ++i) {
              const glm::vec2 jitter(hashUnit(x, y, i + kSamples * j, 2 * t), hashUnit(x, y, i + kSamples * j, 2 * t + 1));
              const glm::vec2 sample = at + pixel * ((glm::vec2(i, j) + jitter) / float(kSamples) - 0.5f);
              value += modelP22(dict, p, mode, base, sample, pixel / kSamples);
            }
          }
          value /= kSamples * kSamples;
        }
        frame[static_cast<std::size_t>(y) * kSize + x] = std::max(0.0, value - smooth);
      }
    }
  };
  std::thread other(rows, 1, 2);
  rows(0, 2);
  other.join();
  return frame;
}

// Frame t + 1 at frame t's pixel centre (x, y), bilinearly: the magnification undone.
double warped(const Frame& next, int t, int x, int y) {
  const double scale = growth(t) / growth(t + 1);
  const double fx = (x + 0.5 - 0.5 * kSize) * scale + 0.5 * kSize - 0.5;
  const double fy = (y + 0.5 - 0.5 * kSize) * scale + 0.5 * kSize - 0.5;
  const int x0 = static_cast<int>(std::floor(fx)), y0 = static_cast<int>(std::floor(fy));
  const double ax = fx - x0, ay = fy - y0;
  const auto at = [&](int i, int j) {
    return next[static_cast<std::size_t>(std::clamp(j, 0, kSize - 1)) * kSize + std::clamp(i, 0, kSize - 1)];
  };
  return (1 - ay) * ((1 - ax) * at(x0, y0) + ax * at(x0 + 1, y0)) + ay * ((1 - ax) * at(x0, y0 + 1) + ax * at(x0 + 1, y0 + 1));
}

void measure(kernel::GlintDictionaryView dict, const Setup& setup, const std::string& mode, unsigned seed) {
  GlintParameters p = defaultGlintParameters();
  p.logDensity = setup.logDensity;
  p.patternSeed = seed;
  // The base: a level below the reference's finest footprint (the first frame's, M times smaller).
  const float finest = static_cast<float>(setup.pixelMid * growth(0)) / kSamples;
  const int base = static_cast<int>(std::floor(dict.numLevels - 1 + std::log2(finest)));
  std::vector<Frame> model, reference;
  for (int t = 0; t < kFrames; ++t) {
    model.push_back(render(dict, p, mode, base, setup, t, false));
    reference.push_back(render(dict, p, mode, base, setup, t, true));
  }
  double overlap = 0, energy = 0, referenceOverlap = 0, referenceEnergy = 0, change = 0, referenceChange = 0, beyond = 0;
  constexpr int blocks = kSize / kBlock;
  for (int t = 0; t + 1 < kFrames; ++t) {
    std::vector<double> before(blocks * blocks), after(blocks * blocks), rBefore(blocks * blocks), rAfter(blocks * blocks);
    for (int y = 0; y < kSize; ++y) {
      for (int x = 0; x < kSize; ++x) {
        const int b = (y / kBlock) * blocks + x / kBlock;
        before[b] += model[t][static_cast<std::size_t>(y) * kSize + x];
        after[b] += warped(model[t + 1], t, x, y);
        rBefore[b] += reference[t][static_cast<std::size_t>(y) * kSize + x];
        rAfter[b] += warped(reference[t + 1], t, x, y);
      }
    }
    for (int b = 0; b < blocks * blocks; ++b) {
      overlap += std::min(before[b], after[b]);
      energy += before[b];
      referenceOverlap += std::min(rBefore[b], rAfter[b]);
      referenceEnergy += rBefore[b];
      const double own = std::abs(after[b] - before[b]), theirs = std::abs(rAfter[b] - rBefore[b]);
      change += own;
      referenceChange += theirs;
      beyond += std::max(0.0, own - theirs);
    }
  }
  double rmse = 0;
  for (int t = 0; t < kFrames; ++t) {
    double squared = 0, mean = 0;
    for (std::size_t i = 0; i < model[t].size(); ++i) {
      squared += (model[t][i] - reference[t][i]) * (model[t][i] - reference[t][i]);
      mean += reference[t][i];
    }
    rmse += std::sqrt(squared / model[t].size()) / (mean / model[t].size()) / kFrames;
  }
  std::printf("| %s | %u | %s | %d | %.3f (%.3f) | %.3f | %.3f (%.3f) | %.3f | %.1f%% |\n", setup.name, seed,
              mode.c_str(), base, overlap / energy, referenceOverlap / referenceEnergy,
              std::abs(overlap / energy - referenceOverlap / referenceEnergy), change / referenceEnergy,
              referenceChange / referenceEnergy, beyond / referenceEnergy, 100.0 * rmse);
  std::fflush(stdout);
}

}  // namespace

// Usage: glint_lod_oracle [MODE...] (default: paper consistent oracle). Two pattern seeds of a dense
// layer (log density 13, about 180 microfacets a pixel at the middle frame) and a sparse one (log
// density 8, about 30); the oracle takes about a minute on two cores.
int main(int argc, char** argv) {
  std::vector<std::string> modes = {"paper", "consistent", "oracle"};
  if (argc > 1) modes.assign(argv + 1, argv + argc);
  for (const std::string& mode : modes) {
    if (mode != "paper" && mode != "consistent" && mode != "oracle") {
      std::fprintf(stderr, "glint_lod_oracle: unknown mode '%s' (paper, consistent or oracle)\n", mode.c_str());
      return 1;
    }
  }
  const Dictionary dictionary = generateDictionary(DictionaryParameters{});
  const kernel::GlintDictionaryView dict = dictionary.view();
  const std::vector<Setup> setups = {{"dense", 13.0f, 0.02f}, {"sparse", 8.0f, 0.1f}};
  std::printf("| layer | seed | lod | base | persistence (reference) | gap | change (reference) | popping | RMSE |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|\n");
  for (const Setup& setup : setups) {
    for (unsigned seed : {0u, 1u}) {
      for (const std::string& mode : modes) measure(dict, setup, mode, seed);
    }
  }
  return 0;
}
