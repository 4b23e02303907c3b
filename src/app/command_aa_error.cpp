// `glint aa-error`: how far each anti-aliasing mode's frame is from the supersampled reference, and
// how much its glints flicker under sub-pixel camera drift (docs/antialiasing.md, "Metrics").
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <optional>

#include <nlohmann/json.hpp>

#include "app/commands.h"
#include "app/raster_options.h"
#include "app/scene_measurements.h"
#include "app/scene_options.h"
#include "gl/context.h"
#include "gl/renderer.h"
#include "glint/error.h"

namespace glint::app {

namespace {

struct AaErrorOptions {
  std::vector<std::string> scenes;
  std::string size = "256x256";
  int reference = 256;
  int sequence = 32;
  std::string camera = "default";
  std::string dictionary;
  std::optional<std::string> lod;  // every glint layer's LOD construction (--lod), the scene's own otherwise
  float aaKernel = 1.0f;
  bool json = false;
  FootprintOptions footprint;
  // Which footprint draws the reference: "paper" (the paper's, for every policy) or "same" (each
  // policy's own, which asks whether a policy's centre frame shows the pixel's mean of its own glints).
  std::string referenceFootprint = "paper";
  // Cost tiers (--quality, gl::qualityPresets) measured besides the modes: each tier's footprint,
  // anti-aliasing and cascades against the paper's reference.
  std::vector<std::string> qualities;
};

using Frame = std::vector<double>;  // RGB radiance, pixel after pixel

Frame renderFrame(gl::Renderer& renderer, gl::FrameSettings frame) {
  renderer.renderFrame(frame);
  const std::vector<float> rgba = renderer.readRadiance();
  Frame rgb(rgba.size() / 4 * 3);
  for (std::size_t p = 0; p < rgba.size() / 4; ++p) {
    for (int c = 0; c < 3; ++c) rgb[3 * p + static_cast<std::size_t>(c)] = rgba[4 * p + static_cast<std::size_t>(c)];
  }
  return rgb;
}

// The glint layer's radiance: a glint frame minus the Cook-Torrance frame of the same view; where
// it is not zero, the metrics look.
Frame glintLayer(gl::Renderer& renderer, gl::FrameSettings frame, const Frame& glint) {
  frame.brdf = SpecularModel::CookTorrance;
  const Frame smooth = renderFrame(renderer, frame);
  Frame layer = glint;
  for (std::size_t i = 0; i < layer.size(); ++i) layer[i] -= smooth[i];
  return layer;
}

// The values where the glint layer shows in the reference (its glint and Cook-Torrance frames
// differ): the pixels the metrics are taken over.
std::vector<std::size_t> glintValues(const Frame& referenceLayer) {
  std::vector<std::size_t> values;
  for (std::size_t p = 0; p + 2 < referenceLayer.size(); p += 3) {
    if (referenceLayer[p] != 0.0 || referenceLayer[p + 1] != 0.0 || referenceLayer[p + 2] != 0.0) {
      for (std::size_t c = 0; c < 3; ++c) values.push_back(p + c);
    }
  }
  return values;
}

// The reference under a footprint policy: the mean of N jittered frames of the 2020 model (glint
// render --reference N), and of their glint layers, which say where the metrics look.
struct Reference {
  Frame radiance;
  Frame layer;
};

Reference drawReference(gl::Renderer& renderer, gl::FrameSettings frame, const AaErrorOptions& options,
                        const FootprintPolicy& policy) {
  frame.antiAliasing = gl::AntiAliasing::None;
  frame.normalMapFinestLevel = true;
  frame.footprintPolicy = policy;
  Reference reference{Frame(static_cast<std::size_t>(frame.width) * frame.height * 3, 0.0), {}};
  reference.layer = reference.radiance;
  for (int k = 0; k < options.reference; ++k) {
    frame.jitter = gl::supersampleJitter(k);
    const Frame radiance = renderFrame(renderer, frame);
    const Frame layer = glintLayer(renderer, frame, radiance);
    for (std::size_t i = 0; i < radiance.size(); ++i) {
      reference.radiance[i] += radiance[i] / options.reference;
      reference.layer[i] += layer[i] / options.reference;
    }
  }
  return reference;
}

// The mean of a frame over the given values.
double meanOver(const Frame& frame, const std::vector<std::size_t>& values) {
  double mean = 0.0;
  for (std::size_t i : values) mean += frame[i] / static_cast<double>(values.size());
  return mean;
}

// One mode's error against the reference (relative to that reference's mean) and its flicker
// (relative to the paper's reference's mean, so that the policies' flickers divide by one figure).
nlohmann::json measureMode(gl::Renderer& renderer, gl::FrameSettings frame, const AaErrorOptions& options,
                           const std::vector<std::size_t>& values, const Frame& reference, double referenceMean,
                           double flickerMean) {
  frame.normalMapFinestLevel = false;
  frame.jitter = glm::vec2(0.0f);
  const Frame centre = renderFrame(renderer, frame);
  double squared = 0.0;
  for (std::size_t i : values) squared += (centre[i] - reference[i]) * (centre[i] - reference[i]);
  const double relativeRmse = std::sqrt(squared / static_cast<double>(values.size())) / referenceMean;
  // Sub-pixel drift: the camera moves one pixel along a slanted line over the sequence.
  std::vector<double> sum(centre.size(), 0.0), sumSquares(centre.size(), 0.0);
  for (int k = 0; k < options.sequence; ++k) {
    const float t = (static_cast<float>(k) + 0.5f) / static_cast<float>(options.sequence) - 0.5f;
    frame.jitter = t * glm::vec2(1.0f, 0.37f);
    const Frame layer = renderFrame(renderer, frame);
    for (std::size_t i = 0; i < layer.size(); ++i) {
      sum[i] += layer[i];
      sumSquares[i] += layer[i] * layer[i];
    }
  }
  double deviation = 0.0;
  for (std::size_t i : values) {
    const double m = sum[i] / options.sequence;
    deviation += std::sqrt(std::max(0.0, sumSquares[i] / options.sequence - m * m));
  }
  const double relativeFlicker = deviation / static_cast<double>(values.size()) / flickerMean;
  return {{"relative_rmse", relativeRmse}, {"relative_flicker", relativeFlicker}};
}

// Each policy is measured on the same frames (the same jitters and drift), one after the other, and
// over the same pixels: those where the paper's reference shows glints. The reference is the
// paper's footprint's whatever --footprint says, so that a policy's error includes the different
// glints it shows, unless --reference-footprint same draws each policy's own.
nlohmann::json measureScene(const scene::Scene& scene, const Dictionary& dictionary, const AaErrorOptions& options,
                            int width, int height) {
  const std::vector<std::pair<std::string, FootprintPolicy>> footprints = options.footprint.all();
  gl::Renderer renderer(scene, dictionary);
  printWarnings(renderer.warnings());
  gl::FrameSettings frame;
  frame.width = width;
  frame.height = height;
  frame.brdf = SpecularModel::Glint;
  frame.camera = scene.cameras.at(options.camera);
  frame.filterScale = options.aaKernel;

  const Reference paperReference = drawReference(renderer, frame, options, FootprintPolicy{});
  // Errors are relative to the reference's mean radiance where its glint layer shows.
  const std::vector<std::size_t> values = glintValues(paperReference.layer);
  if (values.empty()) throw Error("scene '" + scene.name + "' shows no glint layer from camera '" + options.camera + "'");
  const double paperMean = meanOver(paperReference.radiance, values);

  nlohmann::json entry = {{"scene", scene.name},
                          {"reference_mean", paperMean},
                          {"glint_pixels", values.size() / 3}};
  const bool ownReference = options.referenceFootprint == "same";
  for (const auto& [policyName, policy] : footprints) {
    const bool paper = !ownReference || footprintPolicyName(policy) == "exact";
    const Reference own = paper ? Reference{} : drawReference(renderer, frame, options, policy);
    const Frame& reference = paper ? paperReference.radiance : own.radiance;
    const double referenceMean = paper ? paperMean : meanOver(own.radiance, values);
    if (ownReference) entry["footprints"][policyName]["reference_mean"] = referenceMean;
    frame.footprintPolicy = policy;
    for (const gl::AntiAliasing mode : gl::allAntiAliasingModes()) {
      frame.antiAliasing = mode;
      const nlohmann::json measured = measureMode(renderer, frame, options, values, reference, referenceMean, paperMean);
      if (policyName == footprints.front().first) entry[gl::toString(mode)] = measured;
      entry["footprints"][policyName][gl::toString(mode)] = measured;
    }
  }
  for (const std::string& name : options.qualities) {
    const gl::QualityPreset& preset = gl::qualityPreset(name);
    gl::FrameSettings tier = frame;
    tier.footprintPolicy = footprintPolicyFromString(preset.footprint);
    tier.antiAliasing = preset.antiAliasing;
    tier.shadowCascades = preset.shadowCascades;
    entry["qualities"][name] = measureMode(renderer, tier, options, values, paperReference.radiance, paperMean, paperMean);
  }
  return entry;
}

void runAaError(const AaErrorOptions& options) {
  const auto [width, height] = parseImageSize(options.size);
  const std::vector<std::pair<std::string, FootprintPolicy>> footprints = options.footprint.all();
  if (options.reference < 1 || options.reference > 65536) throw Error("--reference must be in [1, 65536]");
  if (options.sequence < 2 || options.sequence > 4096) throw Error("--sequence must be in [2, 4096]");
  if (!(options.aaKernel >= 0.0f && options.aaKernel <= 16.0f)) throw Error("--aa-kernel must be in [0, 16]");
  if (options.referenceFootprint != "paper" && options.referenceFootprint != "same") {
    throw Error("--reference-footprint must be paper or same, not '" + options.referenceFootprint + "'");
  }
  for (const std::string& name : options.qualities) {
    try {
      gl::qualityPreset(name);
    } catch (const Error& error) {
      throw Error(std::string("--quality: ") + error.what());
    }
  }
  requireEachOnce(options.qualities, "--quality");
  const std::vector<std::string> names = options.scenes.empty() ? std::vector<std::string>{"sphere"} : options.scenes;
  SceneOptions sceneOptions;
  sceneOptions.dictionary = options.dictionary;
  sceneOptions.lod = options.lod;
  sceneOptions.camera = options.camera;
  const std::vector<scene::Scene> scenes = sceneOptions.loadScenes(names);
  const Dictionary dictionary = sceneOptions.loadDictionary();
  gl::HeadlessContext context;
  nlohmann::json report = {{"renderer", gl::currentContextInfo().renderer},
                           {"aa_kernel", options.aaKernel},
                           {"footprint", options.footprint.all().front().first},
                           {"reference_footprint", options.referenceFootprint},
                           {"size", options.size},
                           {"reference_frames", options.reference},
                           {"sequence_frames", options.sequence},
                           {"scenes", nlohmann::json::array()}};
  // The size by value: clang 14's lambdas cannot capture a structured binding by reference.
  measureScenes(scenes, report, [&, w = width, h = height](const scene::Scene& scene) {
    return measureScene(scene, dictionary, options, w, h);
  });
  if (options.json) {
    std::printf("%s\n", report.dump(2).c_str());
    return;
  }
  std::printf("glint layer against the %d-frame reference at %s (%s); flicker over %d frames of sub-pixel drift\n",
              options.reference, options.size.c_str(), report["renderer"].get<std::string>().c_str(), options.sequence);
  // Each mode's RMSE and flicker, and both as ratios to the 2020 model's (none).
  std::printf("%-16s", "scene");
  for (const gl::AntiAliasing mode : gl::allAntiAliasingModes()) {
    std::printf(" %22s", (std::string("RMSE ") + gl::toString(mode)).c_str());
  }
  for (const gl::AntiAliasing mode : gl::allAntiAliasingModes()) {
    std::printf(" %22s", (std::string("flicker ") + gl::toString(mode)).c_str());
  }
  std::printf("\n");
  for (const auto& entry : report["scenes"]) {
    std::printf("%-16s", entry["scene"].get<std::string>().c_str());
    for (const char* metric : {"relative_rmse", "relative_flicker"}) {
      const double none = entry["none"][metric];
      for (const gl::AntiAliasing mode : gl::allAntiAliasingModes()) {
        const double value = entry[gl::toString(mode)][metric];
        char cell[64];
        std::snprintf(cell, sizeof cell, "%.1f%% (%.3f)", 100.0 * value, value / none);
        std::printf(" %22s", cell);
      }
    }
    std::printf("\n");
  }
  if (!options.qualities.empty()) {
    // Each tier's RMSE and flicker against the paper's reference, and their ratios to the last tier
    // given (exact, when it is given last).
    const std::string& last = options.qualities.back();
    std::printf("\nquality tiers against the paper's footprint's reference (ratio to %s)\n", last.c_str());
    std::printf("%-16s %-8s %22s %22s\n", "scene", "quality", "RMSE", "flicker");
    for (const auto& entry : report["scenes"]) {
      for (const std::string& name : options.qualities) {
        std::printf("%-16s %-8s", entry["scene"].get<std::string>().c_str(), name.c_str());
        for (const char* metric : {"relative_rmse", "relative_flicker"}) {
          const double value = entry["qualities"][name][metric];
          const double reference = entry["qualities"][last][metric];
          char cell[64];
          std::snprintf(cell, sizeof cell, "%.2f%% (%.3f)", 100.0 * value, value / reference);
          std::printf(" %22s", cell);
        }
        std::printf("\n");
      }
    }
  }
  if (footprints.size() < 2) return;
  // Each footprint policy's RMSE and flicker, and both as ratios to the first policy's, mode by mode.
  std::printf("\nfootprint policies, each against %s (ratio to %s)\n",
              options.referenceFootprint == "same" ? "its own reference" : "the paper's footprint's reference",
              footprints.front().first.c_str());
  std::printf("%-16s %-20s", "scene", "footprint");
  for (const char* metric : {"RMSE ", "flicker "}) {
    for (const gl::AntiAliasing mode : gl::allAntiAliasingModes()) {
      std::printf(" %22s", (std::string(metric) + gl::toString(mode)).c_str());
    }
  }
  std::printf("\n");
  for (const auto& entry : report["scenes"]) {
    for (const auto& [policyName, policy] : footprints) {
      std::printf("%-16s %-20s", entry["scene"].get<std::string>().c_str(), policyName.c_str());
      for (const char* metric : {"relative_rmse", "relative_flicker"}) {
        for (const gl::AntiAliasing mode : gl::allAntiAliasingModes()) {
          const double first = entry["footprints"][footprints.front().first][gl::toString(mode)][metric];
          const double value = entry["footprints"][policyName][gl::toString(mode)][metric];
          char cell[64];
          std::snprintf(cell, sizeof cell, "%.2f%% (%.3f)", 100.0 * value, value / first);
          std::printf(" %22s", cell);
        }
      }
      std::printf("\n");
    }
  }
}

}  // namespace

void registerAaErrorCommand(CLI::App& app) {
  auto options = std::make_shared<AaErrorOptions>();
  CLI::App* command = app.add_subcommand(
      "aa-error", "Measure each anti-aliasing mode's glint error against a supersampled reference, and its flicker");
  command->add_option("scenes", options->scenes, "Scenes to measure (default: sphere)");
  command->add_option("--size", options->size, "Frame size WxH")->capture_default_str();
  command->add_option("--reference", options->reference,
                      "Jittered frames of the 2020 model averaged into the reference")
      ->capture_default_str();
  command->add_option("--sequence", options->sequence, "Frames of sub-pixel camera drift for the flicker")
      ->capture_default_str();
  command->add_option("--camera", options->camera, "Camera preset (every scene must have it)")->capture_default_str();
  command->add_option("--aa-kernel", options->aaKernel, "Size of the anti-aliasing kernel (as glint render's)")
      ->capture_default_str();
  command->add_option("--dict", options->dictionary, "Dictionary file or the authors' EXR folder");
  command->add_option("--lod", options->lod,
                      "The level-of-detail construction of every glint layer, reference included: paper, consistent or tree");
  options->footprint.addTo(*command, true);
  command->add_option("--reference-footprint", options->referenceFootprint,
                      "Footprint of the reference: paper (the paper's, for every policy) or same (each policy's own)")
      ->capture_default_str();
  std::string tiers;
  for (const gl::QualityPreset& preset : gl::qualityPresets()) tiers += (tiers.empty() ? "" : ", ") + std::string(preset.name);
  command->add_option("--quality", options->qualities,
                      "Also measure a cost tier (" + tiers + "): its footprint, anti-aliasing and cascades against "
                      "the paper's reference; repeat it for several")
      ->allow_extra_args(false);
  command->add_flag("--json", options->json, "Print the measurements as JSON");
  command->callback([options] { runAaError(*options); });
}

}  // namespace glint::app
