// Options shared by the commands that draw a scene (render, view): which scene, which camera,
// which dictionary, and glint layers or parameter overrides applied to its materials.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>

#include "app/camera_options.h"
#include "glint/dictionary.h"
#include "scene/builtin_scenes.h"
#include "scene/scene.h"

namespace glint::app {

// The environment options (--env, --env-intensity, --env-rotation, --env-lights) of the commands
// that draw a scene (render, view, trace, bench).
struct EnvironmentOptions {
  std::string file;                  // a .hdr or .exr map replacing the scene's environment
  std::optional<float> intensity;    // scales the environment's radiance
  std::optional<float> rotationDegrees;  // turns it about +y
  std::optional<int> rasterLights;   // scene::Environment::rasterLights
  std::optional<int> rasterRegions;  // scene::Environment::rasterRegions
  bool keepDefaultLights = false;    // keep the invented lights of a file without lights under --env/--sky

  void addTo(CLI::App& command);
  // Validates the values (one line naming the option or the file and the problem) and applies them.
  void applyTo(scene::Scene& scene) const;
  // For a user's environment (--env, --sky): a scene whose lights were invented for it
  // (scene::Scene::defaultLights) loses them unless --keep-default-lights, so that the light is the
  // user's environment alone (a white furnace reads 1, not 1 plus the invented lights). True when
  // it dropped them, for the caller to say so once nothing else failed.
  bool dropDefaultLights(scene::Scene& scene) const;
};

// --rect-light X,Y,Z,W,H,L (repeatable): into `rectLights`, six numbers a light
// (scene::addRectangleLight, applied by SceneOptions::loadScene).
void addRectLightOption(CLI::App& command, std::vector<float>& rectLights);

struct SceneOptions {
  std::string scene = scene::kDefaultScene;
  std::string camera = "default";
  std::string dictionary;
  std::vector<std::string> glintMaterials;
  std::vector<float> alpha;
  std::optional<float> rho;
  std::optional<float> logDensity;
  std::optional<float> relativeArea;
  std::optional<std::int64_t> patternSeed;  // checked to be a uint32 when applied
  std::optional<float> sky;
  EnvironmentOptions environment;
  std::vector<float> rectLights;  // --rect-light: X,Y,Z,W,H,L per light (scene::addRectangleLight)
  CameraOptions cameraOptions;  // --look-from, --look-at, --up, --fov: applied to the chosen preset
  // The specular target of every material (scene::Material::specular).
  std::optional<std::string> ndf;
  std::optional<std::string> masking;
  std::optional<bool> multipleScattering;
  // The LOD construction of every glint layer (GlintLayer::lod): paper, consistent or tree.
  std::optional<std::string> lod;

  // All of the options below (render, view, trace).
  void addTo(CLI::App& command);
  // The scene argument and the options that change its materials (--glint-material, --alpha,
  // --log-density, --relative-area) or add to it (--rect-light), without those of a view (camera,
  // dictionary, sky): export.
  void addSceneAndMaterialsTo(CLI::App& command);
  // Loads the scene, applies --glint-material and the overrides (validated like the file's own
  // parameters), checks the camera and applies the camera options to it; throws Error with one line.
  scene::Scene loadScene() const;
  // loadScene for each of `names` in turn, with these options (commands that measure several scenes).
  std::vector<scene::Scene> loadScenes(const std::vector<std::string>& names) const;
  const scene::Camera& findCamera(const scene::Scene& scene) const;
  Dictionary loadDictionary() const;
  // The output of a command run without -o: the scene's name (scene::sceneName) with `extension`,
  // in the current folder, as pbrt and Mitsuba name theirs.
  std::string outputNamedAfterScene(const std::string& extension) const;
};

// The line --glint-material prints about the log density its new layers got
// (scene::visibleGlintDensity), `layered` as scene::applyGlint returns them: each layer's value
// and its material's uv units per metre, and how to set another, e.g. "log density of the new glint layers, about
// 100 microfacets per pixel at the default camera (512 pixels high): 'Material_MR' 16.9 (0.279 uv
// units per metre); --log-density D sets another".
// Throws Error("--lod 'paper' is given twice") for a value a repeatable option was given twice:
// it would be measured, and reported, twice.
void requireEachOnce(const std::vector<std::string>& values, const std::string& option);

std::string describeDefaultGlintDensity(const scene::Scene& scene, const std::vector<std::size_t>& layered);

// Says on stderr, in one line, when the scene has more lights than the rasteriser draws.
void warnAboutUndrawnLights(const scene::Scene& scene);

// Says on stderr, one line each, what a renderer draws otherwise than the scene says.
void printWarnings(const std::vector<std::string>& warnings);

// `--size WxH` of the commands that write images: each side in [1, 8192]; throws Error with one line.
std::pair<int, int> parseImageSize(const std::string& text);

}  // namespace glint::app
