// `glint env-regions`: an environment map split as glint's rasteriser splits it (docs/renderer.md,
// "HDRI environments"; docs/method.md section 8), for another renderer to light glints with it: the
// brightest small regions as directional lights, the brightest larger ones as regions whose glints
// the kernel draws (glint_extended_lights.h), and the rest, the residual map, to prefilter. The
// three.js package reads it (web/three, `loadGlintEnvironment`).
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/commands.h"
#include "gl/renderer.h"
#include "glint/error.h"
#include "glint/file_io.h"
#include "glint/image_io.h"
#include "scene/environment_map.h"

namespace glint::app {

namespace {

struct EnvRegionsOptions {
  std::string map;
  std::string output;
  int lights = 4;
  int regions = 8;
};

// A direction of the map as its (u, v): u from the left edge, v from the top edge, each in [0, 1].
nlohmann::json mapUv(glm::vec3 direction) {
  const glm::vec2 uv = scene::equirectFromDirection(direction);
  return {uv.x, uv.y};
}

nlohmann::json rgb(glm::vec3 v) { return {v.x, v.y, v.z}; }

void runEnvRegions(const EnvRegionsOptions& options) {
  if (!(options.lights >= 0 && options.lights <= gl::kMaxLights)) {
    throw Error("--lights must be in [0, " + std::to_string(gl::kMaxLights) + "], got " + std::to_string(options.lights));
  }
  if (!(options.regions >= 0 && options.regions <= gl::kMaxEnvironmentRegions)) {
    throw Error("--regions must be in [0, " + std::to_string(gl::kMaxEnvironmentRegions) + "], got " +
                std::to_string(options.regions));
  }
  if (lowercaseExtension(options.output) != ".json") throw Error(options.output + ": the output must end in .json");
  std::filesystem::path residualPath = options.output;
  residualPath.replace_extension(".exr");
  std::error_code error;
  if (std::filesystem::weakly_canonical(residualPath, error) == std::filesystem::weakly_canonical(options.map, error)) {
    throw Error(options.map + ": the residual map would overwrite it; give another -o");
  }
  const scene::Environment map = scene::loadEnvironmentMap(options.map);
  const scene::EnvironmentLights lights = scene::extractEnvironmentLights(map, options.lights);
  const scene::EnvironmentRegions regions = scene::environmentGlintRegions(lights.residual, options.regions);

  nlohmann::json out;
  out["map"] = std::filesystem::path(options.map).filename().string();
  out["size"] = {map.width, map.height};
  out["residual"] = residualPath.filename().string();
  out["coordinates"] =
      "u from the map's left edge, v from its top edge, in [0, 1]; glint's direction of (u, v) is "
      "(sin(pi v) sin(2 pi (u - 1/2)), cos(pi v), -sin(pi v) cos(2 pi (u - 1/2)))";
  out["lights"] = nlohmann::json::array();
  for (std::size_t i = 0; i < lights.lights.size(); ++i) {
    // The direction towards the light; its irradiance on a plane facing it (W/m^2).
    out["lights"].push_back({{"uv", mapUv(-lights.lights[i].direction)},
                             {"irradiance", rgb(lights.lights[i].intensity)},
                             {"solidAngle", lights.solidAngles[i]}});
  }
  out["regions"] = nlohmann::json::array();
  for (const scene::EnvironmentRegion& region : regions.regions) {
    nlohmann::json corners = nlohmann::json::array();
    for (const glm::vec3& corner : region.corners) corners.push_back(mapUv(corner));
    out["regions"].push_back({{"corners", corners}, {"radiance", rgb(region.radiance)}, {"solidAngle", region.solidAngle}});
  }
  // The residual as 32-bit float EXR: within a region it is the map less the region's mean, which
  // is negative where the region is darker than its mean (RGBE cannot hold it).
  const ImageRgbF residual{regions.residual.width, regions.residual.height, regions.residual.pixels};
  writeFilesAtomically({{options.output, textBytes(out.dump(2) + "\n")}, {residualPath, encodeExr(residualPath, residual)}});
  std::fprintf(stderr, "glint: wrote %s (%zu lights, %zu regions) and %s (the residual map)\n", options.output.c_str(),
               lights.lights.size(), regions.regions.size(), residualPath.string().c_str());
}

}  // namespace

void registerEnvRegionsCommand(CLI::App& app) {
  auto options = std::make_shared<EnvRegionsOptions>();
  CLI::App* command = app.add_subcommand(
      "env-regions", "Split an environment map into lights, glint regions and a residual map, as the rasteriser does, for another renderer");
  command->add_option("map", options->map, "Equirectangular .hdr or .exr map")->required();
  command->add_option("-o,--output", options->output,
                      "Output .json (lights and regions in the map's coordinates); the residual map is written "
                      "beside it as .exr")
      ->required();
  command->add_option("--lights", options->lights,
                      "The map's brightest small regions taken out as directional lights (0-8), as --env-lights")
      ->capture_default_str();
  command->add_option("--regions", options->regions,
                      "The map's brightest larger regions whose glints are drawn (0-16), as --env-regions")
      ->capture_default_str();
  command->callback([options] { runEnvRegions(*options); });
}

}  // namespace glint::app
