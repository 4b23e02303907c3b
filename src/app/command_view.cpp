// `glint view`: the renderer in a window, with Dear ImGui sliders for one chosen glint material's
// parameters and one chosen light's direction and intensity (scene/view_controls.h), the BRDF,
// anti-aliasing, exposure and camera preset, the mouse to orbit, pan and zoom, and the frame time
// (docs/cli.md). It opens on the scene as `glint render` draws it: nothing is changed until a
// slider moves.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include <glad/gl.h>
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>

#include "app/commands.h"
#include "app/raster_options.h"
#include "app/scene_options.h"
#include "gl/context.h"
#include "gl/display.h"
#include "gl/frame_timer.h"
#include "gl/renderer.h"
#include "glint/error.h"
#include "glint/file_io.h"
#include "glint/image.h"
#include "glint/image_io.h"
#include "scene/camera_moves.h"
#include "scene/view_controls.h"

namespace glint::app {

namespace {

struct ViewOptions {
  SceneOptions scene;
  int width = 1280;
  int height = 720;
  int frames = 0;          // 0: until the window closes
  std::string screenshot;  // written after the last frame
  std::string antiAliasing = "ggaa+lean";
  bool hidePanel = false;  // start without the panel (H shows it)
  RasterOptions raster;
  FootprintOptions footprint;
  QualityOptions quality;
};

// What the panel edits besides the scene's materials and lights (scene/view_controls.h): how the
// frame is drawn and shown.
struct FrameControls {
  int brdf = 0;          // index into allSpecularModels()
  int antiAliasing = 2;  // index into gl::allAntiAliasingModes()
  float exposure = 1.0f;  // times the scene's exposure
  int camera = 0;
  bool shadows = true;
  int msaa = 0;  // samples a pixel: 2^msaa
  int shadowCascades = 4;
  int footprint = 0;  // index into the panel's footprint policies
};

// The footprint policies the panel offers (docs/antialiasing.md, "Footprint policies"), and the
// one given with --footprint when it is none of them.
std::vector<std::string> panelFootprintPolicies(const FootprintPolicy& start) {
  std::vector<std::string> names = {"exact", "aniso=4", "cells=24", "cells=24,drop=0.5"};
  const std::string startName = footprintPolicyName(start);
  if (std::find(names.begin(), names.end(), startName) == names.end()) names.push_back(startName);
  return names;
}

class ImGuiSession {
 public:
  explicit ImGuiSession(GLFWwindow* window) {
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini written next to the user's files
    ImGui_ImplGlfw_InitForOpenGL(window, true);
    ImGui_ImplOpenGL3_Init("#version 450");
  }
  ~ImGuiSession() {
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
  }
};

// Mouse moves of the next frame's camera (scene/camera_moves.h), unless the mouse is on the panel:
// a left drag orbits the target (a drag over the window's height turns the camera half a turn), a
// right or middle drag pans with the cursor, the wheel zooms by 10% a notch.
void moveCameraWithTheMouse(scene::Camera& camera, int framebufferHeight) {
  const ImGuiIO& io = ImGui::GetIO();
  if (io.WantCaptureMouse) return;
  const glm::vec2 delta(io.MouseDelta.x, io.MouseDelta.y);  // window points; NaN-free when no mouse
  if (ImGui::IsMouseDragging(ImGuiMouseButton_Left, 0.0f)) {
    const float radiansPerPoint = 3.14159265f / std::max(io.DisplaySize.y, 1.0f);
    camera = scene::orbitCamera(camera, -delta.x * radiansPerPoint, delta.y * radiansPerPoint);
  } else if (ImGui::IsMouseDragging(ImGuiMouseButton_Right, 0.0f) || ImGui::IsMouseDragging(ImGuiMouseButton_Middle, 0.0f)) {
    camera = scene::panCamera(camera, delta * io.DisplayFramebufferScale.y, framebufferHeight);
  }
  if (io.MouseWheel != 0.0f) camera = scene::zoomCamera(camera, std::pow(0.9f, io.MouseWheel));
}

// Shows `text` while the mouse is on the last item: every control says its range and meaning.
void tooltip(const std::string& text) {
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", text.c_str());
}

void combo(const char* label, int& choice, const std::vector<std::string>& items) {
  std::vector<const char*> names;
  for (const std::string& item : items) names.push_back(item.c_str());
  ImGui::Combo(label, &choice, names.data(), static_cast<int>(names.size()));
}

// Sliders write their value only when the user moves them: an untouched control stays bit for bit
// what the scene gave (scene/view_controls.h relies on it). SliderAngle would write back its
// degrees converted to radians every frame, so the angles go through a copy.
void angleSlider(const char* label, float& radians, float minDegrees, float maxDegrees) {
  float value = radians;
  if (ImGui::SliderAngle(label, &value, minDegrees, maxDegrees, "%.1f deg", ImGuiSliderFlags_AlwaysClamp)) {
    radians = value;
  }
}

// One axis of the glint layer's roughness: Beckmann alpha, shown with the glTF roughness it
// corresponds to (alpha = roughness^2, so roughness = sqrt(alpha); above 1 for alpha above 1).
void alphaSlider(const char* label, float& alpha, const char* axis) {
  // ImGui's format is a printf format for the value; the roughness goes into it as text.
  char format[64];
  std::snprintf(format, sizeof format, "%%.3f (roughness %.3f)", std::sqrt(alpha));
  ImGui::SliderFloat(label, &alpha, kMinRoughnessAlpha, kMaxRoughnessAlpha, format,
                     ImGuiSliderFlags_Logarithmic | ImGuiSliderFlags_AlwaysClamp);
  char text[256];
  std::snprintf(text, sizeof text,
                "Beckmann roughness alpha_%s (along the %s), %.3g..%.3g, logarithmic. The glTF roughness in "
                "brackets is sqrt(alpha). A roughness texture multiplies it per texel.",
                axis, axis[0] == 'x' ? "tangent" : "bitangent", kMinRoughnessAlpha, kMaxRoughnessAlpha);
  tooltip(text);
}

const char* lightTypeName(scene::Light::Type type) {
  switch (type) {
    case scene::Light::Type::Point: return "point";
    case scene::Light::Type::Directional: return "directional";
    case scene::Light::Type::Spot: return "spot";
  }
  return "light";
}

// The combo labels: the glint materials by name, the lights the rasteriser draws by number and type.
struct Choices {
  std::vector<std::size_t> glintMaterials;  // indices into the scene's materials
  std::vector<std::string> materialNames;
  std::vector<std::string> lightNames;
  int material = 0;  // index into glintMaterials
  int light = 0;     // index into the scene's lights
};

Choices choicesOf(const scene::Scene& scene) {
  Choices choices;
  for (std::size_t i = 0; i < scene.materials.size(); ++i) {
    const scene::Material& m = scene.materials[i];
    if (!m.glint.enabled) continue;
    choices.glintMaterials.push_back(i);
    choices.materialNames.push_back(m.name.empty() ? "material " + std::to_string(i) : m.name);
  }
  const std::size_t drawn = std::min(scene.lights.size(), static_cast<std::size_t>(gl::kMaxLights));
  for (std::size_t i = 0; i < drawn; ++i) {
    choices.lightNames.push_back("light " + std::to_string(i + 1) + " (" + lightTypeName(scene.lights[i].type) + ")");
  }
  return choices;
}

// The sliders of the chosen glint material.
void materialSliders(Choices& choices, scene::ViewControls& controls) {
  if (choices.glintMaterials.empty()) {
    ImGui::TextDisabled("no glint material");
    return;
  }
  combo("material", choices.material, choices.materialNames);
  tooltip("The glint material the sliders below edit; the others keep their own parameters.");
  scene::MaterialControls& m = controls.materials[choices.glintMaterials[static_cast<std::size_t>(choices.material)]];
  alphaSlider("Beckmann alpha x", m.alpha.x, "x");
  alphaSlider("Beckmann alpha y", m.alpha.y, "y");
  ImGui::SliderFloat("slope correlation", &m.rho, -kMaxSlopeCorrelation, kMaxSlopeCorrelation, "%.2f",
                     ImGuiSliderFlags_AlwaysClamp);
  tooltip("rho, -0.99..0.99: the correlation of the Beckmann target's slopes; 0 is the 2020 model.");
  ImGui::SliderFloat("log density", &m.logDensity, 0.0f, 50.0f, "%.2f", ImGuiSliderFlags_AlwaysClamp);
  tooltip("ln(microfacets per unit glint-uv area), 0..50 (the paper's range is 15..40): higher gives more, fainter "
          "glints, towards the smooth Beckmann lobe. A log density texture replaces it per texel.");
  ImGui::SliderFloat("relative area", &m.relativeArea, 0.01f, 1.0f, "%.3f", ImGuiSliderFlags_AlwaysClamp);
  tooltip("The share of the surface's cells that hold microfacets, 0.01..1: below 1, some cells stay dark. A "
          "relative area texture multiplies it per texel.");
  combo("smooth target", m.specular.ndf, {"Beckmann (the paper's)", "GGX (glTF's)"});
  tooltip("The normal distribution the glints converge to at high density, and the material's Cook-Torrance: "
          "Beckmann as in the 2020 paper, or GGX as glTF's metallic-roughness BRDF (docs/method.md section 6).");
  combo("masking", m.specular.masking, {"V-cavity (the paper's)", "Smith (glTF's)"});
  tooltip("The microfacets' masking and shadowing: V-cavity as in the 2020 paper, or height-correlated Smith with "
          "the smooth target's Lambda.");
  ImGui::Checkbox("multiple scattering", &m.specular.multipleScattering);
  tooltip("Adds the energy a single bounce between the microfacets loses (Kulla & Conty 2017): rough surfaces "
          "keep their brightness.");
}

// The sliders of the chosen light: its direction from the scene's centre and its strength.
void lightSliders(const scene::Scene& scene, const scene::ViewControls& sceneControls, Choices& choices,
                  scene::ViewControls& controls) {
  if (choices.lightNames.empty()) {
    ImGui::TextDisabled("no light");
    return;
  }
  combo("light", choices.light, choices.lightNames);
  tooltip("The light the sliders below move; the others stay where the scene puts them.");
  const std::size_t index = static_cast<std::size_t>(choices.light);
  scene::LightControls& l = controls.lights[index];
  const bool positional = scene.lights[index].positional();
  angleSlider("light azimuth", l.azimuth, -180.0f, 180.0f);
  tooltip(std::string("-180..180 degrees about the vertical, 0 towards +z, 90 towards +x: where the light ") +
          (positional ? "stands, seen from the scene's centre (its distance kept; a spot turns with it)."
                      : "comes from."));
  angleSlider("light elevation", l.elevation, -90.0f, 90.0f);
  tooltip(std::string("-90..90 degrees above the horizontal: where the light ") +
          (positional ? "stands, seen from the scene's centre." : "comes from."));
  // Up to ten times the scene's own strength (a black light up to 100).
  const float own = sceneControls.lights[index].strength;
  const float maxStrength = own > 0.0f ? 10.0f * own : 100.0f;
  ImGui::SliderFloat("light intensity", &l.strength, 0.0f, maxStrength, "%.3g",
                     ImGuiSliderFlags_Logarithmic | ImGuiSliderFlags_AlwaysClamp);
  char text[256];
  std::snprintf(text, sizeof text,
                "The largest component of the light's intensity, in %s, 0..%.3g (ten times the scene's); its colour "
                "is kept.",
                positional ? "W/sr" : "W/m^2", maxStrength);
  tooltip(text);
}

void runView(const ViewOptions& options) {
  if (options.width < 64 || options.height < 64 || options.width > 8192 || options.height > 8192) {
    throw Error("--width and --height must be in [64, 8192], got " + std::to_string(options.width) + "x" +
                std::to_string(options.height));
  }
  if (options.frames < 0) throw Error("--frames must be 0 (until closed) or positive");
  if (!options.screenshot.empty() && lowercaseExtension(options.screenshot) != ".png") {
    throw Error(options.screenshot + ": the screenshot must end in .png (it is the window's 8-bit image)");
  }
  if (!options.screenshot.empty()) requireWritablePlace(options.screenshot);
  if (!options.screenshot.empty() && options.frames == 0) {
    throw Error("--screenshot needs --frames N (the screenshot is of frame N)");
  }
  const FootprintPolicy footprintPolicy = options.footprint.policy();  // refused before a window opens
  const scene::Scene scene = options.scene.loadScene();
  const Dictionary dictionary = options.scene.loadDictionary();
  gl::WindowContext window(options.width, options.height, "glint view: " + options.scene.scene);
  const gl::ContextInfo info = gl::currentContextInfo();
  warnAboutUndrawnLights(scene);
  gl::Renderer renderer(scene, dictionary);
  printWarnings(renderer.warnings());
  gl::FrameSettings startSettings;  // --shadows, --shadow-cascades and --msaa, which the panel changes
  options.raster.applyTo(startSettings, renderer);
  const gl::DisplayPass display;
  gl::FrameTimer timer;
  ImGuiSession imgui(window.window());

  // The materials and lights are drawn as the scene has them, with the controls applied every
  // frame; the controls start as the scene's own, so that nothing changes until a slider moves.
  const glm::vec3 pivot = scene::lightPivot(scene);
  const scene::ViewControls sceneControls = scene::viewControls(scene, pivot);
  scene::ViewControls controls = sceneControls;
  Choices choices = choicesOf(scene);
  FrameControls frameControls;
  frameControls.shadows = startSettings.shadows;
  frameControls.shadowCascades = startSettings.shadowCascades;
  const std::vector<std::string> footprintNames = panelFootprintPolicies(footprintPolicy);
  std::vector<FootprintPolicy> footprintPolicies;
  for (const std::string& name : footprintNames) footprintPolicies.push_back(footprintPolicyFromString(name));
  frameControls.footprint = static_cast<int>(
      std::find(footprintNames.begin(), footprintNames.end(), footprintPolicyName(footprintPolicy)) -
      footprintNames.begin());
  std::vector<std::string> msaaNames;
  for (int samples = 1; samples <= renderer.maxMsaaSamples(); samples *= 2) {
    if (samples == startSettings.msaa) frameControls.msaa = static_cast<int>(msaaNames.size());
    msaaNames.push_back(std::to_string(samples));
  }
  const gl::AntiAliasing initialAntiAliasing = gl::antiAliasingFromString(options.antiAliasing);
  const std::vector<gl::AntiAliasing> antiAliasingModes = gl::allAntiAliasingModes();
  frameControls.antiAliasing = static_cast<int>(
      std::find(antiAliasingModes.begin(), antiAliasingModes.end(), initialAntiAliasing) - antiAliasingModes.begin());
  std::vector<std::string> brdfNames;
  for (SpecularModel model : allSpecularModels()) brdfNames.emplace_back(toString(model));
  std::vector<std::string> antiAliasingNames;
  for (gl::AntiAliasing mode : antiAliasingModes) antiAliasingNames.emplace_back(gl::toString(mode));
  std::vector<std::string> cameraNames;
  for (const auto& [name, camera] : scene.cameras) {
    if (name == options.scene.camera) frameControls.camera = static_cast<int>(cameraNames.size());
    cameraNames.push_back(name);
  }
  // The camera the mouse moves, starting from the chosen preset and back to it when another is
  // chosen or "reset camera" is pressed.
  scene::Camera viewCamera = scene.cameras.at(cameraNames[static_cast<std::size_t>(frameControls.camera)]);
  int viewCameraPreset = frameControls.camera;
  bool showPanel = !options.hidePanel;
  double frameMilliseconds = 0.0;

  for (int frameIndex = 0; !glfwWindowShouldClose(window.window()); ++frameIndex) {
    if (options.frames > 0 && frameIndex >= options.frames) break;
    glfwPollEvents();
    scene::applyViewControls(scene, controls, pivot, renderer.materials(), renderer.lights());
    int width = 0;
    int height = 0;
    glfwGetFramebufferSize(window.window(), &width, &height);
    if (width <= 0 || height <= 0) continue;  // minimised

    gl::FrameSettings frame;
    frame.width = width;
    frame.height = height;
    frame.brdf = allSpecularModels()[static_cast<std::size_t>(frameControls.brdf)];
    frame.antiAliasing = antiAliasingModes[static_cast<std::size_t>(frameControls.antiAliasing)];
    frame.camera = viewCamera;
    frame.shadows = frameControls.shadows;
    frame.shadowCascades = frameControls.shadowCascades;
    frame.msaa = 1 << frameControls.msaa;
    frame.footprintPolicy = footprintPolicies[static_cast<std::size_t>(frameControls.footprint)];
    frameMilliseconds = timer.milliseconds([&] { renderer.renderFrame(frame); });

    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    display.draw(renderer.radianceTexture(), scene.exposure * frameControls.exposure, width, height);

    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    // H shows and hides the panel, unless a slider is taking typed text.
    if (!ImGui::GetIO().WantCaptureKeyboard && ImGui::IsKeyPressed(GLFW_KEY_H, false)) showPanel = !showPanel;
    bool resetCamera = false;
    if (showPanel) {
      ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_FirstUseEver);
      ImGui::Begin("glint");
      materialSliders(choices, controls);
      ImGui::Separator();
      lightSliders(scene, sceneControls, choices, controls);
      ImGui::Separator();
      combo("BRDF", frameControls.brdf, brdfNames);
      tooltip("The specular model of the glint materials: glint (Chermain et al. 2020), cook-torrance (the "
              "smooth lobe of the same roughness), zirr-kaplanyan (Zirr & Kaplanyan 2016) or zirr-kaplanyan-reference "
              "(the same on the reference shader's slower schedule), as `glint render --brdf`.");
      combo("anti-aliasing", frameControls.antiAliasing, antiAliasingNames);
      tooltip("ggaa+lean: glints filtered by the half vector's variation over the pixel and by the normal map's "
              "slope variance; ggaa: the first only; none: the 2020 model.");
      ImGui::Checkbox("shadows", &frameControls.shadows);
      tooltip("The lights' shadows, from shadow maps, as `glint render --shadows`.");
      ImGui::SliderInt("shadow cascades", &frameControls.shadowCascades, 1, 4, "%d", ImGuiSliderFlags_AlwaysClamp);
      tooltip("Shadow maps of a directional light, each over a range of the view's depth; 1 fits one map to the "
              "whole scene, as `glint render --shadow-cascades`.");
      combo("footprint", frameControls.footprint, footprintNames);
      tooltip("The cells a pixel's glints walk: exact (the paper's footprint), aniso=4 (anisotropy at most 4), "
              "cells=24 (each walked level at most 24 cells), drop=0.5 (the coarser level skipped below blend "
              "weight 0.5), as `glint render --footprint`. A policy's first frame compiles its program.");
      combo("msaa", frameControls.msaa, msaaNames);
      tooltip("Samples a pixel of the geometry, for anti-aliased edges; each surface in a pixel is shaded once, "
              "as `glint render --msaa`.");
      ImGui::SliderFloat("exposure", &frameControls.exposure, 0.05f, 20.0f, "%.2f",
                         ImGuiSliderFlags_Logarithmic | ImGuiSliderFlags_AlwaysClamp);
      tooltip("0.05..20, logarithmic: multiplies the scene's exposure before the tone curve, as `glint render "
              "--exposure` does.");
      combo("camera", frameControls.camera, cameraNames);
      tooltip("The scene's camera presets; the mouse moves the camera from the chosen one.");
      resetCamera = ImGui::Button("reset camera");
      tooltip("Back to the chosen preset.");
      ImGui::SameLine();
      ImGui::TextDisabled("drag: orbit, right-drag: pan, wheel: zoom, H: hide");
      ImGui::Separator();
      ImGui::Text("%dx%d on %s", width, height, info.renderer.c_str());
      if (timer.usesGpuQueries()) {
        ImGui::Text("frame %.2f ms (GPU timer query)", frameMilliseconds);
      } else {
        ImGui::Text("frame %.1f ms (wall clock around glFinish;", frameMilliseconds);
        ImGui::Text("GPU timer queries are meaningless on llvmpipe)");
      }
      ImGui::End();
    }
    if (resetCamera || frameControls.camera != viewCameraPreset) {
      viewCamera = scene.cameras.at(cameraNames[static_cast<std::size_t>(frameControls.camera)]);
      viewCameraPreset = frameControls.camera;
    }
    moveCameraWithTheMouse(viewCamera, height);
    ImGui::Render();
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    if (options.frames > 0 && frameIndex + 1 == options.frames && !options.screenshot.empty()) {
      writePng(options.screenshot, gl::readFramebufferRgb8(width, height));
      std::fprintf(stderr, "glint: wrote %s (frame %d, %dx%d)\n", options.screenshot.c_str(), options.frames, width, height);
    }
    glfwSwapBuffers(window.window());
  }
}

}  // namespace

void registerViewCommand(CLI::App& app) {
  auto options = std::make_shared<ViewOptions>();
  CLI::App* command = app.add_subcommand("view", "Show a scene in a window with sliders (needs a display; xvfb-run works)");
  options->scene.addTo(*command);
  command->add_option("--width", options->width, "Window width")->capture_default_str();
  command->add_option("--height", options->height, "Window height")->capture_default_str();
  command->add_option("--frames", options->frames, "Close after this many frames (0: when the window is closed)")
      ->capture_default_str();
  command->add_option("--aa", options->antiAliasing, "Glint anti-aliasing at start: ggaa+lean, ggaa or none")
      ->capture_default_str();
  command->add_option("--screenshot", options->screenshot,
                      "With --frames N: write frame N as the window shows it (the panel too, unless hidden) to a PNG");
  command->add_flag("--hide-panel", options->hidePanel, "Start with the panel hidden (H shows and hides it)");
  options->raster.addTo(*command);
  options->footprint.addTo(*command, false);
  options->quality.addTo(*command);
  command->callback([options, command] {
    options->quality.applyTo(*command, options->antiAliasing, options->footprint, options->raster);
    runView(*options);
  });
}

}  // namespace glint::app
