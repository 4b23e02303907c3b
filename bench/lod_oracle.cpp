// glint_lod_oracle: what level-of-detail constructions consistent at every cell would give
// (docs/antialiasing.md, "Levels consistent at every cell, idealised").
//
// On an idealised zoom (a fronto-parallel glint plane under an orthographic camera, one half-vector
// slope everywhere, the footprint doubling twice over 16 frames, nothing else changing), it
// measures the figures of `glint lod-consistency` (persistence, change, popping beyond the
// reference's, RMSE), the glint layer's correlation between neighbouring pixels, and how far the
// last frame shows the first frame's glints averaged (coarseAndFine), for four constructions of the
// P-SDF's levels:
//   paper       the 2020 model (kernel glintP22, GLINT_LOD_PAPER);
//   consistent  glint's four-blocks construction (GLINT_LOD_CONSISTENT);
//   oracle      every cell of a level above a base level b is the exact mean of its 4^(l-b)
//               descendants at b, each drawn as the 2020 model draws its cells: consistent at
//               every cell and level by construction, evaluated by brute force. b lies below every
//               footprint of the sequence, the reference's samples included;
//   tree        glint's tree construction (GLINT_LOD_TREE, docs/method.md 2.8): every cell below
//               the own level (set by the density, above every footprint of the sequence here) is
//               the mean of its four children, read from the dictionary's tree levels, whose lobes
//               are level 0's N single ones; a whole subtree shares its own cell's rotation.
// Each against a reference of its own: the same construction at N x N samples a pixel (4 x 4 unless
// --reference-samples says), at the centres of the pixel's sub-pixels (the first of
// `glint lod-consistency`'s reference frames).
// The glint layer is the P22 above the smooth target's at the slope (its positive part); the image
// spans less than the pattern's period (2 uv) in every frame, so no glint is counted twice.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "glint/bsdf.h"
#include "glint/dictionary.h"
#include "glint/image_io.h"

namespace {

using namespace glint;

struct Setup {
  const char* name;
  float logDensity;
  float pixelMid;  // the pixel's size in uv at the middle frame
};

constexpr int kSize = 96;    // pixels across
constexpr int kFrames = 16;
int referenceSamples = 4;  // the reference's samples across a pixel (--reference-samples)
// --figure: one row a construction, of the dense layer's first seed (figureRow).
std::optional<ImageRgbF> figure;
const char* figurePath = nullptr;
const char* directionsPath = nullptr;  // --directions (directionsFigure)
constexpr int kBlock = 4;
const glm::vec2 kSlope(0.2f, 0.1f);
// The dense layer's log density, ln(microfacets a pixel / pixel area) at 0.01 uv: the zoom's first
// setup and the area --directions looks at.
constexpr float kDenseLogDensity = 14.4f;

double growth(int t) { return std::exp2(2.0 * (static_cast<double>(t) / (kFrames - 1) - 0.5)); }

// One cell's P22 at a slope (the sequence's, kSlope, unless said), as glintLevelP22 sums it.
double cellP22(kernel::GlintDictionaryView dict, const GlintParameters& p, const kernel::GlintCell& cell,
               glm::vec2 slope = kSlope) {
  if (cell.smoothLimit) return cell.coverage * kernel::glintTargetP22(p.ndf, slope, p.alpha, p.rho);
  if (!cell.readsDictionary) return 0.0;
  const glm::vec2 unscaled = kernel::glintUnscaledSlope(dict, p, slope);
  return static_cast<double>(kernel::glintCellMarginals(dict, cell.dictionaryLevel,
                                                        cell.distributions, cell.complement,
                                                        kernel::glintCellRotation(cell.hash), unscaled)) *
         cell.coverage * kernel::glintScalingJacobian(dict, p);
}

// The P-SDF with the 2020 model's footprint, levels and EWA weights and its own cells' values.
template <typename CellValue>
double walkedP22(kernel::GlintDictionaryView dict, const GlintParameters& p, glm::vec2 uv, float size, CellValue value) {
  const kernel::GlintFootprint footprint =
      kernel::glintPixelFootprint(glm::vec2(size, 0.0f), glm::vec2(0.0f, size), p, dict.numLevels);
  const glm::vec2 wrapped = kernel::glintWrapUv(uv, dict.numLevels);
  const int level = kernel::glintLodLevel(footprint);
  const float blend = kernel::glintLodBlend(footprint);
  const auto levelP22 = [&](int l) {
    const kernel::GlintCellGrid grid = kernel::glintCellGrid(footprint, wrapped, dict.numLevels, l);
    double sum = 0.0, weights = 0.0;
    for (kernel::GlintCellWalk walk = kernel::glintWalkStart(grid); kernel::glintWalkGoing(grid, walk);
         walk = kernel::glintWalkStep(grid, walk)) {
      const float weight = kernel::glintWalkWeight(grid, walk);
      if (!(weight > 0.0f)) continue;
      const glm::ivec2 cell = kernel::glintCellAt(grid, walk.s, walk.t);
      sum += weight * value(cell.x, cell.y, l, footprint.logDensity);
      weights += weight;
    }
    return weights > 0.0 ? sum / weights : 0.0;
  };
  double p22 = (1.0 - blend) * levelP22(level);
  if (blend > 0.0f) p22 += blend * levelP22(level + 1);
  return p22;
}

// The oracle: each cell the mean of its descendants at the base level, drawn as the 2020 model's.
double oracleP22(kernel::GlintDictionaryView dict, const GlintParameters& p, int base, glm::vec2 uv, float size) {
  std::optional<kernel::GlintLevelDraw> baseDraw;  // the same for every cell of the footprint
  return walkedP22(dict, p, uv, size, [&](int x, int y, int l, float logDensity) {
    if (l < base) std::abort();  // the base must lie below every footprint
    if (!baseDraw) baseDraw = kernel::glintLevelDraw(dict, p, logDensity, base);
    const int side = 1 << (l - base);
    double mean = 0.0;
    for (int j = 0; j < side; ++j) {
      for (int i = 0; i < side; ++i) {
        mean += cellP22(dict, p, kernel::glintCell(dict, p, *baseDraw, x * side + i, y * side + j, base));
      }
    }
    return mean / (static_cast<double>(side) * side);
  });
}

// The levels a sequence spans: the base below its finest footprint, the own level above its coarsest.
struct Span {
  int base;
  int top;
};

double modelP22(kernel::GlintDictionaryView dict, const GlintParameters& p, const std::string& mode, Span span,
                glm::vec2 uv, float size) {
  if (mode == "oracle") return oracleP22(dict, p, span.base, uv, size);
  GlintParameters q = p;
  q.lod = lodFromName("mode", mode);
  return kernel::glintP22(dict, q, uv, glm::vec2(size, 0.0f), glm::vec2(0.0f, size), kSlope);
}

using Frame = std::vector<double>;

// Frame t's P22, at one sample a pixel or the reference's 4 x 4.
Frame render(kernel::GlintDictionaryView dict, const GlintParameters& p, const std::string& mode, Span span,
             const Setup& setup, int t, bool reference) {
  const float pixel = static_cast<float>(setup.pixelMid * growth(t));
  const glm::vec2 centre(0.37f, 0.61f);
  Frame frame(static_cast<std::size_t>(kSize) * kSize);
  const auto rows = [&](int first, int step) {
    for (int y = first; y < kSize; y += step) {
      for (int x = 0; x < kSize; ++x) {
        const glm::vec2 at = centre + pixel * glm::vec2(x + 0.5f - 0.5f * kSize, y + 0.5f - 0.5f * kSize);
        double value = 0.0;
        if (!reference) {
          value = modelP22(dict, p, mode, span, at, pixel);
        } else {
          for (int j = 0; j < referenceSamples; ++j) {
            for (int i = 0; i < referenceSamples; ++i) {
              const glm::vec2 sample = at + pixel * ((glm::vec2(i, j) + 0.5f) / float(referenceSamples) - 0.5f);
              value += modelP22(dict, p, mode, span, sample, pixel / referenceSamples);
            }
          }
          value /= referenceSamples * referenceSamples;
        }
        frame[static_cast<std::size_t>(y) * kSize + x] = value;
      }
    }
  };
  std::thread other(rows, 1, 2);
  rows(0, 2);
  other.join();
  return frame;
}

// The glint layer: the P22 above the smooth target's, its positive part.
Frame glints(const Frame& p22, const GlintParameters& p) {
  const double smooth = kernel::glintTargetP22(p.ndf, kSlope, p.alpha, p.rho);
  Frame layer(p22.size());
  for (std::size_t i = 0; i < p22.size(); ++i) layer[i] = std::max(0.0, p22[i] - smooth);
  return layer;
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

// The share of the tree's own cells whose marginals repeat some of level 0's N single lobes: those
// whose dictionary level k has 2^k > N (4,096 own cells).
double ownCellsWithRepeatedLobes(kernel::GlintDictionaryView dict, const GlintParameters& p, int own) {
  const kernel::GlintLevelDraw draw = kernel::glintLevelDraw(dict, p, kernel::glintLayerLogDensity(p), own);
  int repeated = 0;
  for (int i = 0; i < 4096; ++i) {
    const kernel::GlintCell cell = kernel::glintTreeOwnCell(dict, p, draw, i % 64, i / 64, own);
    repeated += cell.readsDictionary && std::exp2(static_cast<double>(cell.dictionaryLevel)) > dict.numDistributions;
  }
  return repeated / 4096.0;
}

// The surface that the first frame shows, seen at the last frame's footprint, 4 times larger: the
// last frame's middle 24 x 24 pixels (`coarse`), and the means of the first frame's pixels over 4 x 4
// blocks (`averagedFine`). Levels consistent at every cell make the first the second, to the
// footprints' shapes; the 2020 model's coarse glints lie elsewhere.
struct CoarseAndFine {
  static constexpr int kWidth = kSize / 4;
  Frame coarse, averagedFine;
};

CoarseAndFine coarseAndFine(const std::vector<Frame>& p22s) {
  static_assert(kFrames > 1 && kSize % 4 == 0);  // growth(kFrames - 1) / growth(0) = 4
  const Frame& fine = p22s.front();
  const Frame& last = p22s.back();
  constexpr int w = CoarseAndFine::kWidth;
  CoarseAndFine views{Frame(w * w), Frame(w * w)};
  for (int y = 0; y < w; ++y) {
    for (int x = 0; x < w; ++x) {
      double sum = 0.0;
      for (int j = 0; j < 4; ++j) {
        for (int i = 0; i < 4; ++i) sum += fine[static_cast<std::size_t>(4 * y + j) * kSize + 4 * x + i];
      }
      views.averagedFine[static_cast<std::size_t>(y) * w + x] = sum / 16.0;
      views.coarse[static_cast<std::size_t>(y) * w + x] =
          last[static_cast<std::size_t>(y + (kSize - w) / 2) * kSize + x + (kSize - w) / 2];
    }
  }
  return views;
}

// Pearson's correlation of two frames of the same size.
double correlation(const Frame& a, const Frame& b) {
  double meanA = 0.0, meanB = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    meanA += a[i] / static_cast<double>(a.size());
    meanB += b[i] / static_cast<double>(b.size());
  }
  double ab = 0.0, aa = 0.0, bb = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    ab += (a[i] - meanA) * (b[i] - meanB);
    aa += (a[i] - meanA) * (a[i] - meanA);
    bb += (b[i] - meanB) * (b[i] - meanB);
  }
  return ab / std::max(std::sqrt(aa * bb), 1e-300);
}

// The figure's row for one construction: the first frame's glint layer, then coarseAndFine's
// averaged fine and coarse views of the same surface (drawn 4 times larger). Black to white over
// the first panel's 99th percentile, the last two over the second's.
void figureRow(const std::vector<Frame>& p22s, const GlintParameters& p) {
  const CoarseAndFine views = coarseAndFine(p22s);
  const Frame panels[3] = {glints(p22s.front(), p), glints(views.averagedFine, p), glints(views.coarse, p)};
  const auto whitePoint = [](Frame layer) {
    std::sort(layer.begin(), layer.end());
    return std::max(layer[layer.size() * 99 / 100], 1e-30);
  };
  const double whites[3] = {whitePoint(panels[0]), whitePoint(panels[1]), whitePoint(panels[1])};
  ImageRgbF row = ImageRgbF::filled(3 * kSize + 2 * 2, kSize, glm::vec3(1.0f));
  for (int panel = 0; panel < 3; ++panel) {
    const int zoom = panel == 0 ? 1 : 4, width = kSize / zoom;
    for (int y = 0; y < kSize; ++y) {
      for (int x = 0; x < kSize; ++x) {
        const double value = panels[panel][static_cast<std::size_t>(y / zoom) * width + x / zoom] / whites[panel];
        row.at(panel * (kSize + 2) + x, y) = glm::vec3(static_cast<float>(std::min(value, 1.0)));
      }
    }
  }
  if (!figure) {
    figure = row;
    return;
  }
  ImageRgbF taller = ImageRgbF::filled(row.width, figure->height + 2 + kSize, glm::vec3(1.0f));
  for (int y = 0; y < taller.height; ++y) {
    for (int x = 0; x < taller.width; ++x) {
      if (y < figure->height) taller.at(x, y) = figure->at(x, y);
      if (y >= figure->height + 2) taller.at(x, y) = row.at(x, y - figure->height - 2);
    }
  }
  figure = taller;
}

void measure(kernel::GlintDictionaryView dict, const Setup& setup, const std::string& mode, unsigned seed) {
  GlintParameters p = defaultGlintParameters();
  p.logDensity = setup.logDensity;
  p.patternSeed = seed;
  // The base below the reference's finest footprint (the first frame's, N times smaller), the
  // coarsest level walked (the last frame's floor(lod) + 1), which the tree's own level must reach.
  const float finest = static_cast<float>(setup.pixelMid * growth(0)) / referenceSamples;
  const float coarsest = static_cast<float>(setup.pixelMid * growth(kFrames - 1));
  const Span span{static_cast<int>(std::floor(dict.numLevels - 1 + std::log2(finest))),
                  static_cast<int>(std::floor(dict.numLevels - 1 + std::log2(coarsest))) + 1};
  // The oracle's base cells hold microfacets as the 2020 model's cells do: at least one (dictionary
  // level 0) however few the density gives them, so below one a cell its coarse cells would hold
  // more microfacets than the layer has. It is measured where the base holds at least one.
  const double baseMicrofacets = std::exp(static_cast<double>(p.logDensity)) * std::exp2(2.0 * (span.base - (dict.numLevels - 1)));
  if (mode == "oracle" && baseMicrofacets < 1.0) {
    std::printf("| %s | %u | %s | base %d | not measured: %.2f microfacets a base cell, which the model rounds up to 1 |\n",
                setup.name, seed, mode.c_str(), span.base, baseMicrofacets);
    std::fflush(stdout);
    return;
  }
  std::vector<Frame> modelP22s, referenceP22s, model, reference;
  for (int t = 0; t < kFrames; ++t) {
    modelP22s.push_back(render(dict, p, mode, span, setup, t, false));
    referenceP22s.push_back(render(dict, p, mode, span, setup, t, true));
    model.push_back(glints(modelP22s.back(), p));
    reference.push_back(glints(referenceP22s.back(), p));
  }
  if (figurePath && std::string(setup.name) == "dense" && seed == 0) figureRow(modelP22s, p);
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
  // RMSE as `glint lod-consistency` takes it: each frame's P22 (the radiance's glint part) against
  // the reference's, relative to the reference's mean, averaged over the frames.
  double rmse = 0;
  for (int t = 0; t < kFrames; ++t) {
    double squared = 0, mean = 0;
    for (std::size_t i = 0; i < modelP22s[t].size(); ++i) {
      squared += (modelP22s[t][i] - referenceP22s[t][i]) * (modelP22s[t][i] - referenceP22s[t][i]);
      mean += referenceP22s[t][i];
    }
    rmse += std::sqrt(squared / modelP22s[t].size()) / (mean / modelP22s[t].size()) / kFrames;
  }
  // The glint layer's correlation between neighbouring pixels (the middle frame), which share an
  // own cell of the tree more often than not: glints that neighbouring cells show independently
  // correlate only as far as the footprints overlap; a shared rotation or repeated lobes would make
  // them light up together.
  const Frame& middle = model[kFrames / 2];
  double mean = 0, meanProduct = 0, meanSquare = 0;
  int pairs = 0;
  for (int y = 0; y < kSize; ++y) {
    for (int x = 0; x + 1 < kSize; ++x) {
      const double a = middle[static_cast<std::size_t>(y) * kSize + x], b = middle[static_cast<std::size_t>(y) * kSize + x + 1];
      mean += 0.5 * (a + b);
      meanProduct += a * b;
      meanSquare += 0.5 * (a * a + b * b);
      ++pairs;
    }
  }
  mean /= pairs;
  const double neighbourCorrelation =
      (meanProduct / pairs - mean * mean) / std::max(meanSquare / pairs - mean * mean, 1e-30);
  // The middle frame's P22: its mean against the smooth target's (1 when unbiased) and its
  // coefficient of variation, how spiky the glints are.
  double p22Mean = 0.0, p22Square = 0.0;
  for (double v : modelP22s[kFrames / 2]) {
    p22Mean += v / static_cast<double>(modelP22s[kFrames / 2].size());
    p22Square += v * v / static_cast<double>(modelP22s[kFrames / 2].size());
  }
  const double target = kernel::glintTargetP22(p.ndf, kSlope, p.alpha, p.rho);
  const double variation = std::sqrt(std::max(p22Square - p22Mean * p22Mean, 0.0)) / p22Mean;
  // How far the last frame shows the first frame's glints averaged (coarseAndFine), on the P22.
  const CoarseAndFine views = coarseAndFine(modelP22s);
  const double coarseFine = correlation(views.coarse, views.averagedFine);
  std::string level = "-";
  if (mode == "oracle") level = "base " + std::to_string(span.base);
  if (mode == "tree") {
    GlintParameters tree = p;
    tree.lod = kernel::GLINT_LOD_TREE;
    const int own = kernel::glintTreeOwnLevel(dict, kernel::glintLayerLogDensity(tree));
    if (own < span.top) {
      std::fprintf(stderr, "glint_lod_oracle: the tree's own level %d is below the sequence's coarsest, %d\n", own, span.top);
      std::exit(1);
    }
    char text[64];
    std::snprintf(text, sizeof text, "own %d, %.0f%% above N lobes", own, 100.0 * ownCellsWithRepeatedLobes(dict, tree, own));
    level = text;
  }
  std::printf("| %s | %u | %s | %s | %.3f (%.3f) | %.3f | %.3f (%.3f) | %.3f | %.1f%% | %.3f | %.3f | %.3f, %.2f |\n",
              setup.name, seed, mode.c_str(), level.c_str(), overlap / energy, referenceOverlap / referenceEnergy,
              std::abs(overlap / energy - referenceOverlap / referenceEnergy), change / referenceEnergy,
              referenceChange / referenceEnergy, beyond / referenceEnergy, 100.0 * rmse, neighbourCorrelation, coarseFine,
              p22Mean / target, variation);
  std::fflush(stdout);
}

// --directions: where the glints of one small area point. For a construction, the cells whose mean
// P22 is an area's: the area of own cell `ownCell` at the dense layer's own level
// (glintTreeOwnLevel), as the cells `levelsBelow` levels below it (a nearer view) make it up. Two
// levels below, the paper's 16 cells are drawn independently (16 rotations); the tree's are blocks
// of their own cell, so their lobes lie on its one rotated grid; the oracle's, at any level, are the
// means of independent base cells four levels below the own level, what consistent levels without
// a shared rotation would give (so its list holds those 256 base cells). `realisation` offsets the
// pattern seed.
struct Area {
  GlintParameters params;
  std::vector<kernel::GlintCell> cells;
};

Area areaCells(kernel::GlintDictionaryView dict, const std::string& mode, glm::ivec2 ownCell, int levelsBelow,
               unsigned realisation = 0) {
  Area area{defaultGlintParameters(), {}};
  area.params.logDensity = kDenseLogDensity;
  area.params.patternSeed += realisation;
  const bool oracle = mode == "oracle";
  area.params.lod = oracle ? kernel::GLINT_LOD_PAPER : lodFromName("mode", mode);
  const float logDensity = kernel::glintLayerLogDensity(area.params);
  const int own = kernel::glintTreeOwnLevel(dict, logDensity);
  const int cellLevel = oracle ? own - 4 : own - levelsBelow;  // the oracle's base is fixed
  const int side = 1 << (own - cellLevel);
  const kernel::GlintLevelDraw draw = kernel::glintLevelDraw(dict, area.params, logDensity, cellLevel);
  const kernel::GlintLodDraws draws = kernel::glintLodDraws(dict, area.params, logDensity, cellLevel, draw);
  for (int y = 0; y < side; ++y) {
    for (int x = 0; x < side; ++x) {
      area.cells.push_back(kernel::glintLodCell(dict, area.params, draws, ownCell.x * side + x, ownCell.y * side + y, cellLevel));
    }
  }
  return area;
}

double areaP22(kernel::GlintDictionaryView dict, const Area& area, glm::vec2 slope) {
  double sum = 0.0;
  for (const kernel::GlintCell& cell : area.cells) sum += cellP22(dict, area.params, cell, slope);
  return sum / static_cast<double>(area.cells.size());
}

// How unevenly an area glints over directions: the coefficient of variation of its P22 over the
// slopes within one roughness of the normal (a 48 x 48 grid, the disc's), averaged over 16 own cells'
// areas. Independent lobes spread evenly; lobes on one grid glint in rows and columns. With
// `products` > 1 the area is the mean of that many independent realisations of the construction
// (pattern seeds), as a cell made of that many tensor products at their own rotations would be.
double directionsVariation(kernel::GlintDictionaryView dict, const std::string& mode, int levelsBelow,
                           unsigned products = 1) {
  // Sixteen distinct own cells of those across the pattern at the dense layer's own level (32 for
  // the default dictionary), on a diagonal-ish walk.
  const int across = 1 << (dict.numLevels - kernel::glintTreeOwnLevel(dict, kDenseLogDensity));
  double sum = 0.0;
  for (int k = 0; k < 16; ++k) {
    const glm::ivec2 ownCell((3 + 5 * k) % across, (7 + 3 * k) % across);
    std::vector<Area> areas;
    for (unsigned r = 0; r < products; ++r) areas.push_back(areaCells(dict, mode, ownCell, levelsBelow, r));
    double mean = 0.0, square = 0.0;
    int slopes = 0;
    for (int j = 0; j < 48; ++j) {
      for (int i = 0; i < 48; ++i) {
        const glm::vec2 unit((i + 0.5f) / 24.0f - 1.0f, (j + 0.5f) / 24.0f - 1.0f);
        if (glm::dot(unit, unit) > 1.0f) continue;
        double value = 0.0;
        for (const Area& area : areas) value += areaP22(dict, area, unit * area.params.alpha) / products;
        mean += value;
        square += value * value;
        ++slopes;
      }
    }
    mean /= slopes;
    sum += std::sqrt(std::max(0.0, square / slopes - mean * mean)) / mean;
  }
  return sum / 16.0;
}

// The figure: one panel a construction, left to right, each the area of own cell (5, 3) seen from
// near (4 x 4 cells) over the slopes within 1.5 roughnesses on one brightness scale, each dark dot
// a lobe, a direction in which the area glints; after the paper's, the paper's view of the same
// area from 4 times farther (its one cell there).
ImageRgbF directionsFigure(kernel::GlintDictionaryView dict, const std::vector<std::string>& modes) {
  constexpr int kPanel = 160;
  constexpr int kGap = 4;
  std::vector<Area> panels;
  for (const std::string& mode : modes) {
    panels.push_back(areaCells(dict, mode, glm::ivec2(5, 3), 2));
    if (mode == "paper") panels.push_back(areaCells(dict, mode, glm::ivec2(5, 3), 0));
  }
  ImageRgbF out = ImageRgbF::filled(static_cast<int>(panels.size()) * (kPanel + kGap) - kGap, kPanel, glm::vec3(1.0f));
  for (std::size_t m = 0; m < panels.size(); ++m) {
    const Area& area = panels[m];
    const double reach = 1.5 * area.params.alpha.x;
    const double scale = kernel::glintTargetP22(area.params.ndf, glm::vec2(0.0f), area.params.alpha, area.params.rho);
    for (int py = 0; py < kPanel; ++py) {
      for (int px = 0; px < kPanel; ++px) {
        const glm::vec2 slope(static_cast<float>(reach * (2.0 * (px + 0.5) / kPanel - 1.0)),
                              static_cast<float>(reach * (1.0 - 2.0 * (py + 0.5) / kPanel)));
        const float ink = static_cast<float>(1.0 - std::exp(-areaP22(dict, area, slope) / scale));
        out.at(static_cast<int>(m) * (kPanel + kGap) + px, py) = glm::vec3(1.0f - ink);
      }
    }
  }
  return out;
}

}  // namespace

// Usage: glint_lod_oracle [--reference-samples N] [--figure PNG] [--directions PNG] [MODE...] (defaults: 4
// samples across a pixel; paper consistent oracle tree). --directions draws directionsFigure, prints
// directionsVariation's table and stops (a second), without the zoom (--figure and
// --reference-samples have nothing to do then). Two pattern seeds of a dense layer (about 180 microfacets a pixel
// at the middle frame) and a sparse one (about 30), with pixels of 0.005 to 0.02 uv; about a minute
// on two cores at 4 samples (the oracle's cost grows as the samples' square).
int main(int argc, char** argv) {
  std::vector<std::string> modes;
  for (int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    if (arg == "--reference-samples") {
      referenceSamples = a + 1 < argc ? std::atoi(argv[++a]) : 0;
      if (referenceSamples < 1 || referenceSamples > 64) {
        std::fprintf(stderr, "glint_lod_oracle: --reference-samples takes 1 to 64 (samples across a pixel)\n");
        return 1;
      }
    } else if (arg == "--figure") {
      if (a + 1 >= argc) {
        std::fprintf(stderr, "glint_lod_oracle: --figure takes a PNG path\n");
        return 1;
      }
      figurePath = argv[++a];
    } else if (arg == "--directions") {
      if (a + 1 >= argc) {
        std::fprintf(stderr, "glint_lod_oracle: --directions takes a PNG path\n");
        return 1;
      }
      directionsPath = argv[++a];
    } else {
      modes.push_back(arg);
    }
  }
  if (modes.empty()) modes = {"paper", "consistent", "oracle", "tree"};
  for (const std::string& mode : modes) {
    if (mode != "paper" && mode != "consistent" && mode != "oracle" && mode != "tree") {
      std::fprintf(stderr, "glint_lod_oracle: unknown mode '%s' (paper, consistent, oracle or tree)\n", mode.c_str());
      return 1;
    }
  }
  const Dictionary dictionary = generateDictionary(DictionaryParameters{});
  const kernel::GlintDictionaryView dict = dictionary.view();
  if (directionsPath) {
    try {
      writePngSrgb(directionsPath, directionsFigure(dict, modes));
    } catch (const std::exception& e) {
      std::fprintf(stderr, "glint_lod_oracle: %s\n", e.what());
      return 1;
    }
    std::printf("wrote %s: where one own cell's area glints, a panel a construction\n", directionsPath);
    std::printf("| lod | variation over directions, the area as 4 x 4 cells | as one cell (a view 4 times farther) |\n|---|---|---|\n");
    for (const std::string& mode : modes) {
      std::printf("| %s | %.2f | %.2f |\n", mode.c_str(), directionsVariation(dict, mode, 2), directionsVariation(dict, mode, 0));
    }
    // A cell of two or four tensor products, each at its own rotation and each split into blocks as
    // the tree splits one: the mean of its children still, and its area more even over directions.
    for (unsigned products : {2u, 4u}) {
      for (const std::string& mode : modes) {
        if (mode != "paper" && mode != "tree") continue;
        std::printf("| %s, %u products a cell | %.2f | |\n", mode.c_str(), products, directionsVariation(dict, mode, 2, products));
      }
    }
    return 0;
  }
  // log density ln(microfacets a pixel / pixel area): 14.4 and 12.6 at 0.01 uv.
  const std::vector<Setup> setups = {{"dense", kDenseLogDensity, 0.01f}, {"sparse", 12.6f, 0.01f}};
  std::printf("| layer | seed | lod | levels | persistence (reference) | gap | change (reference) | popping | RMSE | correlation | coarse, fine | mean / target, CV |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const Setup& setup : setups) {
    for (unsigned seed : {0u, 1u}) {
      for (const std::string& mode : modes) measure(dict, setup, mode, seed);
    }
  }
  if (figurePath && figure) {
    try {
      // Drawn twice as large, each pixel a 2 x 2 block, to be seen on a page.
      ImageRgbF large = ImageRgbF::filled(2 * figure->width, 2 * figure->height);
      for (int y = 0; y < large.height; ++y) {
        for (int x = 0; x < large.width; ++x) large.at(x, y) = figure->at(x / 2, y / 2);
      }
      writePngSrgb(figurePath, large);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "glint_lod_oracle: %s\n", e.what());
      return 1;
    }
    std::printf("wrote %s: a row a construction (%s), the dense layer's seed 0\n", figurePath, [&] {
      std::string names;
      for (const std::string& mode : modes) names += (names.empty() ? "" : ", ") + mode;
      return names;
    }().c_str());
  }
  return 0;
}
