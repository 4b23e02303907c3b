// `glint bench`: frame times per scene and BRDF, with the ratios glint / Cook-Torrance (and glint /
// every other model) measured in the same run (docs/benchmarks.md).
#include <algorithm>
#include <cstdio>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "app/commands.h"
#include "app/raster_options.h"
#include "app/scene_options.h"
#include "gl/context.h"
#include "gl/frame_timer.h"
#include "gl/renderer.h"
#include "glint/error.h"
#include "scene/area_lights.h"
#include "scene/builtin_scenes.h"

namespace glint::app {

namespace {

struct BenchOptions {
  std::vector<std::string> scenes;
  std::string size = "512x512";
  int frames = 20;
  int warmup = 3;
  bool json = false;
  std::string dictionary;
  std::optional<std::string> lod;  // every glint layer's LOD construction (--lod), the scene's own otherwise
  std::string camera = "default";
  CameraOptions cameraOptions;
  std::string antiAliasing = "ggaa+lean";
  bool gltfTarget = false;
  RasterOptions raster;
  FootprintOptions footprint;
  QualityOptions quality;
  bool featureCost = false;
  EnvironmentOptions environment;
  bool compareEnvironmentLights = false;
  std::vector<float> rectLights;  // --rect-light, as for render
  bool compareExtendedLights = false;
};

// What one column of the table times: a specular model under an anti-aliasing mode. With glint
// anti-aliased, the 2020 model (glint-none) is timed in the same alternation, for the filter's cost.
// With --gltf-target, glint is timed a second time with every material's specular lobe turned to
// glTF's (GGX, Smith, multiple-scattering compensation: scene::kGltfSpecular), glint-gltf. With
// --feature-cost, glint is timed without shadows (glint-no-shadows), at one sample a pixel
// (glint-msaa1), with its shadow maps drawn again every frame (glint-moving-lights: the renderer
// keeps them while the lights and the camera stay, so the other columns only read them), and with
// one shadow map a directional light instead of cascades (glint-one-cascade).
// --compare-env-lights, glint is timed a second time without the directional lights taken out of
// the environment map (scene::Environment::rasterLights 0), glint-no-env-lights. With
// --compare-extended-lights, glint is timed with each area light replaced by a point light at its
// centre (glint-area-as-points: intensity radiance times area, its mesh no longer emitting) and
// without the environment's regions (glint-no-env-regions: the whole map prefiltered).
struct Variant {
  std::string label;
  SpecularModel brdf;
  gl::AntiAliasing antiAliasing;
  bool gltfTarget = false;
  bool withoutEnvironmentLights = false;
  bool areaAsPoints = false;
  bool withoutEnvironmentRegions = false;
  bool noShadows = false;
  bool oneSample = false;
  bool movingLights = false;
  bool oneCascade = false;
  FootprintPolicy footprint = exactFootprintPolicy();
};

// The column of glint under one of the other --footprint policies.
std::string policyColumn(const std::string& policyName) { return "glint[" + policyName + "]"; }

// With several --footprint policies, the first is every column's, and glint is timed again with each
// of the others, glint[policy].
std::vector<Variant> benchVariants(gl::AntiAliasing antiAliasing, bool gltfTarget, bool compareEnvironmentLights,
                                   bool compareExtendedLights, bool featureCost,
                                   const std::vector<std::pair<std::string, FootprintPolicy>>& footprints) {
  std::vector<Variant> variants;
  for (SpecularModel model : allSpecularModels()) variants.push_back({toString(model), model, antiAliasing});
  if (antiAliasing != gl::AntiAliasing::None) variants.push_back({"glint-none", SpecularModel::Glint, gl::AntiAliasing::None});
  if (gltfTarget) variants.push_back({"glint-gltf", SpecularModel::Glint, antiAliasing, true});
  if (compareEnvironmentLights) {
    variants.push_back({"glint-no-env-lights", SpecularModel::Glint, antiAliasing, false, true});
  }
  if (compareExtendedLights) {
    Variant points{"glint-area-as-points", SpecularModel::Glint, antiAliasing};
    points.areaAsPoints = true;
    variants.push_back(points);
    Variant prefiltered{"glint-no-env-regions", SpecularModel::Glint, antiAliasing};
    prefiltered.withoutEnvironmentRegions = true;
    variants.push_back(prefiltered);
  }
  if (featureCost) {
    variants.push_back({"glint-no-shadows", SpecularModel::Glint, antiAliasing, false, false, true});
    variants.push_back({"glint-msaa1", SpecularModel::Glint, antiAliasing, false, false, false, true});
    variants.push_back({"glint-moving-lights", SpecularModel::Glint, antiAliasing, false, false, false, false, true});
    variants.push_back({"glint-one-cascade", SpecularModel::Glint, antiAliasing, false, false, false, false, false, true});
  }
  for (Variant& variant : variants) variant.footprint = footprints.front().second;
  for (std::size_t k = 1; k < footprints.size(); ++k) {
    Variant variant{policyColumn(footprints[k].first), SpecularModel::Glint, antiAliasing};
    variant.footprint = footprints[k].second;
    variants.push_back(variant);
  }
  return variants;
}

struct Timing {
  double median, min, max;
};

Timing summarise(std::vector<double> times) {
  std::sort(times.begin(), times.end());
  const std::size_t n = times.size();
  const double median = n % 2 ? times[n / 2] : 0.5 * (times[n / 2 - 1] + times[n / 2]);
  return {median, times.front(), times.back()};
}

void runBench(const BenchOptions& options) {
  const auto [width, height] = parseImageSize(options.size);
  if (options.frames < 1 || options.frames > 100000) throw Error("--frames must be in [1, 100000]");
  if (options.warmup < 0 || options.warmup > 1000) throw Error("--warmup must be in [0, 1000]");
  const std::vector<std::string> sceneNames = options.scenes.empty() ? scene::builtinSceneNames() : options.scenes;
  std::vector<scene::Scene> scenes;
  for (const std::string& name : sceneNames) {
    SceneOptions sceneOptions;
    sceneOptions.scene = name;
    sceneOptions.camera = options.camera;
    sceneOptions.cameraOptions = options.cameraOptions;
    sceneOptions.environment = options.environment;
    sceneOptions.lod = options.lod;
    sceneOptions.rectLights = options.rectLights;
    scenes.push_back(sceneOptions.loadScene());
  }
  SceneOptions dictionaryOptions;
  dictionaryOptions.dictionary = options.dictionary;
  const Dictionary dictionary = dictionaryOptions.loadDictionary();

  gl::HeadlessContext context;
  const gl::ContextInfo info = gl::currentContextInfo();
  gl::FrameTimer timer;
  const bool progress = isatty(STDERR_FILENO);
  const std::vector<std::pair<std::string, FootprintPolicy>> footprints = options.footprint.all();
  const std::vector<Variant> models =
      benchVariants(gl::antiAliasingFromString(options.antiAliasing), options.gltfTarget,
                    options.compareEnvironmentLights, options.compareExtendedLights, options.featureCost, footprints);
  nlohmann::json report = {{"size", {width, height}}, {"renderer", info.renderer}, {"timer", timer.method()},
                           {"frames", options.frames}, {"footprint", footprints.front().first},
                           {"anti_aliasing", options.antiAliasing}, {"shadow_cascades", options.raster.shadowCascades},
                           {"quality", options.quality.quality.empty() ? "none" : options.quality.quality},
                           {"scenes", nlohmann::json::array()}};
  for (std::size_t s = 0; s < scenes.size(); ++s) {
    const scene::Scene& scene = scenes[s];
    warnAboutUndrawnLights(scene);
    gl::Renderer renderer(scene, dictionary);
    printWarnings(renderer.warnings());
    std::unique_ptr<gl::Renderer> gltfRenderer;
    scene::Scene gltfScene;  // outlives its renderer
    if (options.gltfTarget) {
      gltfScene = scene;
      for (scene::Material& m : gltfScene.materials) m.specular = scene::kGltfSpecular;
      gltfRenderer = std::make_unique<gl::Renderer>(gltfScene, dictionary);
    }
    std::unique_ptr<gl::Renderer> unlitRenderer;
    scene::Scene unlitScene;  // outlives its renderer
    if (options.compareEnvironmentLights) {
      unlitScene = scene;
      unlitScene.environment.rasterLights = 0;
      unlitRenderer = std::make_unique<gl::Renderer>(unlitScene, dictionary);
    }
    std::unique_ptr<gl::Renderer> pointsRenderer, prefilteredRenderer;
    scene::Scene pointsScene, prefilteredScene;  // outlive their renderers
    if (options.compareExtendedLights) {
      pointsScene = scene;
      for (const scene::AreaLight& area : scene::findAreaLights(scene).lights) {
        scene::Light point;
        point.type = scene::Light::Type::Point;
        point.position = area.centre();
        point.intensity = area.radiance * area.area();
        pointsScene.lights.push_back(point);
        pointsScene.materials[static_cast<std::size_t>(pointsScene.meshes[static_cast<std::size_t>(area.mesh)].material)].emissive =
            glm::vec3(0.0f);
      }
      pointsRenderer = std::make_unique<gl::Renderer>(pointsScene, dictionary);
      prefilteredScene = scene;
      prefilteredScene.environment.rasterRegions = 0;
      prefilteredRenderer = std::make_unique<gl::Renderer>(prefilteredScene, dictionary);
    }
    // The renderer keeps its shadow maps while the lights and the camera stay, so a variant that
    // draws other maps (one cascade, a moving light) draws with a renderer of its own: on the
    // shared one it would make the next variant's frame draw the maps again as well.
    std::unique_ptr<gl::Renderer> oneCascadeRenderer;
    std::unique_ptr<gl::Renderer> movingLightsRenderer;
    if (options.featureCost) {
      oneCascadeRenderer = std::make_unique<gl::Renderer>(scene, dictionary);
      movingLightsRenderer = std::make_unique<gl::Renderer>(scene, dictionary);
    }
    gl::FrameSettings frame;
    frame.width = width;
    frame.height = height;
    frame.camera = scene.cameras.at(options.camera);
    options.raster.applyTo(frame, renderer);
    const gl::FrameSettings timed = frame;
    std::map<std::string, std::vector<double>> times;
    // Models alternate frame by frame, starting with a different one each round, so that machine
    // noise and warm caches fall on all of them alike.
    for (int round = -options.warmup; round < options.frames; ++round) {
      for (std::size_t k = 0; k < models.size(); ++k) {
        const Variant& variant = models[(k + static_cast<std::size_t>(round + options.warmup)) % models.size()];
        frame.brdf = variant.brdf;
        frame.antiAliasing = variant.antiAliasing;
        frame.shadows = timed.shadows && !variant.noShadows;
        frame.msaa = variant.oneSample ? 1 : timed.msaa;
        frame.shadowCascades = variant.oneCascade ? 1 : timed.shadowCascades;
        frame.footprintPolicy = variant.footprint;
        gl::Renderer& drawing = variant.gltfTarget                 ? *gltfRenderer
                                : variant.withoutEnvironmentLights ? *unlitRenderer
                                : variant.areaAsPoints             ? *pointsRenderer
                                : variant.withoutEnvironmentRegions ? *prefilteredRenderer
                                : variant.oneCascade               ? *oneCascadeRenderer
                                : variant.movingLights             ? *movingLightsRenderer
                                                                   : renderer;
        // A light that moved by a hair since the last frame: its shadow maps are drawn again.
        if (variant.movingLights && !drawing.lights().empty()) drawing.lights()[0].direction.x += round % 2 ? 1e-6f : -1e-6f;
        const double ms = timer.milliseconds([&] { drawing.renderFrame(frame); });
        if (round >= 0) times[variant.label].push_back(ms);
      }
      if (progress) std::fprintf(stderr, "\rglint: %s frame %d/%d   ", scene.name.c_str(), round + 1, options.frames);
    }
    if (glGetError() != GL_NO_ERROR) throw Error("OpenGL error while rendering scene '" + scene.name + "'");
    std::size_t triangles = 0;
    for (const scene::Mesh& mesh : scene.meshes) triangles += mesh.indices.size() / 3;
    nlohmann::json entry = {{"scene", sceneNames[s]}, {"triangles", triangles}};
    std::map<std::string, Timing> timings;
    for (const Variant& model : models) {
      timings[model.label] = summarise(times[model.label]);
      entry[model.label] = {{"median_ms", timings[model.label].median},
                            {"min_ms", timings[model.label].min},
                            {"max_ms", timings[model.label].max}};
    }
    for (const Variant& model : models) {
      if (model.label == "glint") continue;
      entry["ratio_glint_" + model.label] = timings["glint"].median / timings[model.label].median;
    }
    // Each other footprint policy's glint against Cook-Torrance, from the same frames.
    for (std::size_t k = 1; k < footprints.size(); ++k) {
      const std::string label = policyColumn(footprints[k].first);
      entry["ratio_" + label + "_cook-torrance"] = timings[label].median / timings["cook-torrance"].median;
    }
    report["scenes"].push_back(entry);
  }
  if (progress) std::fprintf(stderr, "\r%60s\r", "");

  // The cost's spread: the highest glint / Cook-Torrance ratio against the mean of them.
  double sum = 0.0;
  double highest = 0.0;
  for (const auto& entry : report["scenes"]) {
    const double ratio = entry["ratio_glint_cook-torrance"].get<double>();
    sum += ratio;
    highest = std::max(highest, ratio);
  }
  const double mean = sum / static_cast<double>(report["scenes"].size());
  report["glint_cook-torrance"] = {{"mean_ratio", mean}, {"max_ratio", highest}, {"max_over_mean", highest / mean}};
  for (std::size_t k = 1; k < footprints.size(); ++k) {
    const std::string label = policyColumn(footprints[k].first);
    double policySum = 0.0;
    double policyHighest = 0.0;
    for (const auto& entry : report["scenes"]) {
      const double ratio = entry["ratio_" + label + "_cook-torrance"].get<double>();
      policySum += ratio;
      policyHighest = std::max(policyHighest, ratio);
    }
    const double policyMean = policySum / static_cast<double>(report["scenes"].size());
    report[label + "_cook-torrance"] = {{"mean_ratio", policyMean}, {"max_ratio", policyHighest}};
  }

  if (options.json) {
    std::cout << report.dump() << std::endl;
    return;
  }
  std::printf("%dx%d on %s, %s timer, median of %d frame%s after %d warm-up (min..max), %santi-aliasing %s, shadows %s "
              "(%d cascade%s), msaa %d, footprint %s\n",
              width, height, info.renderer.c_str(), timer.method(), options.frames, options.frames == 1 ? "" : "s",
              options.warmup, options.quality.quality.empty() ? "" : ("quality " + options.quality.quality + ": ").c_str(),
              options.antiAliasing.c_str(), options.raster.shadows.c_str(), options.raster.shadowCascades,
              options.raster.shadowCascades == 1 ? "" : "s", options.raster.msaa, footprints.front().first.c_str());
  std::printf("%-16s %9s", "scene", "triangles");
  for (const Variant& model : models) std::printf("  %-26s", model.label.c_str());
  for (const Variant& model : models) {
    if (model.label != "glint") std::printf("  glint/%s", model.label.c_str());
  }
  for (std::size_t k = 1; k < footprints.size(); ++k) {
    std::printf("  glint[%s]/cook-torrance", footprints[k].first.c_str());
  }
  std::printf("\n");
  for (const auto& entry : report["scenes"]) {
    std::printf("%-16s %9zu", entry["scene"].get<std::string>().c_str(), entry["triangles"].get<std::size_t>());
    for (const Variant& model : models) {
      const auto& t = entry[model.label];
      char cell[64];
      std::snprintf(cell, sizeof cell, "%.2f ms (%.2f..%.2f)", t["median_ms"].get<double>(), t["min_ms"].get<double>(),
                    t["max_ms"].get<double>());
      std::printf("  %-26s", cell);
    }
    for (const Variant& model : models) {
      if (model.label == "glint") continue;
      std::printf("  %*.2fx", static_cast<int>(6 + model.label.size()) - 1,
                  entry["ratio_glint_" + model.label].get<double>());
    }
    for (std::size_t k = 1; k < footprints.size(); ++k) {
      const std::string label = policyColumn(footprints[k].first);
      std::printf("  %*.2fx", static_cast<int>(label.size() + 13) - 1,
                  entry["ratio_" + label + "_cook-torrance"].get<double>());
    }
    std::printf("\n");
  }
  std::printf("glint / cook-torrance: mean %.2fx, highest %.2fx, highest / mean %.2f\n", mean, highest, highest / mean);
  for (std::size_t k = 1; k < footprints.size(); ++k) {
    const std::string label = policyColumn(footprints[k].first);
    std::printf("%s / cook-torrance: mean %.2fx, highest %.2fx\n", label.c_str(),
                report[label + "_cook-torrance"]["mean_ratio"].get<double>(),
                report[label + "_cook-torrance"]["max_ratio"].get<double>());
  }
}

}  // namespace

void registerBenchCommand(CLI::App& app) {
  auto options = std::make_shared<BenchOptions>();
  CLI::App* command = app.add_subcommand("bench", "Frame times per scene and BRDF, with ratios measured in one run");
  command->add_option("scenes", options->scenes, "Scenes to time (default: every built-in scene)");
  command->add_option("--size", options->size, "Frame size WxH")->capture_default_str();
  command->add_option("--frames", options->frames, "Timed frames per scene and BRDF (the median is reported)")
      ->capture_default_str();
  command->add_option("--warmup", options->warmup, "Untimed frames per scene and BRDF first")->capture_default_str();
  command->add_option("--camera", options->camera, "Camera preset (every scene must have it)")->capture_default_str();
  options->cameraOptions.addTo(*command);
  command->add_option("--aa", options->antiAliasing,
                      "Glint anti-aliasing of the timed glint frames: ggaa+lean, ggaa or none; unless none, the 2020 "
                      "model is timed too (glint-none), for the filter's cost")
      ->capture_default_str();
  command->add_option("--dict", options->dictionary, "Dictionary file or the authors' EXR folder");
  command->add_option("--lod", options->lod, "The level-of-detail construction of every glint layer: paper, consistent or tree");
  command->add_flag("--gltf-target", options->gltfTarget,
                    "Also time glint with glTF's specular lobe on every material: GGX, Smith masking and the "
                    "multiple-scattering compensation (glint-gltf)");
  options->raster.addTo(*command);
  options->footprint.addTo(*command, true);
  command->add_flag("--feature-cost", options->featureCost,
                    "Also time glint without shadows (glint-no-shadows), at one sample a pixel (glint-msaa1) and "
                    "with its shadow maps drawn again every frame, as when a light moves (glint-moving-lights), and "
                    "with one shadow map a directional light (glint-one-cascade)");
  options->environment.addTo(*command);
  command->add_flag("--compare-env-lights", options->compareEnvironmentLights,
                    "Also time glint without the lights taken out of the environment map (glint-no-env-lights)");
  addRectLightOption(*command, options->rectLights);
  command->add_flag("--compare-extended-lights", options->compareExtendedLights,
                    "Also time glint with each area light replaced by a point light at its centre (glint-area-as-points) "
                    "and without the environment's regions, the whole map prefiltered (glint-no-env-regions)");
  command->add_flag("--json", options->json, "Print one JSON object instead of the table");
  options->quality.addTo(*command);
  command->callback([options, command] {
    options->quality.applyTo(*command, options->antiAliasing, options->footprint, options->raster);
    runBench(*options);
  });
}

}  // namespace glint::app
