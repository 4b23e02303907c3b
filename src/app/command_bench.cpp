// `glint bench`: frame times per scene and BRDF, with the ratios glint / Cook-Torrance (and glint /
// every other model) measured in the same run (docs/benchmarks.md).
#include <algorithm>
#include <cstdio>
#include <iostream>
#include <map>
#include <memory>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "app/commands.h"
#include "app/scene_options.h"
#include "gl/context.h"
#include "gl/frame_timer.h"
#include "gl/renderer.h"
#include "glint/error.h"
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
  std::string camera = "default";
};

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
    scenes.push_back(sceneOptions.loadScene());
  }
  SceneOptions dictionaryOptions;
  dictionaryOptions.dictionary = options.dictionary;
  const Dictionary dictionary = dictionaryOptions.loadDictionary();

  gl::HeadlessContext context;
  const gl::ContextInfo info = gl::currentContextInfo();
  gl::FrameTimer timer;
  const bool progress = isatty(STDERR_FILENO);
  const std::vector<gl::BrdfModel> models = gl::allBrdfModels();
  nlohmann::json report = {{"size", {width, height}}, {"renderer", info.renderer}, {"timer", timer.method()},
                           {"frames", options.frames}, {"scenes", nlohmann::json::array()}};
  for (std::size_t s = 0; s < scenes.size(); ++s) {
    const scene::Scene& scene = scenes[s];
    warnAboutUndrawnLights(scene);
    gl::Renderer renderer(scene, dictionary);
    gl::FrameSettings frame;
    frame.width = width;
    frame.height = height;
    frame.camera = scene.cameras.at(options.camera);
    std::map<gl::BrdfModel, std::vector<double>> times;
    // Models alternate frame by frame, starting with a different one each round, so that machine
    // noise and warm caches fall on all of them alike.
    for (int round = -options.warmup; round < options.frames; ++round) {
      for (std::size_t k = 0; k < models.size(); ++k) {
        frame.brdf = models[(k + static_cast<std::size_t>(round + options.warmup)) % models.size()];
        const double ms = timer.milliseconds([&] { renderer.renderFrame(frame); });
        if (round >= 0) times[frame.brdf].push_back(ms);
      }
      if (progress) std::fprintf(stderr, "\rglint: %s frame %d/%d   ", scene.name.c_str(), round + 1, options.frames);
    }
    if (glGetError() != GL_NO_ERROR) throw Error("OpenGL error while rendering scene '" + scene.name + "'");
    nlohmann::json entry = {{"scene", sceneNames[s]}};
    std::map<gl::BrdfModel, Timing> timings;
    for (gl::BrdfModel model : models) {
      timings[model] = summarise(times[model]);
      entry[gl::toString(model)] = {{"median_ms", timings[model].median},
                                    {"min_ms", timings[model].min},
                                    {"max_ms", timings[model].max}};
    }
    for (gl::BrdfModel model : models) {
      if (model == gl::BrdfModel::Glint) continue;
      entry[std::string("ratio_glint_") + gl::toString(model)] =
          timings[gl::BrdfModel::Glint].median / timings[model].median;
    }
    report["scenes"].push_back(entry);
  }
  if (progress) std::fprintf(stderr, "\r%60s\r", "");

  // Cost bound of issue 5: the highest glint / Cook-Torrance ratio against the mean of them.
  double sum = 0.0;
  double highest = 0.0;
  for (const auto& entry : report["scenes"]) {
    const double ratio = entry["ratio_glint_cook-torrance"].get<double>();
    sum += ratio;
    highest = std::max(highest, ratio);
  }
  const double mean = sum / static_cast<double>(report["scenes"].size());
  report["glint_cook-torrance"] = {{"mean_ratio", mean}, {"max_ratio", highest}, {"max_over_mean", highest / mean}};

  if (options.json) {
    std::cout << report.dump() << std::endl;
    return;
  }
  std::printf("%dx%d on %s, %s timer, median of %d frame%s after %d warm-up (min..max)\n", width, height,
              info.renderer.c_str(), timer.method(), options.frames, options.frames == 1 ? "" : "s", options.warmup);
  std::printf("%-16s", "scene");
  for (gl::BrdfModel model : models) std::printf("  %-26s", gl::toString(model));
  for (gl::BrdfModel model : models) {
    if (model != gl::BrdfModel::Glint) std::printf("  glint/%s", gl::toString(model));
  }
  std::printf("\n");
  for (const auto& entry : report["scenes"]) {
    std::printf("%-16s", entry["scene"].get<std::string>().c_str());
    for (gl::BrdfModel model : models) {
      const auto& t = entry[gl::toString(model)];
      char cell[64];
      std::snprintf(cell, sizeof cell, "%.2f ms (%.2f..%.2f)", t["median_ms"].get<double>(), t["min_ms"].get<double>(),
                    t["max_ms"].get<double>());
      std::printf("  %-26s", cell);
    }
    for (gl::BrdfModel model : models) {
      if (model == gl::BrdfModel::Glint) continue;
      std::printf("  %*.2fx", static_cast<int>(6 + std::string(gl::toString(model)).size()) - 1,
                  entry[std::string("ratio_glint_") + gl::toString(model)].get<double>());
    }
    std::printf("\n");
  }
  std::printf("glint / cook-torrance: mean %.2fx, highest %.2fx, highest / mean %.2f\n", mean, highest, highest / mean);
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
  command->add_option("--dict", options->dictionary, "Dictionary file or the authors' EXR folder");
  command->add_flag("--json", options->json, "Print one JSON object instead of the table");
  command->callback([options] { runBench(*options); });
}

}  // namespace glint::app
