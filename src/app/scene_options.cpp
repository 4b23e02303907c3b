#include "app/scene_options.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <regex>

#include "gl/renderer.h"
#include "glint/dictionary_exr.h"
#include "glint/error.h"
#include "scene/area_lights.h"
#include "scene/builtin_scenes.h"
#include "scene/environment_map.h"
#include "scene/gltf_loader.h"

namespace glint::app {

void SceneOptions::addTo(CLI::App& command) {
  addSceneAndMaterialsTo(command);
  command.add_option("--camera", camera, "Camera preset of the scene (see docs/scenes.md)")->capture_default_str();
  cameraOptions.addTo(command);
  command.add_option("--dict", dictionary,
                     "Dictionary file or the authors' EXR folder (default: generate the paper's, about 0.7 s)");
  command.add_option("--sky", sky, "Replace the scene's environment by the procedural sky at this intensity");
  environment.addTo(command);
}

void addRectLightOption(CLI::App& command, std::vector<float>& rectLights) {
  command
      .add_option("--rect-light", rectLights,
                  "Add an emissive rectangle that lights the scene in both renderers: X,Y,Z,W,H,L, a W x H m "
                  "rectangle centred at X,Y,Z facing the scene's centre, one-sided, of radiance L (white, W/(m^2 sr)); "
                  "repeatable")
      ->delimiter(',');
}

void EnvironmentOptions::addTo(CLI::App& command) {
  command.add_option("--env", file, "Replace the scene's environment by this equirectangular .hdr or .exr map");
  command.add_option("--env-intensity", intensity, "Scale the environment's radiance by K (>= 0)");
  command.add_option("--env-rotation", rotationDegrees, "Turn the environment about +y by DEG (counter-clockwise from above)");
  command.add_option("--env-lights", rasterLights,
                     "The rasteriser draws the map's N brightest small regions as directional lights (0-8, default 4)");
  command.add_option("--env-regions", rasterRegions,
                     "The rasteriser draws the rest of the map's N brightest regions analytically, with their "
                     "glints (0-" + std::to_string(gl::kMaxEnvironmentRegions) + ", default 0: none)");
  command.add_flag("--keep-default-lights", keepDefaultLights,
                   "With --env or --sky, keep the point and directional light invented for a glTF file without lights");
}

bool EnvironmentOptions::dropDefaultLights(scene::Scene& scene) const {
  if (!scene.defaultLights || keepDefaultLights) return false;
  scene.lights.clear();
  scene.defaultLights = false;
  return true;
}

void EnvironmentOptions::applyTo(scene::Scene& scene) const {
  const auto text = [](float value) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%g", static_cast<double>(value));
    return std::string(buffer);
  };
  if (intensity && !(std::isfinite(*intensity) && *intensity >= 0.0f)) {
    throw Error("--env-intensity must be a finite number >= 0, got " + text(*intensity));
  }
  if (rotationDegrees && !std::isfinite(*rotationDegrees)) {
    throw Error("--env-rotation must be a finite angle in degrees, got " + text(*rotationDegrees));
  }
  if (rasterLights && !(*rasterLights >= 0 && *rasterLights <= gl::kMaxLights)) {
    throw Error("--env-lights must be in [0, " + std::to_string(gl::kMaxLights) + "], got " + std::to_string(*rasterLights));
  }
  if (rasterRegions && !(*rasterRegions >= 0 && *rasterRegions <= gl::kMaxEnvironmentRegions)) {
    throw Error("--env-regions must be in [0, " + std::to_string(gl::kMaxEnvironmentRegions) + "], got " +
                std::to_string(*rasterRegions));
  }
  if (!file.empty()) {
    const int lights = scene.environment.rasterLights;
    const int regions = scene.environment.rasterRegions;
    scene.environment = scene::loadEnvironmentMap(file);
    scene.environment.rasterLights = lights;
    scene.environment.rasterRegions = regions;
  }
  if (intensity) scene.environment.intensity *= *intensity;
  if (rotationDegrees) scene.environment.rotation += glm::radians(*rotationDegrees);
  if (rasterLights) scene.environment.rasterLights = *rasterLights;
  if (rasterRegions) scene.environment.rasterRegions = *rasterRegions;
}

void SceneOptions::addSceneAndMaterialsTo(CLI::App& command) {
  std::string builtins;
  for (const std::string& name : scene::builtinSceneNames()) builtins += (builtins.empty() ? "" : ", ") + name;
  command.add_option("scene", scene, "A built-in scene (" + builtins + ") or a glTF 2.0 file")->capture_default_str();
  command.add_option("--glint-material", glintMaterials,
                     "Put a glint layer on this material of a glTF scene ('*' for all); repeatable");
  command.add_option("--alpha", alpha, "Override the roughness of every glint layer: A or AX,AY, each in [0.005, 2] (shaded as at least 0.01)")->delimiter(',');
  command.add_option("--rho", rho, "Override the slope correlation of every glint layer, in [-0.99, 0.99]");
  command.add_option("--log-density", logDensity, "Override the log microfacet density of every glint layer");
  command.add_option("--relative-area", relativeArea, "Override the microfacet relative area of every glint layer");
  command.add_option("--pattern-seed", patternSeed,
                     "Override the pattern seed of every glint layer, 0..4294967295: another realisation of the same "
                     "statistics");
  command.add_option("--ndf", ndf, "The smooth target of every material's specular lobe: beckmann or ggx");
  command.add_option("--masking", masking, "The masking of every material's specular lobe: v-cavity or smith");
  // CLI11 would take 2, -3, yes and on as booleans: the words the docs give, and only them.
  command.add_option("--multiple-scattering", multipleScattering,
                     "Compensate the energy lost to multiple scattering on every material: true or false")
      ->check(CLI::IsMember({"true", "false"}));
  command.add_option("--lod", lod,
                     "The level-of-detail construction of every glint layer: paper (each cell its own glints), "
                     "consistent (a cell's glints shared out among its children) or tree (every cell below a level set "
                     "by the density the mean of its four children)");
  addRectLightOption(command, rectLights);
}

void requireEachOnce(const std::vector<std::string>& values, const std::string& option) {
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (std::find(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(i), values[i]) != values.begin() + static_cast<std::ptrdiff_t>(i)) {
      throw Error(option + " '" + values[i] + "' is given twice");
    }
  }
}

std::string describeDefaultGlintDensity(const scene::Scene& scene, const std::vector<std::size_t>& layered) {
  std::string text = "log density of the new glint layers, about " +
                     std::to_string(static_cast<int>(scene::kVisibleGlintMicrofacetsPerPixel)) +
                     " microfacets per pixel at the default camera (" + std::to_string(scene::kVisibleGlintFrameSize) +
                     " pixels high):";
  char number[64];
  for (std::size_t k = 0; k < layered.size(); ++k) {
    const scene::Material& m = scene.materials[layered[k]];
    const scene::VisibleGlintDensity d = scene::visibleGlintDensity(scene, static_cast<int>(layered[k]));
    if (d.hasUvArea) {
      std::snprintf(number, sizeof number, " %.1f (%.3g uv units per metre)", m.glint.logDensity,
                    std::sqrt(d.uvAreaPerSquareMetre));
    } else {
      std::snprintf(number, sizeof number, " %.1f (no uv area: smooth)", m.glint.logDensity);
    }
    text += (k == 0 ? " '" : ", '") + m.name + "'" + number;
  }
  return text + "; --log-density D sets another";
}

scene::Scene SceneOptions::loadScene() const {
  scene::Scene s = scene::loadScene(scene);
  const std::vector<std::size_t> layered = glintMaterials.empty() ? std::vector<std::size_t>{}
                                                                  : scene::applyGlint(s, glintMaterials);
  if (alpha.size() > 2) throw Error("--alpha takes one or two values");
  if (sky) {
    if (!(*sky >= 0.0f && *sky <= 100.0f)) throw Error("--sky must be in [0, 100]");
    if (!environment.file.empty()) throw Error("--sky and --env both replace the environment; give one");
    s.environment = scene::skyEnvironment(*sky);
  }
  environment.applyTo(s);
  if (rectLights.size() % 6 != 0) throw Error("--rect-light takes six numbers: X,Y,Z,W,H,L");
  const glm::vec3 sceneCentre = 0.5f * (s.boundsMin() + s.boundsMax());
  for (std::size_t i = 0; i < rectLights.size(); i += 6) {
    const float* r = &rectLights[i];
    if (!std::all_of(r, r + 6, [](float v) { return std::isfinite(v); }) || !(r[3] > 0.0f && r[4] > 0.0f && r[5] >= 0.0f)) {
      throw Error("--rect-light: X,Y,Z,W,H,L must be finite, W and H > 0 and L >= 0");
    }
    scene::addRectangleLight(s, glm::vec3(r[0], r[1], r[2]), sceneCentre, r[3], r[4], glm::vec3(r[5]));
  }
  const bool droppedDefaultLights =
      (sky || !environment.file.empty() || !rectLights.empty()) && environment.dropDefaultLights(s);
  if (patternSeed && !(*patternSeed >= 0 && *patternSeed <= 0xffffffffLL)) {
    throw Error("--pattern-seed must be a whole number in [0, 4294967295], got " + std::to_string(*patternSeed));
  }
  // The layer overrides are checked as options first, so that a bad one is named as the option
  // ("--alpha: alpha_x must be in [0.005, 2], got 5"), not as the first material it reaches.
  const auto checkOverride = [](const char* option, const std::function<void(scene::GlintLayer&)>& set) {
    scene::GlintLayer probe;
    probe.enabled = true;
    set(probe);
    try {
      scene::validateGlintLayer(probe, 0);
    } catch (const Error& e) {
      throw Error(std::string(option) + ": " + e.what());
    }
  };
  if (!alpha.empty()) checkOverride("--alpha", [&](scene::GlintLayer& p) { p.alpha = glm::vec2(alpha.front(), alpha.back()); });
  if (rho) checkOverride("--rho", [&](scene::GlintLayer& p) { p.rho = *rho; });
  if (logDensity) checkOverride("--log-density", [&](scene::GlintLayer& p) { p.logDensity = *logDensity; });
  if (relativeArea) checkOverride("--relative-area", [&](scene::GlintLayer& p) { p.relativeArea = *relativeArea; });
  for (scene::Material& m : s.materials) {
    if (ndf) m.specular.ndf = ndfFromName("--ndf", *ndf);
    if (masking) m.specular.masking = maskingFromName("--masking", *masking);
    if (multipleScattering) m.specular.multipleScattering = *multipleScattering;
    if (!m.glint.enabled) continue;
    if (!alpha.empty()) m.glint.alpha = glm::vec2(alpha.front(), alpha.back());
    if (rho) m.glint.rho = *rho;
    if (logDensity) m.glint.logDensity = *logDensity;
    if (relativeArea) m.glint.relativeArea = *relativeArea;
    if (patternSeed) m.glint.patternSeed = static_cast<std::uint32_t>(*patternSeed);
    if (lod) m.glint.lod = lodFromName("--lod", *lod);
    try {
      scene::validateGlintLayer(m.glint, s.textures.size());
    } catch (const Error& e) {
      throw Error("material '" + m.name + "': " + e.what());
    }
  }
  for (const std::string& unread : s.unreadFeatures) {
    std::fprintf(stderr, "glint: warning: %s: %s\n", scene.c_str(), unread.c_str());
  }
  for (const std::string& note : s.notes) std::fprintf(stderr, "glint: %s: %s\n", scene.c_str(), note.c_str());
  for (const scene::Material& m : s.materials) {
    if (m.alphaMode == scene::Material::AlphaMode::Blend) {
      std::fprintf(stderr, "glint: warning: %s: material '%s' has alphaMode BLEND; glint does not blend and draws it opaque\n",
                   scene.c_str(), m.name.c_str());
    }
  }
  s.cameras[camera] = cameraOptions.applyTo(findCamera(s));
  // Which density the new layers got, unless --log-density replaced it; only once nothing above
  // failed, so that an error stays the one line on stderr.
  if (!layered.empty() && !logDensity) std::fprintf(stderr, "glint: %s\n", describeDefaultGlintDensity(s, layered).c_str());
  if (droppedDefaultLights) {
    std::fprintf(stderr,
                 "glint: the %s the default lights of %s, which has none of its own "
                 "(--keep-default-lights keeps them)\n",
                 sky || !environment.file.empty() ? "environment replaces" : "rectangle lights replace", scene.c_str());
  }
  return s;
}

std::vector<scene::Scene> SceneOptions::loadScenes(const std::vector<std::string>& names) const {
  SceneOptions each = *this;
  std::vector<scene::Scene> scenes;
  for (const std::string& name : names) {
    each.scene = name;
    scenes.push_back(each.loadScene());
  }
  return scenes;
}

const scene::Camera& SceneOptions::findCamera(const scene::Scene& s) const {
  const auto it = s.cameras.find(camera);
  if (it == s.cameras.end()) {
    std::string names;
    for (const auto& [name, c] : s.cameras) names += (names.empty() ? "" : ", ") + name;
    throw Error("scene '" + scene + "' has no camera '" + camera + "' (cameras: " + names + ")");
  }
  return it->second;
}

Dictionary SceneOptions::loadDictionary() const {
  return dictionary.empty() ? generateDictionary(DictionaryParameters{}) : loadAnyDictionary(dictionary);
}

std::string SceneOptions::outputNamedAfterScene(const std::string& extension) const {
  return scene::sceneName(scene) + extension;
}

std::pair<int, int> parseImageSize(const std::string& text) {
  static const std::regex pattern(R"((\d+)x(\d+))");
  std::smatch match;
  if (!std::regex_match(text, match, pattern)) throw Error("--size must look like 512x512, got '" + text + "'");
  // More than five digits is past the range whatever they say (and past an int's).
  const auto side = [](const std::string& digits) { return digits.size() > 5 ? 100000 : std::stoi(digits); };
  const int w = side(match[1]);
  const int h = side(match[2]);
  if (w < 1 || h < 1 || w > 8192 || h > 8192) throw Error("--size must be between 1x1 and 8192x8192, got " + text);
  return {w, h};
}

void printWarnings(const std::vector<std::string>& warnings) {
  for (const std::string& warning : warnings) std::fprintf(stderr, "glint: warning: %s\n", warning.c_str());
}

void warnAboutUndrawnLights(const scene::Scene& scene) {
  if (scene.lights.size() > static_cast<std::size_t>(gl::kMaxLights)) {
    std::fprintf(stderr, "glint: warning: scene '%s' has %zu lights; the rasteriser draws the first %d\n",
                 scene.name.c_str(), scene.lights.size(), gl::kMaxLights);
  }
}

}  // namespace glint::app
