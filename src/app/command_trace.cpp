// `glint trace`: the CPU path tracer (docs/trace.md) to a linear EXR and a tone-mapped PNG beside it.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>
#include <unistd.h>

#include <tbb/global_control.h>

#include "app/commands.h"
#include "app/raster_options.h"
#include "app/scene_options.h"
#include "gl/renderer.h"
#include "glint/error.h"
#include "glint/file_io.h"
#include "glint/image_io.h"
#include "trace/path_tracer.h"

namespace glint::app {

namespace {

struct TraceOptions {
  SceneOptions scene;
  std::string output;
  std::string size = "256x256";
  std::string brdf = "glint";
  std::string sampler = "mixture";
  int spp = 16;
  int maxDepth = 4;
  bool directOnly = false;
  bool pixelCentres = false;
  bool unfilteredNormalMaps = false;
  float exposure = 1.0f;
  int threads = 0;
  OrbitOptions orbit;
  FootprintOptions footprint;
};

// A bar with the percentage done and the time left, redrawn at most ten times a second by
// whichever worker finishes a tile; only on a terminal (a log gets the summary line alone).
class ProgressBar {
 public:
  explicit ProgressBar(bool enabled) : enabled_(enabled), start_(Clock::now()) {}

  void update(double fraction) {
    if (!enabled_) return;
    const std::unique_lock lock(mutex_, std::try_to_lock);
    if (!lock.owns_lock()) return;  // another worker is drawing it; skipping one update is fine
    const auto now = Clock::now();
    if (fraction < 1.0 && now - lastDrawn_ < std::chrono::milliseconds(100)) return;
    lastDrawn_ = now;
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    constexpr int kWidth = 30;
    const int filled = std::clamp(static_cast<int>(fraction * kWidth), 0, kWidth);
    char bar[kWidth + 1];
    for (int i = 0; i < kWidth; ++i) bar[i] = i < filled ? '#' : '-';
    bar[kWidth] = '\0';
    if (fraction > 0.0) {
      const int left = static_cast<int>(std::lround(elapsed * (1.0 - fraction) / fraction));
      std::fprintf(stderr, "\rglint: trace [%s] %3d%%  %d:%02d left   ", bar, static_cast<int>(fraction * 100.0),
                   left / 60, left % 60);
    }
  }

  void finish() {
    if (enabled_) std::fprintf(stderr, "\n");
  }

 private:
  using Clock = std::chrono::steady_clock;
  bool enabled_;
  Clock::time_point start_;
  Clock::time_point lastDrawn_{};
  std::mutex mutex_;
};

void runTrace(const TraceOptions& options) {
  // Every option is checked before anything is loaded or written.
  trace::TraceSettings settings;
  std::tie(settings.width, settings.height) = parseImageSize(options.size);
  settings.spp = options.spp;
  settings.maxDepth = options.maxDepth;
  settings.brdf = specularModelFromName(options.brdf);
  settings.sampler = trace::glintSamplerFromString(options.sampler);
  settings.directOnly = options.directOnly;
  settings.pixelCentres = options.pixelCentres;
  settings.normalMapFiltering = !options.unfilteredNormalMaps;
  settings.footprintPolicy = options.footprint.policy();
  trace::validateTraceSettings(settings);
  const std::filesystem::path output =
      options.output.empty() ? options.scene.outputNamedAfterScene(".exr") : options.output;
  options.orbit.validate();
  const bool video = isVideoPath(output);
  if (video && !options.orbit.enabled()) throw Error(output.string() + ": a video (.mp4) needs --orbit N");
  if (!video && lowercaseExtension(output) != ".exr") {
    throw Error(output.string() + ": the output must end in .exr (a .png preview is written beside it), or .mp4 with --orbit");
  }
  if (!(options.exposure > 0.0f && options.exposure < 1e6f)) throw Error("--exposure must be in (0, 1e6)");
  if (options.threads < 0 || options.threads > 1024) throw Error("--threads must be in [0, 1024]");
  // Every file the run writes has a place, before the render that makes it (the video's too).
  if (video) requireWritablePlace(output);
  const std::vector<std::filesystem::path> exrPaths = options.orbit.framePaths(output, ".exr");
  for (const std::filesystem::path& exrPath : exrPaths) {
    requireWritablePlace(exrPath);
    requireWritablePlace(std::filesystem::path(exrPath).replace_extension(".png"));
  }
  std::optional<tbb::global_control> threadLimit;
  if (options.threads > 0) {
    threadLimit.emplace(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(options.threads));
  }

  const scene::Scene scene = options.scene.loadScene();
  const std::vector<scene::Camera> cameras =
      options.orbit.cameras(options.scene.findCamera(scene), orbitPivot(scene, options.scene.cameraOptions));
  const int frames = static_cast<int>(cameras.size());
  const Dictionary dictionary = options.scene.loadDictionary();
  const auto start = std::chrono::steady_clock::now();
  std::string first, last;
  std::uint64_t nonFiniteSamples = 0;
  StagedFiles written;  // an orbit's frames are one output: written all or none, renamed together
  for (int f = 0; f < frames; ++f) {
    settings.camera = cameras[static_cast<std::size_t>(f)];
    // What the tracer refuses of the scene (coordinates beyond its rays' range) names the scene.
    const trace::PathTracer tracer = [&] {
      try {
        return trace::PathTracer(scene, dictionary, settings);
      } catch (const Error& e) {
        throw Error(options.scene.scene + ": " + e.what());
      }
    }();
    if (frames > 1 && isatty(STDERR_FILENO)) std::fprintf(stderr, "glint: frame %d/%d\n", f + 1, frames);
    ProgressBar progress(isatty(STDERR_FILENO) != 0);
    const ImageRgbF image = tracer.render([&](double fraction) { progress.update(fraction); });
    progress.finish();
    nonFiniteSamples += tracer.nonFiniteSamples();

    const std::filesystem::path& exrPath = exrPaths[static_cast<std::size_t>(f)];
    const std::filesystem::path pngPath = std::filesystem::path(exrPath).replace_extension(".png");
    // The EXR and its preview are one output: both replace what was there, or neither does.
    const ImageRgb8 preview = displayEncode(image, scene.exposure * options.exposure);
    written.add(exrPath, encodeExr(exrPath, image));
    written.add(pngPath, encodePng(preview));
    (f == 0 ? first : last) = exrPath.string() + " and " + pngPath.string();
  }
  written.commit();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const double samples = static_cast<double>(settings.width) * settings.height * settings.spp * frames;
  const std::string brdf = settings.brdf == SpecularModel::Glint
                               ? options.brdf + footprintNote(settings.footprintPolicy) + ", " +
                                     trace::glintSamplerName(settings.sampler) + " sampler"
                               : options.brdf;
  const std::string paths =
      settings.directOnly ? std::string("direct light only") : "max depth " + std::to_string(settings.maxDepth);
  const std::string report = frames > 1 ? std::to_string(frames) + " frames " + first + " .. " + last : first;
  std::fprintf(stderr, "glint: wrote %s (%s, %dx%d, %d spp, %s, %s, %.2f s, %.0f samples/s on %zu threads)\n",
               report.c_str(), options.scene.scene.c_str(), settings.width, settings.height, settings.spp,
               brdf.c_str(), paths.c_str(), seconds, samples / seconds,
               tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
  if (nonFiniteSamples > 0) {
    std::fprintf(stderr, "glint: warning: %llu samples were not finite and count as black\n",
                 static_cast<unsigned long long>(nonFiniteSamples));
  }
  if (video && encodeVideo(output, frames)) std::fprintf(stderr, "glint: wrote %s\n", output.string().c_str());
}

}  // namespace

void registerTraceCommand(CLI::App& app) {
  auto options = std::make_shared<TraceOptions>();
  CLI::App* command = app.add_subcommand(
      "trace", "Path-trace a scene on the CPU (Embree, oneTBB) to a linear EXR and a PNG preview beside it");
  options->scene.addTo(*command);
  command->add_option("-o,--output", options->output,
                      "Output EXR (linear radiance); OUT.png is written beside it; without it SCENE.exr and "
                      "SCENE.png in the current folder (the built-in name or the glTF file's name); with --orbit, "
                      ".mp4 makes a video of the PNG previews (with ffmpeg)");
  command->add_option("--size", options->size, "Image size WxH")->capture_default_str();
  command->add_option("--spp", options->spp, "Samples per pixel")->capture_default_str();
  command->add_option("--max-depth", options->maxDepth, "Bounces: 1 is direct light (lights and environment) at the first hit")->capture_default_str();
  command->add_option("--brdf", options->brdf, "Specular model of glint materials: glint, cook-torrance, zirr-kaplanyan or zirr-kaplanyan-reference (the same images)")
      ->capture_default_str();
  command->add_option("--sampler", options->sampler, "Importance sampling of the glint BRDF: mixture or gaussian")
      ->capture_default_str();
  command->add_flag("--direct-only", options->directOnly,
                    "Only point and directional lights at the first hit: no environment, no bounces");
  command->add_flag("--pixel-centres", options->pixelCentres,
                    "Every sample through its pixel's centre (no jitter): the rasteriser's footprint");
  command->add_flag("--unfiltered-normal-maps", options->unfilteredNormalMaps,
                    "Glint layers read the filtered normal texture only, not the normal map's slope variance (as "
                    "glint render --aa ggaa or none)");
  options->footprint.addTo(*command, false);
  command->add_option("--exposure", options->exposure, "Exposure multiplier for the PNG preview")
      ->capture_default_str();
  command->add_option("--threads", options->threads, "Worker threads (0: all cores); the image does not depend on it")
      ->capture_default_str();
  options->orbit.addTo(*command);
  command->callback([options] { runTrace(*options); });
}

}  // namespace glint::app
