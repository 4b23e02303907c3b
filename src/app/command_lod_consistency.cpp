// `glint lod-consistency`: how the glints of a surface hold up while the camera backs away along its
// view axis and every pixel's footprint grows (docs/antialiasing.md, "Level-of-detail consistency"):
// how much of a frame's glint layer the next frame shows again, how much it pops beyond what a
// supersampled reference does, and whether its mean over a fixed patch of surface drifts.
#include <algorithm>
#include <cstdint>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "app/commands.h"
#include "app/scene_measurements.h"
#include "app/scene_options.h"
#include "gl/context.h"
#include "gl/renderer.h"
#include "glint/error.h"
#include "glint/pcg.h"

namespace glint::app {

namespace {

struct LodConsistencyOptions {
  std::vector<std::string> scenes;
  std::string size = "128x128";
  int frames = 16;
  float doublings = 2.0f;
  std::string move = "dolly";
  int referenceScale = 4;
  int referenceFrames = 4;
  int block = 4;
  std::string camera = "default";
  std::string dictionary;
  // ggaa, not ggaa+lean: under ggaa+lean the layer is taken against the glint model's smooth limit
  // (layerAgainstSmoothLimit) instead of the Cook-Torrance frame, so its figures are not those of
  // the other filters.
  std::string antiAliasing = gl::toString(gl::AntiAliasing::Ggaa);
  std::vector<std::string> lodModes;
  std::optional<std::int64_t> patternSeed;  // another realisation of every glint layer (--pattern-seed)
  bool withoutNormalMaps = false;
  bool json = false;
};

// The default scenes: a sphere (one depth), the arctic field (a normal-mapped grazing field and
// objects), a grazing plane (footprints long and thin) and the car (a built-in asset, no glTF).
const std::vector<std::string> kDefaultScenes = {"sphere", "arctic", "grazing-smooth", "carpaint"};

double luminance(const float* rgb) { return 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2]; }

// One frame's luminance, rows bottom-up, supersampled: `frames` frames at `scale` times the size,
// each jittered within its own pixels (gl::supersampleJitter; the first at the centres), averaged
// over each scale x scale block and over the frames. At scale 1 and one frame, the frame itself.
std::vector<double> renderLuminance(gl::Renderer& renderer, gl::FrameSettings frame, int scale, int frames = 1) {
  const int width = frame.width;
  const int height = frame.height;
  frame.width *= scale;
  frame.height *= scale;
  std::vector<double> out(static_cast<std::size_t>(width) * height, 0.0);
  const double weight = 1.0 / (static_cast<double>(scale) * scale * frames);
  for (int k = 0; k < frames; ++k) {
    frame.jitter = gl::supersampleJitter(k);
    renderer.renderFrame(frame);
    const std::vector<float> rgba = renderer.readRadiance();
    for (int y = 0; y < frame.height; ++y) {
      for (int x = 0; x < frame.width; ++x) {
        const std::size_t at = static_cast<std::size_t>(y) * frame.width + x;
        out[static_cast<std::size_t>(y / scale) * width + x / scale] += weight * luminance(&rgba[4 * at]);
      }
    }
  }
  return out;
}

// Where each pixel's surface point lies, from the depth buffer of the frame just drawn (at one
// sample a pixel, scale 1); `hit` is false where no mesh was drawn.
struct SurfacePoints {
  std::vector<glm::dvec3> position;
  std::vector<char> hit;
  std::vector<double> viewDepth;  // along the camera's view axis
};

struct View {
  scene::Camera camera;
  glm::dmat4 viewProjection;
  glm::dvec3 axis;
};

View makeView(const scene::Scene& scene, const scene::Camera& camera, int width, int height) {
  View view;
  view.camera = camera;
  view.viewProjection = glm::dmat4(gl::viewProjection(camera, width, height, glm::vec2(0.0f), scene.boundsMin(),
                                                      scene.boundsMax()));
  view.axis = glm::normalize(glm::dvec3(camera.target - camera.position));
  return view;
}

SurfacePoints surfacePoints(const gl::Renderer& renderer, const View& view, int width, int height) {
  const std::vector<float> depth = renderer.readDepth();
  const glm::dmat4 inverse = glm::inverse(view.viewProjection);
  SurfacePoints points;
  points.position.resize(depth.size());
  points.hit.resize(depth.size(), 0);
  points.viewDepth.resize(depth.size(), 0.0);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const std::size_t p = static_cast<std::size_t>(y) * width + x;
      if (!(depth[p] < 1.0f)) continue;
      const glm::dvec4 ndc(2.0 * (x + 0.5) / width - 1.0, 2.0 * (y + 0.5) / height - 1.0, 2.0 * depth[p] - 1.0, 1.0);
      const glm::dvec4 world = inverse * ndc;
      points.position[p] = glm::dvec3(world) / world.w;
      points.hit[p] = 1;
      points.viewDepth[p] = glm::dot(points.position[p] - glm::dvec3(view.camera.position), view.axis);
    }
  }
  return points;
}

// Where a surface point of one frame lies in another frame: its continuous pixel coordinates
// (pixel centres at k + 0.5) and the four pixels around it with their bilinear weights, or nothing
// where it leaves the frame or another surface hides it there (its view depth outside the range
// of the four pixels' depths by more than 2%).
struct Warp {
  bool valid = false;
  std::size_t pixel[4] = {};
  double weight[4] = {};
};

Warp warpInto(glm::dvec3 point, const View& view, const SurfacePoints& target, int width, int height) {
  Warp warp;
  const glm::dvec4 clip = view.viewProjection * glm::dvec4(point, 1.0);
  if (!(clip.w > 0.0)) return warp;
  const double px = (clip.x / clip.w * 0.5 + 0.5) * width - 0.5;
  const double py = (clip.y / clip.w * 0.5 + 0.5) * height - 0.5;
  const int x0 = static_cast<int>(std::floor(px));
  const int y0 = static_cast<int>(std::floor(py));
  if (x0 < 0 || y0 < 0 || x0 + 1 >= width || y0 + 1 >= height) return warp;
  const double fx = px - x0;
  const double fy = py - y0;
  const double depth = glm::dot(point - glm::dvec3(view.camera.position), view.axis);
  double nearest = 1e300, furthest = 0.0;
  for (int k = 0; k < 4; ++k) {
    const std::size_t p = static_cast<std::size_t>(y0 + k / 2) * width + static_cast<std::size_t>(x0 + k % 2);
    if (!target.hit[p]) return warp;
    nearest = std::min(nearest, target.viewDepth[p]);
    furthest = std::max(furthest, target.viewDepth[p]);
    warp.pixel[k] = p;
    warp.weight[k] = (k % 2 ? fx : 1.0 - fx) * (k / 2 ? fy : 1.0 - fy);
  }
  warp.valid = depth > 0.98 * nearest && depth < 1.02 * furthest;
  return warp;
}

double sample(const std::vector<double>& image, const Warp& warp) {
  double value = 0.0;
  for (int k = 0; k < 4; ++k) value += warp.weight[k] * image[warp.pixel[k]];
  return value;
}

// A sequence's frames: the glint layer (glint frame minus the smooth frame of the same view),
// its positive part (the glints: where the layer is above the smooth lobe) and the glint frame, per
// pixel, in luminance. The positive part is taken before any resampling: the positive part of an
// interpolation between a glint and the dark around it would lose some of the glint.
struct Sequence {
  std::vector<std::vector<double>> layer;
  std::vector<std::vector<double>> glints;
  std::vector<std::vector<double>> radiance;
};

// The figures of one LOD mode over the dolly, each beside its reference's where it has one.
struct Figures {
  double persistence = 0.0, referencePersistence = 0.0;
  double change = 0.0, referenceChange = 0.0;  // mean |layer(t) - layer(t+1) warped|, / mean |reference layer|
  double popping = 0.0;                        // the part of the change beyond the reference's, pixel by pixel
  double relativeRmse = 0.0;                   // the glint frames against the reference's, / reference's mean
  std::vector<double> drift, referenceDrift;   // the patch's mean layer / its mean smooth radiance, per frame
  double driftRange = 0.0, referenceDriftRange = 0.0;
};

struct Dolly {
  std::vector<View> views;
  std::vector<SurfacePoints> points;
  std::vector<std::vector<double>> smooth;           // the smooth frame (layerAgainstSmoothLimit), scale 1
  std::vector<std::vector<double>> referenceSmooth;  // Cook-Torrance, supersampled
  std::vector<std::vector<char>> patch;              // the fixed surface patch's pixels, per frame
};

// Frame t of N, the footprint's growth s = 2^(doublings (t / (N - 1) - 1/2)) around the preset's
// view. A dolly: the camera backs away from its target along its view axis, to s times the preset's
// distance, so a pixel's footprint on a surface at the target's distance grows s times (and the
// view directions change: the camera moves). A zoom: the camera stays and its field of view widens,
// tan(fov / 2) times s, so every pixel's footprint grows s times and the view directions stay.
scene::Camera movedCamera(const scene::Camera& preset, const std::string& move, int frame, int frames,
                          float doublings) {
  scene::Camera camera = preset;
  const double growth = std::exp2(doublings * (static_cast<double>(frame) / (frames - 1) - 0.5));
  if (move == "zoom") {
    const double halfFov = std::atan(std::tan(glm::radians(0.5 * preset.verticalFovDegrees)) * growth);
    camera.verticalFovDegrees = static_cast<float>(glm::degrees(2.0 * halfFov));
    camera.orthographicHalfHeight = static_cast<float>(preset.orthographicHalfHeight * growth);
  } else {
    const glm::vec3 offset = preset.position - preset.target;
    camera.position = preset.target + static_cast<float>(growth) * offset;
  }
  return camera;
}

// Whether the glint layer is taken against the glint model's smooth limit drawn as the measured
// frames are (renderSmoothLimit) rather than the Cook-Torrance frame: under ggaa+lean, whose
// normal-map filtering widens the glint layer's roughness by the normal map's slope covariance,
// which the Cook-Torrance program does not.
bool layerAgainstSmoothLimit(const LodConsistencyOptions& options) {
  return gl::antiAliasingFromString(options.antiAliasing) == gl::AntiAliasing::GgaaLean;
}

// The glint model's smooth limit, as a frame filters it: every glint layer covering all of its
// cells at a density whose cells are all past the dictionary's last level (their P22 is the smooth
// target's).
std::vector<double> renderSmoothLimit(gl::Renderer& renderer, gl::FrameSettings frame) {
  // e^80 4^-15 = 4^42 microfacets in a finest cell of the largest dictionary (16 levels), and with
  // no density randomisation every level's threshold is crossed exactly: all past the last level.
  constexpr float kSmoothLimitLogDensity = 80.0f;
  const std::vector<scene::Material> drawn = renderer.materials();
  for (scene::Material& material : renderer.materials()) {
    material.glint.logDensity = kSmoothLimitLogDensity;
    material.glint.densityRandomisation = 0.0f;
    material.glint.logDensityTexture = -1;
    material.glint.relativeArea = 1.0f;
    material.glint.relativeAreaTexture = -1;
  }
  frame.brdf = SpecularModel::Glint;
  std::vector<double> smooth = renderLuminance(renderer, frame, 1);
  renderer.materials() = drawn;
  return smooth;
}

// The glint energy of frame t and of frame t + 1 warped back onto frame t's pixels, summed over
// blocks of block x block pixels of frame t: the layer's positive part (the glints, above the
// smooth lobe), pixel by pixel, where the reference shows a glint layer and the surface point
// stays in view. Blocks, so that a glint that moves by a fraction of a pixel between frames
// (which the bilinear resampling cannot follow exactly) stays in its block and does not count as
// a glint lost.
struct BlockEnergies {
  std::vector<double> before, after, referenceBefore, referenceAfter;
};

BlockEnergies blockEnergies(const Dolly& dolly, const Sequence& mode, const Sequence& reference, int t, int width,
                            int height, int block) {
  const int blocksAcross = (width + block - 1) / block;
  const std::size_t blocks = static_cast<std::size_t>(blocksAcross) * ((height + block - 1) / block);
  BlockEnergies e{std::vector<double>(blocks, 0.0), std::vector<double>(blocks, 0.0), std::vector<double>(blocks, 0.0),
                  std::vector<double>(blocks, 0.0)};
  const auto now = static_cast<std::size_t>(t);
  const SurfacePoints& here = dolly.points[now];
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const std::size_t p = static_cast<std::size_t>(y) * width + x;
      if (!here.hit[p] || reference.layer[now][p] == 0.0) continue;  // no glint layer here (no glint material)
      const Warp warp = warpInto(here.position[p], dolly.views[now + 1], dolly.points[now + 1], width, height);
      if (!warp.valid) continue;
      const std::size_t b = static_cast<std::size_t>(y / block) * blocksAcross + static_cast<std::size_t>(x / block);
      e.before[b] += mode.glints[now][p];
      e.after[b] += sample(mode.glints[now + 1], warp);
      e.referenceBefore[b] += reference.glints[now][p];
      e.referenceAfter[b] += sample(reference.glints[now + 1], warp);
    }
  }
  return e;
}

Figures measureMode(const Dolly& dolly, const Sequence& mode, const Sequence& reference, int width, int height,
                    int block) {
  Figures figures;
  const int frames = static_cast<int>(dolly.views.size());
  double overlap = 0.0, energy = 0.0, referenceOverlap = 0.0, referenceEnergy = 0.0;
  double change = 0.0, referenceChange = 0.0, beyond = 0.0;
  for (int t = 0; t + 1 < frames; ++t) {
    const BlockEnergies e = blockEnergies(dolly, mode, reference, t, width, height, block);
    for (std::size_t b = 0; b < e.before.size(); ++b) {
      overlap += std::min(e.before[b], e.after[b]);
      energy += e.before[b];
      referenceOverlap += std::min(e.referenceBefore[b], e.referenceAfter[b]);
      referenceEnergy += e.referenceBefore[b];
      const double modeChange = std::abs(e.after[b] - e.before[b]);
      const double ownChange = std::abs(e.referenceAfter[b] - e.referenceBefore[b]);
      change += modeChange;
      referenceChange += ownChange;
      beyond += std::max(0.0, modeChange - ownChange);
    }
  }
  if (energy <= 0.0 || referenceEnergy <= 0.0) throw Error("no glint layer stays in view across the frames");
  // Persistence: the share of a frame's glint energy, block by block, that the next frame shows
  // again. Change and popping: the energy that comes or goes between frames, block by block, and
  // the part of it beyond the reference's in the same block, both per unit of the reference's
  // glint energy.
  figures.persistence = overlap / energy;
  figures.referencePersistence = referenceOverlap / referenceEnergy;
  figures.change = change / referenceEnergy;
  figures.referenceChange = referenceChange / referenceEnergy;
  figures.popping = beyond / referenceEnergy;
  // Error: each frame's glint radiance against the reference's, where the reference shows a glint
  // layer, relative to the reference's mean there; averaged over the frames.
  for (int t = 0; t < frames; ++t) {
    double squared = 0.0, mean = 0.0;
    std::size_t count = 0;
    for (std::size_t p = 0; p < dolly.points[static_cast<std::size_t>(t)].hit.size(); ++p) {
      if (reference.layer[static_cast<std::size_t>(t)][p] == 0.0) continue;
      const double d = mode.radiance[static_cast<std::size_t>(t)][p] - reference.radiance[static_cast<std::size_t>(t)][p];
      squared += d * d;
      mean += reference.radiance[static_cast<std::size_t>(t)][p];
      ++count;
    }
    if (count > 0 && mean > 0.0) figures.relativeRmse += std::sqrt(squared / count) / (mean / count) / frames;
  }
  // Drift: the mean glint layer over the fixed patch, relative to the patch's mean smooth radiance,
  // frame by frame.
  for (int t = 0; t < frames; ++t) {
    double layer = 0.0, referenceLayer = 0.0, smooth = 0.0, referenceSmooth = 0.0;
    for (std::size_t p = 0; p < dolly.patch[static_cast<std::size_t>(t)].size(); ++p) {
      if (!dolly.patch[static_cast<std::size_t>(t)][p]) continue;
      layer += mode.layer[static_cast<std::size_t>(t)][p];
      referenceLayer += reference.layer[static_cast<std::size_t>(t)][p];
      smooth += dolly.smooth[static_cast<std::size_t>(t)][p];
      referenceSmooth += dolly.referenceSmooth[static_cast<std::size_t>(t)][p];
    }
    figures.drift.push_back(smooth > 0.0 ? layer / smooth : 0.0);
    figures.referenceDrift.push_back(referenceSmooth > 0.0 ? referenceLayer / referenceSmooth : 0.0);
  }
  const auto range = [](const std::vector<double>& v) {
    const auto [low, high] = std::minmax_element(v.begin(), v.end());
    return *high - *low;
  };
  figures.driftRange = range(figures.drift);
  figures.referenceDriftRange = range(figures.referenceDrift);
  return figures;
}

// The fixed patch: the surface points of the first frame's central half (in each axis) that show a
// glint layer in its reference, and in every frame the pixels they fall in, where no other surface
// hides them.
void markPatch(Dolly& dolly, const std::vector<double>& firstReferenceLayer, int width, int height) {
  const SurfacePoints& first = dolly.points.front();
  for (std::size_t t = 0; t < dolly.views.size(); ++t) {
    std::vector<char> patch(first.hit.size(), 0);
    for (int y = height / 4; y < height - height / 4; ++y) {
      for (int x = width / 4; x < width - width / 4; ++x) {
        const std::size_t p = static_cast<std::size_t>(y) * width + x;
        if (!first.hit[p] || firstReferenceLayer[p] == 0.0) continue;
        const Warp warp = warpInto(first.position[p], dolly.views[t], dolly.points[t], width, height);
        if (!warp.valid) continue;
        const int nearest = static_cast<int>(std::max_element(warp.weight, warp.weight + 4) - warp.weight);
        patch[warp.pixel[nearest]] = 1;
      }
    }
    dolly.patch.push_back(std::move(patch));
  }
}

// How aligned the glints of neighbouring cells are: the mean resultant length of the doubled
// rotation angles (a cell's lobes are symmetric under a half turn) of the cells that read the
// dictionary, in windows of `window` x `window` cells at random levels and places, averaged over
// the windows. Independent angles give about 0.89 / sqrt(n) for n cells; cells sharing one angle 1.
double alignment(const Dictionary& dictionary, GlintParameters params, int window) {
  const kernel::GlintDictionaryView dict = dictionary.view();
  glint::Pcg32 rng(2107, static_cast<std::uint64_t>(window));
  double sum = 0.0;
  int windows = 0;
  for (int i = 0; i < 4000; ++i) {
    const int level = 1 + static_cast<int>(rng.nextBelow(static_cast<std::uint32_t>(dict.numLevels - 2)));
    const int across = 1 << (16 - level);
    const int x0 = static_cast<int>(rng.nextBelow(static_cast<std::uint32_t>(across))) & ~(window - 1);
    const int y0 = static_cast<int>(rng.nextBelow(static_cast<std::uint32_t>(across))) & ~(window - 1);
    const float logDensity = kernel::glintLayerLogDensity(params);
    const kernel::GlintLevelDraw draw = kernel::glintLevelDraw(dict, params, logDensity, level);
    const kernel::GlintLodDraws draws = kernel::glintLodDraws(dict, params, logDensity, level, draw);
    glm::dvec2 resultant(0.0);
    int cells = 0;
    for (int y = y0; y < y0 + window; ++y) {
      for (int x = x0; x < x0 + window; ++x) {
        const kernel::GlintCell cell = kernel::glintLodCell(dict, params, draws, x, y, level);
        if (!cell.readsDictionary) continue;
        const glm::vec2 r = kernel::glintCellRotation(cell.hash);  // (cos t, sin t)
        resultant += glm::dvec2(r.x * r.x - r.y * r.y, 2.0 * r.x * r.y);  // (cos 2t, sin 2t)
        ++cells;
      }
    }
    if (cells < 2) continue;
    sum += glm::length(resultant) / cells;
    ++windows;
  }
  return windows > 0 ? sum / windows : 0.0;
}

// The glint layer whose cells the alignment is measured on: the scene's first.
std::optional<GlintParameters> firstGlintLayer(const scene::Scene& scene) {
  for (const scene::Material& m : scene.materials) {
    if (m.glint.enabled) return kernel::glintMaterialConstants(scene::glintMaterial(m.glint, m.specular), exactFootprintPolicy());
  }
  return std::nullopt;
}

nlohmann::json measureScene(const scene::Scene& scene, const Dictionary& dictionary,
                            const LodConsistencyOptions& options, int width, int height) {
  gl::Renderer renderer(scene, dictionary);
  printWarnings(renderer.warnings());
  gl::FrameSettings frame;
  frame.width = width;
  frame.height = height;
  const scene::Camera preset = scene.cameras.at(options.camera);

  // The views, their surface points and their smooth frames, shared by every mode.
  Dolly dolly;
  for (int t = 0; t < options.frames; ++t) {
    frame.camera = movedCamera(preset, options.move, t, options.frames, options.doublings);
    dolly.views.push_back(makeView(scene, frame.camera, width, height));
    frame.brdf = SpecularModel::CookTorrance;
    frame.antiAliasing = gl::AntiAliasing::None;
    frame.normalMapFinestLevel = true;
    dolly.referenceSmooth.push_back(renderLuminance(renderer, frame, options.referenceScale, options.referenceFrames));
    frame.antiAliasing = gl::antiAliasingFromString(options.antiAliasing);
    frame.normalMapFinestLevel = false;
    dolly.smooth.push_back(layerAgainstSmoothLimit(options) ? renderSmoothLimit(renderer, frame)
                                                            : renderLuminance(renderer, frame, 1));
    dolly.points.push_back(surfacePoints(renderer, dolly.views.back(), width, height));
  }

  nlohmann::json entry = {{"scene", scene.name}};
  bool patchMarked = false;
  for (const std::string& lodMode : options.lodModes) {
    // Every glint layer takes the construction, the reference's frames too: each is measured
    // against the supersampled image of its own glints.
    for (scene::Material& material : renderer.materials()) material.glint.lod = lodFromName("--lod", lodMode);
    Sequence mode, reference;
    for (int t = 0; t < options.frames; ++t) {
      frame.camera = dolly.views[static_cast<std::size_t>(t)].camera;
      frame.brdf = SpecularModel::Glint;
      // The reference: the 2020 model (no anti-aliasing) at referenceScale^2 samples a pixel on a
      // regular grid, its footprints that many times smaller: finer levels of detail, averaged.
      frame.antiAliasing = gl::AntiAliasing::None;
      frame.normalMapFinestLevel = true;
      reference.radiance.push_back(renderLuminance(renderer, frame, options.referenceScale, options.referenceFrames));
      frame.antiAliasing = gl::antiAliasingFromString(options.antiAliasing);
      frame.normalMapFinestLevel = false;
      mode.radiance.push_back(renderLuminance(renderer, frame, 1));
      std::vector<double> layer = mode.radiance.back(), referenceLayer = reference.radiance.back();
      for (std::size_t p = 0; p < layer.size(); ++p) {
        layer[p] -= dolly.smooth[static_cast<std::size_t>(t)][p];
        referenceLayer[p] -= dolly.referenceSmooth[static_cast<std::size_t>(t)][p];
      }
      const auto positive = [](std::vector<double> v) {
        for (double& x : v) x = std::max(x, 0.0);
        return v;
      };
      mode.glints.push_back(positive(layer));
      reference.glints.push_back(positive(referenceLayer));
      mode.layer.push_back(std::move(layer));
      reference.layer.push_back(std::move(referenceLayer));
    }
    if (!patchMarked) {
      markPatch(dolly, reference.layer.front(), width, height);
      patchMarked = true;
    }
    const Figures f = measureMode(dolly, mode, reference, width, height, options.block);
    std::optional<GlintParameters> layer = firstGlintLayer(scene);
    if (!layer) throw Error("scene '" + scene.name + "' has no glint layer");
    layer->lod = lodFromName("--lod", lodMode);
    entry["modes"][lodMode] = {{"alignment_2x2", alignment(dictionary, *layer, 2)},
                               {"alignment_4x4", alignment(dictionary, *layer, 4)},
                               {"persistence", f.persistence},
                               {"reference_persistence", f.referencePersistence},
                               {"change", f.change},
                               {"reference_change", f.referenceChange},
                               {"popping", f.popping},
                               {"relative_rmse", f.relativeRmse},
                               {"drift", f.drift},
                               {"reference_drift", f.referenceDrift},
                               {"drift_range", f.driftRange},
                               {"reference_drift_range", f.referenceDriftRange}};
  }
  return entry;
}

void runLodConsistency(LodConsistencyOptions options) {
  const auto [width, height] = parseImageSize(options.size);
  if (options.frames < 2 || options.frames > 1024) throw Error("--frames must be in [2, 1024]");
  if (!(options.doublings > 0.0f && options.doublings <= 8.0f)) throw Error("--doublings must be in (0, 8]");
  if (options.referenceScale < 1 || options.referenceScale > 16) throw Error("--reference-scale must be in [1, 16]");
  if (options.referenceFrames < 1 || options.referenceFrames > 1024) throw Error("--reference-frames must be in [1, 1024]");
  if (options.block < 1 || options.block > 64) throw Error("--block must be in [1, 64]");
  if (options.move != "dolly" && options.move != "zoom") throw Error("--move must be dolly or zoom, not '" + options.move + "'");
  if (options.move == "zoom" && !(std::exp2(0.5 * options.doublings) * std::tan(glm::radians(0.5f * 45.0f)) < 1e3)) {
    throw Error("--doublings is too large for a zoom");
  }
  gl::antiAliasingFromString(options.antiAliasing);  // throws naming the choices
  if (options.lodModes.empty()) options.lodModes = {"paper", "consistent", "tree"};
  for (const std::string& lodMode : options.lodModes) lodFromName("--lod", lodMode);  // throws naming the choices
  requireEachOnce(options.lodModes, "--lod");
  const std::vector<std::string> names = options.scenes.empty() ? kDefaultScenes : options.scenes;
  SceneOptions sceneOptions;
  sceneOptions.dictionary = options.dictionary;
  sceneOptions.patternSeed = options.patternSeed;
  sceneOptions.camera = options.camera;
  std::vector<scene::Scene> scenes = sceneOptions.loadScenes(names);
  if (options.withoutNormalMaps) {
    // The measured frames read a normal map at the footprint's mip level and the reference at its
    // finest: under sharp glints that difference alone pops and errs, whatever the construction.
    for (scene::Scene& scene : scenes) {
      for (scene::Material& material : scene.materials) material.normalTexture = -1;
    }
  }
  const Dictionary dictionary = sceneOptions.loadDictionary();
  gl::HeadlessContext context;
  nlohmann::json report = {{"renderer", gl::currentContextInfo().renderer},
                           {"size", options.size},
                           {"frames", options.frames},
                           {"doublings", options.doublings},
                           {"move", options.move},
                           {"reference_scale", options.referenceScale},
                           {"reference_frames", options.referenceFrames},
                           {"block", options.block},
                           {"aa", options.antiAliasing},
                           {"normal_maps", !options.withoutNormalMaps},
                           {"smooth_frame", layerAgainstSmoothLimit(options) ? "glint-smooth-limit" : "cook-torrance"},
                           {"scenes", nlohmann::json::array()}};
  // The size by value: clang 14's lambdas cannot capture a structured binding by reference.
  measureScenes(scenes, report, [&, w = width, h = height](const scene::Scene& scene) {
    try {
      return measureScene(scene, dictionary, options, w, h);
    } catch (const Error& e) {
      throw Error("scene '" + scene.name + "': " + e.what());  // which of the scenes it was
    }
  });
  if (options.json) {
    std::printf("%s\n", report.dump(2).c_str());
    return;
  }
  std::printf("%s of %d frames, footprint doubled %.3g times, %s at %s (%s); reference: the 2020 model at %dx%d "
              "samples a pixel, %d jittered frames; glint energy over %dx%d-pixel blocks, the layer against %s%s\n",
              options.move.c_str(), options.frames, options.doublings, options.antiAliasing.c_str(), options.size.c_str(),
              report["renderer"].get<std::string>().c_str(), options.referenceScale, options.referenceScale,
              options.referenceFrames, options.block, options.block,
              layerAgainstSmoothLimit(options) ? "the glint smooth limit" : "Cook-Torrance",
              options.withoutNormalMaps ? "; normal maps left out" : "");
  std::printf("%-16s %-12s %12s %12s %10s %10s %10s %12s %12s %10s %10s %10s\n", "scene", "lod", "persistence",
              "(reference)", "change", "(ref.)", "popping", "drift range", "(reference)", "RMSE", "align 2x2",
              "align 4x4");
  for (const auto& entry : report["scenes"]) {
    for (const std::string& lodMode : options.lodModes) {
      const auto& m = entry["modes"][lodMode];
      std::printf("%-16s %-12s %12.3f %12.3f %10.3f %10.3f %10.3f %12.4f %12.4f %9.1f%% %10.3f %10.3f\n",
                  entry["scene"].get<std::string>().c_str(), lodMode.c_str(), m["persistence"].get<double>(),
                  m["reference_persistence"].get<double>(), m["change"].get<double>(),
                  m["reference_change"].get<double>(), m["popping"].get<double>(), m["drift_range"].get<double>(),
                  m["reference_drift_range"].get<double>(), 100.0 * m["relative_rmse"].get<double>(),
                  m["alignment_2x2"].get<double>(), m["alignment_4x4"].get<double>());
    }
  }
}

}  // namespace

void registerLodConsistencyCommand(CLI::App& app) {
  auto options = std::make_shared<LodConsistencyOptions>();
  CLI::App* command = app.add_subcommand(
      "lod-consistency", "Measure how glints persist, pop and drift while the camera backs away (a dolly)");
  command->add_option("scenes", options->scenes, "Scenes to measure (default: sphere arctic grazing-smooth carpaint)");
  command->add_option("--size", options->size, "Frame size WxH")->capture_default_str();
  command->add_option("--frames", options->frames, "Frames of the dolly")->capture_default_str();
  command->add_option("--doublings", options->doublings, "How many times the footprint doubles over the dolly")
      ->capture_default_str();
  command->add_option("--move", options->move,
                      "How the footprint grows: dolly (the camera backs away along its view axis) or zoom (its field "
                      "of view widens)")
      ->capture_default_str();
  command->add_option("--reference-scale", options->referenceScale,
                      "The reference's samples a pixel along each axis (the 2020 model)")
      ->capture_default_str();
  command->add_option("--reference-frames", options->referenceFrames,
                      "Jittered frames of the reference, each at --reference-scale")
      ->capture_default_str();
  command->add_option("--block", options->block, "Side in pixels of the blocks glint energy is compared over")
      ->capture_default_str();
  command->add_option("--aa", options->antiAliasing, "Anti-aliasing of the measured frames")->capture_default_str();
  command->add_option("--lod", options->lodModes,
                      "LOD constructions to measure, each on the same frames (repeatable): paper, consistent, "
                      "tree (default: all three)");
  command->add_option("--camera", options->camera, "Camera preset the dolly starts around")->capture_default_str();
  command->add_option("--dict", options->dictionary, "Dictionary file or the authors' EXR folder");
  command->add_option("--pattern-seed", options->patternSeed,
                      "Every glint layer's pattern seed, 0..4294967295: the figures of another realisation");
  command->add_flag("--without-normal-maps", options->withoutNormalMaps,
                   "Leave every material's normal map out, so that the figures measure the glint construction "
                   "alone (the measured frames read a normal map filtered, the reference at its finest level)");
  command->add_flag("--json", options->json, "Print the measurements as JSON");
  command->callback([options] { runLodConsistency(*options); });
}

}  // namespace glint::app
