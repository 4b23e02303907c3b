// `glint hdri`: writes an equirectangular environment map, the procedural sky with a sun
// (scene::sunSkyEnvironment), as a Radiance .hdr or an EXR, for --env (docs/cli.md).
#include <cmath>
#include <cstdio>
#include <memory>
#include <tuple>

#include "app/commands.h"
#include "app/scene_options.h"
#include "glint/error.h"
#include "glint/radiance_hdr.h"
#include "scene/environment_map.h"

namespace glint::app {

namespace {

struct HdriOptions {
  std::string output;
  std::string size = "512x256";
  std::string preset = "sun";
  scene::SunSky sky;
};

void requireWithin(const char* option, float value, float low, float high) {
  if (!(value >= low && value <= high)) {
    char text[160];
    std::snprintf(text, sizeof text, "%s must be in [%g, %g], got %g", option, static_cast<double>(low),
                  static_cast<double>(high), static_cast<double>(value));
    throw Error(text);
  }
}

void runHdri(const HdriOptions& options) {
  scene::SunSky sky = options.sky;
  std::tie(sky.width, sky.height) = parseImageSize(options.size);
  requireWithin("--sun-elevation", sky.sunElevationDegrees, -90.0f, 90.0f);
  requireWithin("--sun-azimuth", sky.sunAzimuthDegrees, -360.0f, 360.0f);
  requireWithin("--sun-diameter", sky.sunDiameterDegrees, 0.1f, 30.0f);
  requireWithin("--sun-irradiance", sky.sunIrradiance, 0.0f, 1e6f);
  const std::string extension = lowercaseExtension(options.output);
  if (extension != ".hdr" && extension != ".exr") {
    throw Error(options.output + ": the output must end in .hdr or .exr");
  }
  if (options.preset != "sun" && options.preset != "studio" && options.preset != "overcast") {
    throw Error("--preset must be sun, studio or overcast, got '" + options.preset + "'");
  }
  const scene::Environment environment = options.preset == "studio"     ? scene::studioEnvironment(sky.width, sky.height)
                                         : options.preset == "overcast" ? scene::overcastEnvironment(sky.width, sky.height)
                                                                        : scene::sunSkyEnvironment(sky);
  const ImageRgbF image{environment.width, environment.height, environment.pixels};
  if (extension == ".hdr") {
    writeRadianceHdr(options.output, image);
  } else {
    writeExr(options.output, image);
  }
  if (options.preset == "sun") {
    std::fprintf(stderr, "glint: wrote %s (%dx%d, sun at elevation %g, azimuth %g degrees)\n", options.output.c_str(),
                 sky.width, sky.height, static_cast<double>(sky.sunElevationDegrees),
                 static_cast<double>(sky.sunAzimuthDegrees));
  } else {
    std::fprintf(stderr, "glint: wrote %s (%dx%d, %s)\n", options.output.c_str(), sky.width, sky.height, options.preset.c_str());
  }
}

}  // namespace

void registerHdriCommand(CLI::App& app) {
  auto options = std::make_shared<HdriOptions>();
  CLI::App* command =
      app.add_subcommand("hdri", "Write the procedural sky with a sun as an equirectangular .hdr or .exr map");
  command->add_option("-o,--output", options->output, "Output file: .hdr (Radiance RGBE) or .exr")->required();
  command->add_option("--preset", options->preset,
                      "sun (a sky with a sun, the --sun-* options), studio (four softboxes 12 to 60 degrees wide "
                      "over a dim backdrop) or overcast (the CIE overcast sky)")
      ->capture_default_str();
  command->add_option("--size", options->size, "Map size WxH (width twice the height)")->capture_default_str();
  command->add_option("--sun-elevation", options->sky.sunElevationDegrees, "Sun elevation above the horizon, degrees")
      ->capture_default_str();
  command->add_option("--sun-azimuth", options->sky.sunAzimuthDegrees,
                      "Sun azimuth, degrees to the left of -z (the built-in views' forward)")
      ->capture_default_str();
  command->add_option("--sun-diameter", options->sky.sunDiameterDegrees, "Sun disc diameter, degrees")
      ->capture_default_str();
  command->add_option("--sun-irradiance", options->sky.sunIrradiance, "Sun irradiance on a plane facing it")
      ->capture_default_str();
  command->callback([options] { runHdri(*options); });
}

}  // namespace glint::app
