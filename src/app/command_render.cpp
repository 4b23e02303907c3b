// `glint render`: one frame of the real-time renderer, headless, to PNG or EXR (docs/cli.md).
#include <chrono>
#include <cstdio>
#include <memory>
#include <unistd.h>

#include "app/commands.h"
#include "app/raster_options.h"
#include "app/scene_options.h"
#include "gl/context.h"
#include "gl/display.h"
#include "gl/renderer.h"
#include "glint/error.h"
#include "glint/file_io.h"
#include "glint/image.h"
#include "glint/image_io.h"

namespace glint::app {

namespace {

struct RenderOptions {
  SceneOptions scene;
  std::string output;
  std::string size = "512x512";
  std::string brdf = "glint";
  std::string antiAliasing = "ggaa+lean";
  float aaKernel = 1.0f;
  int spp = 1;
  int reference = 0;
  float exposure = 1.0f;
  OrbitOptions orbit;
  RasterOptions raster;
  FootprintOptions footprint;
  QualityOptions quality;
};

void runRender(const RenderOptions& options) {
  const auto [width, height] = parseImageSize(options.size);
  const SpecularModel brdf = specularModelFromName(options.brdf);
  const std::string output = options.output.empty() ? options.scene.outputNamedAfterScene(".png") : options.output;
  options.orbit.validate();
  const bool video = isVideoPath(output);
  if (video && !options.orbit.enabled()) throw Error(output + ": a video (.mp4) needs --orbit N");
  // A video's frames are PNG images beside it.
  const std::string extension = video ? ".png" : lowercaseExtension(output);
  if (extension != ".png" && extension != ".exr") {
    throw Error(output + ": the output must end in .png or .exr (or .mp4 with --orbit)");
  }
  if (options.spp < 1 || options.spp > 65536) throw Error("--spp must be in [1, 65536]");
  if (options.reference != 0 && (options.reference < 1 || options.reference > 65536)) {
    throw Error("--reference must be in [1, 65536]");
  }
  if (options.reference != 0 && options.spp != 1) throw Error("--reference and --spp cannot be combined");
  if (!(options.aaKernel >= 0.0f && options.aaKernel <= 16.0f)) throw Error("--aa-kernel must be in [0, 16]");
  // The anti-aliasing paper's reference protocol: the 2020 model, averaged over jittered frames.
  const gl::AntiAliasing antiAliasing =
      options.reference != 0 ? gl::AntiAliasing::None : gl::antiAliasingFromString(options.antiAliasing);
  const int spp = options.reference != 0 ? options.reference : options.spp;
  if (!(options.exposure > 0.0f && options.exposure < 1e6f)) throw Error("--exposure must be in (0, 1e6)");
  // Every file the run writes has a place, before the render that makes it (the video's too).
  if (video) requireWritablePlace(output);
  const std::vector<std::filesystem::path> paths = options.orbit.framePaths(output, extension);
  for (const std::filesystem::path& path : paths) requireWritablePlace(path);
  const scene::Scene scene = options.scene.loadScene();
  const Dictionary dictionary = options.scene.loadDictionary();
  const auto start = std::chrono::steady_clock::now();

  gl::HeadlessContext context;
  warnAboutUndrawnLights(scene);
  gl::Renderer renderer(scene, dictionary);
  printWarnings(renderer.warnings());
  gl::FrameSettings frame;
  frame.width = width;
  frame.height = height;
  frame.brdf = brdf;
  frame.antiAliasing = antiAliasing;
  frame.normalMapFinestLevel = options.reference != 0;
  frame.filterScale = options.aaKernel;
  options.raster.applyTo(frame, renderer);
  frame.footprintPolicy = options.footprint.policy();
  const std::vector<scene::Camera> cameras =
      options.orbit.cameras(options.scene.findCamera(scene), orbitPivot(scene, options.scene.cameraOptions));
  const int frames = static_cast<int>(cameras.size());
  const bool progress = (spp > 1 || frames > 1) && isatty(STDERR_FILENO);
  std::string first, last;
  StagedFiles written;  // an orbit's frames are one output: written all or none, renamed together
  for (int f = 0; f < frames; ++f) {
    frame.camera = cameras[static_cast<std::size_t>(f)];
    const ImageRgbF image = gl::renderSupersampled(renderer, frame, spp, [&](int k) {
      if (!progress) return;
      if (frames > 1) std::fprintf(stderr, "\rglint: frame %d/%d", f + 1, frames);
      if (spp > 1) std::fprintf(stderr, "%s sample %d/%d", frames > 1 ? "," : "\rglint:", k + 1, spp);
    });
    const std::string path = paths[static_cast<std::size_t>(f)].string();
    if (extension == ".exr") {
      written.add(path, encodeExr(path, image));
    } else {
      // The display pass of the viewer's window, so that `glint view` shows these very bytes.
      written.add(path, encodePng(gl::DisplayPass().encode(image, scene.exposure * options.exposure)));
    }
    (f == 0 ? first : last) = path;
  }
  written.commit();
  if (progress) std::fprintf(stderr, "\n");
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const std::string report = frames > 1 ? std::to_string(frames) + " frames " + first + " .. " + last : first;
  std::fprintf(stderr, "glint: wrote %s (%s, %dx%d, %d spp, %s%s, anti-aliasing %s, shadows %s, msaa %d, %.2f s on %s)\n",
               report.c_str(), options.scene.scene.c_str(), width, height, spp, toString(brdf),
               footprintNote(frame.footprintPolicy).c_str(), gl::toString(antiAliasing), frame.shadows ? "on" : "off",
               frame.msaa, seconds, gl::currentContextInfo().renderer.c_str());
  if (video && encodeVideo(output, frames)) std::fprintf(stderr, "glint: wrote %s\n", output.c_str());
}

}  // namespace

void registerRenderCommand(CLI::App& app) {
  auto options = std::make_shared<RenderOptions>();
  CLI::App* command = app.add_subcommand("render", "Render one frame headless (OpenGL 4.5 through EGL) to PNG or EXR");
  options->scene.addTo(*command);
  command->add_option("-o,--output", options->output,
                      "Output image: .png (tone-mapped sRGB) or .exr (linear radiance), or with --orbit .mp4 (a "
                      "video of the PNG frames, with ffmpeg); without it SCENE.png in the current folder (the "
                      "built-in name or the glTF file's name)");
  command->add_option("--size", options->size, "Image size WxH")->capture_default_str();
  command->add_option("--brdf", options->brdf, "Specular model of glint materials: glint, cook-torrance, zirr-kaplanyan or zirr-kaplanyan-reference (the same "
                      "images on the reference shader's slower schedule)")
      ->capture_default_str();
  command->add_option("--aa", options->antiAliasing,
                      "Glint anti-aliasing: ggaa+lean (the glints filtered by the half vector's variation over the "
                      "pixel and the normal map's slope variance), ggaa (the former only) or none (the 2020 model)")
      ->capture_default_str();
  command->add_option("--aa-kernel", options->aaKernel,
                      "Size of the anti-aliasing kernel: 1 matches the pixel's box, 0 filters nothing")
      ->capture_default_str();
  command->add_option("--spp", options->spp, "Jittered samples per pixel, averaged: a supersampled reference")
      ->capture_default_str();
  command->add_option("--reference", options->reference,
                      "The anti-aliasing reference: the mean of N jittered frames of the 2020 model (--aa none), "
                      "normal maps at their finest level");
  command->add_option("--exposure", options->exposure, "Exposure multiplier for PNG output")->capture_default_str();
  options->orbit.addTo(*command);
  options->raster.addTo(*command);
  options->footprint.addTo(*command, false);
  options->quality.addTo(*command);
  command->callback([options, command] {
    options->quality.applyTo(*command, options->antiAliasing, options->footprint, options->raster);
    runRender(*options);
  });
}

}  // namespace glint::app
