// `glint view`: the renderer in a window, with Dear ImGui sliders for the glint parameters, the
// BRDF, the light and the camera preset, the mouse to orbit, pan and zoom, and the frame time
// (docs/cli.md).
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
#include "app/scene_options.h"
#include "gl/context.h"
#include "gl/frame_timer.h"
#include "gl/renderer.h"
#include "gl/shader.h"
#include "glint/error.h"
#include "glint/image.h"
#include "scene/camera_moves.h"

namespace glint::app {

namespace {

struct ViewOptions {
  SceneOptions scene;
  int width = 1280;
  int height = 720;
  int frames = 0;          // 0: until the window closes
  std::string screenshot;  // written after the last frame
  std::string antiAliasing = "ggaa+lean";
};

// The parameters the sliders edit, applied to every glint layer of the scene.
struct Controls {
  glm::vec2 alpha{0.5f};
  float rho = 0.0f;
  float logDensity = 27.0f;
  float relativeArea = 1.0f;
  int brdf = 0;  // index into gl::allBrdfModels()
  int antiAliasing = 2;  // index into gl::allAntiAliasingModes()
  float lightAzimuth = 0.6f;
  float lightElevation = 0.9f;
  float lightScale = 1.0f;
  float exposure = 1.0f;
  int camera = 0;
};

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

void writeScreenshot(const std::string& path, int width, int height) {
  std::vector<std::uint8_t> rgb(static_cast<std::size_t>(width) * height * 3);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE, rgb.data());
  ImageRgb8 image(width, height, {0, 0, 0});
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const std::uint8_t* p = &rgb[(static_cast<std::size_t>(height - 1 - y) * width + x) * 3];
      image.at(x, y) = {p[0], p[1], p[2]};
    }
  }
  writePng(path, image);
}

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

void runView(const ViewOptions& options) {
  if (options.width < 64 || options.height < 64 || options.width > 8192 || options.height > 8192) {
    throw Error("--size must be between 64x64 and 8192x8192");
  }
  if (options.frames < 0) throw Error("--frames must be 0 (until closed) or positive");
  if (!options.screenshot.empty() && options.frames == 0) {
    throw Error("--screenshot needs --frames N (the screenshot is of frame N)");
  }
  const scene::Scene scene = options.scene.loadScene();
  const Dictionary dictionary = options.scene.loadDictionary();
  gl::WindowContext window(options.width, options.height, "glint view: " + options.scene.scene);
  const gl::ContextInfo info = gl::currentContextInfo();
  warnAboutUndrawnLights(scene);
  gl::Renderer renderer(scene, dictionary);
  printWarnings(renderer.warnings());
  gl::ShaderProgram display({{GL_VERTEX_SHADER, "fullscreen.vert"}, {GL_FRAGMENT_SHADER, "display.frag"}});
  GLuint emptyVertexArray = 0;
  glCreateVertexArrays(1, &emptyVertexArray);
  gl::FrameTimer timer;
  ImGuiSession imgui(window.window());

  Controls controls;
  const gl::AntiAliasing initialAntiAliasing = gl::antiAliasingFromString(options.antiAliasing);
  const std::vector<gl::AntiAliasing> antiAliasingModes = gl::allAntiAliasingModes();
  controls.antiAliasing = static_cast<int>(
      std::find(antiAliasingModes.begin(), antiAliasingModes.end(), initialAntiAliasing) - antiAliasingModes.begin());
  for (const scene::Material& m : scene.materials) {
    if (!m.glint.enabled) continue;
    controls.alpha = m.glint.alpha;
    controls.rho = m.glint.rho;
    controls.logDensity = m.glint.logDensity;
    controls.relativeArea = m.glint.relativeArea;
    break;
  }
  std::vector<std::string> cameraNames;
  for (const auto& [name, camera] : scene.cameras) {
    if (name == options.scene.camera) controls.camera = static_cast<int>(cameraNames.size());
    cameraNames.push_back(name);
  }
  // The camera the mouse moves, starting from the chosen preset and back to it when another is
  // chosen or "reset camera" is pressed.
  scene::Camera viewCamera = scene.cameras.at(cameraNames[static_cast<std::size_t>(controls.camera)]);
  int viewCameraPreset = controls.camera;
  const std::vector<scene::Light> originalLights = scene.lights;
  const glm::vec3 centre = 0.5f * (scene.boundsMin() + scene.boundsMax());
  double frameMilliseconds = 0.0;

  for (int frameIndex = 0; !glfwWindowShouldClose(window.window()); ++frameIndex) {
    if (options.frames > 0 && frameIndex >= options.frames) break;
    glfwPollEvents();
    for (scene::Material& m : renderer.materials()) {
      if (!m.glint.enabled) continue;
      m.glint.alpha = controls.alpha;
      m.glint.rho = controls.rho;
      m.glint.logDensity = controls.logDensity;
      m.glint.relativeArea = controls.relativeArea;
    }
    // The first light is moved by the sliders around the scene's centre; all are scaled.
    renderer.lights() = originalLights;
    for (scene::Light& light : renderer.lights()) light.intensity *= controls.lightScale;
    if (!renderer.lights().empty()) {
      const glm::vec3 direction(std::cos(controls.lightElevation) * std::sin(controls.lightAzimuth),
                                std::sin(controls.lightElevation),
                                std::cos(controls.lightElevation) * std::cos(controls.lightAzimuth));
      scene::Light& light = renderer.lights().front();
      if (light.positional()) {
        light.position = centre + direction * glm::length(originalLights.front().position - centre);
        if (light.type == scene::Light::Type::Spot) light.direction = -direction;  // still aimed at the centre
      } else {
        light.direction = -direction;
      }
    }
    int width = 0;
    int height = 0;
    glfwGetFramebufferSize(window.window(), &width, &height);
    if (width <= 0 || height <= 0) continue;  // minimised

    gl::FrameSettings frame;
    frame.width = width;
    frame.height = height;
    frame.brdf = gl::allBrdfModels()[static_cast<std::size_t>(controls.brdf)];
    frame.antiAliasing = gl::allAntiAliasingModes()[static_cast<std::size_t>(controls.antiAliasing)];
    frame.camera = viewCamera;
    frameMilliseconds = timer.milliseconds([&] { renderer.renderFrame(frame); });

    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, width, height);
    glDisable(GL_DEPTH_TEST);
    glUseProgram(display.id());
    glUniform1f(display.uniform("uExposure"), scene.exposure * controls.exposure);
    glBindTextureUnit(0, renderer.radianceTexture());
    glBindVertexArray(emptyVertexArray);
    glDrawArrays(GL_TRIANGLES, 0, 3);

    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_FirstUseEver);
    ImGui::Begin("glint");
    std::vector<const char*> brdfNames;
    for (gl::BrdfModel model : gl::allBrdfModels()) brdfNames.push_back(gl::toString(model));
    ImGui::Combo("BRDF", &controls.brdf, brdfNames.data(), static_cast<int>(brdfNames.size()));
    ImGui::SliderFloat("roughness x", &controls.alpha.x, 0.01f, 1.0f, "%.3f", ImGuiSliderFlags_Logarithmic);
    ImGui::SliderFloat("roughness y", &controls.alpha.y, 0.01f, 1.0f, "%.3f", ImGuiSliderFlags_Logarithmic);
    ImGui::SliderFloat("slope correlation", &controls.rho, -kMaxSlopeCorrelation, kMaxSlopeCorrelation, "%.2f");
    if (ImGui::IsItemHovered()) {
      ImGui::SetTooltip("rho in [-0.99, 0.99]: the Beckmann target's slope correlation; 0 is the 2020 model");
    }
    std::vector<const char*> antiAliasingNames;
    for (gl::AntiAliasing mode : gl::allAntiAliasingModes()) antiAliasingNames.push_back(gl::toString(mode));
    ImGui::Combo("anti-aliasing", &controls.antiAliasing, antiAliasingNames.data(),
                 static_cast<int>(antiAliasingNames.size()));
    if (ImGui::IsItemHovered()) {
      ImGui::SetTooltip("ggaa+lean: glints filtered by the half vector's variation over the pixel and by the normal "
                        "map's slope variance; ggaa: the first only; none: the 2020 model");
    }
    ImGui::SliderFloat("log density", &controls.logDensity, 10.0f, 45.0f, "%.1f");
    ImGui::SliderFloat("relative area", &controls.relativeArea, 0.01f, 1.0f, "%.2f");
    ImGui::SliderAngle("light azimuth", &controls.lightAzimuth, -180.0f, 180.0f);
    ImGui::SliderAngle("light elevation", &controls.lightElevation, 5.0f, 90.0f);
    ImGui::SliderFloat("light intensity", &controls.lightScale, 0.0f, 10.0f, "%.2f", ImGuiSliderFlags_Logarithmic);
    ImGui::SliderFloat("exposure", &controls.exposure, 0.05f, 20.0f, "%.2f", ImGuiSliderFlags_Logarithmic);
    std::vector<const char*> names;
    for (const std::string& n : cameraNames) names.push_back(n.c_str());
    ImGui::Combo("camera", &controls.camera, names.data(), static_cast<int>(names.size()));
    const bool resetCamera = ImGui::Button("reset camera");
    ImGui::SameLine();
    ImGui::TextDisabled("drag: orbit, right-drag: pan, wheel: zoom");
    if (resetCamera || controls.camera != viewCameraPreset) {
      viewCamera = scene.cameras.at(cameraNames[static_cast<std::size_t>(controls.camera)]);
      viewCameraPreset = controls.camera;
    }
    moveCameraWithTheMouse(viewCamera, height);
    ImGui::Separator();
    ImGui::Text("%dx%d on %s", width, height, info.renderer.c_str());
    if (timer.usesGpuQueries()) {
      ImGui::Text("frame %.2f ms (GPU timer query)", frameMilliseconds);
    } else {
      ImGui::Text("frame %.1f ms (wall clock around glFinish;", frameMilliseconds);
      ImGui::Text("GPU timer queries are meaningless on llvmpipe)");
    }
    ImGui::End();
    ImGui::Render();
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    if (options.frames > 0 && frameIndex + 1 == options.frames && !options.screenshot.empty()) {
      writeScreenshot(options.screenshot, width, height);
    }
    glfwSwapBuffers(window.window());
  }
  glDeleteVertexArrays(1, &emptyVertexArray);
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
  command->add_option("--screenshot", options->screenshot, "With --frames N: write frame N, sliders included, to a PNG");
  command->callback([options] { runView(*options); });
}

}  // namespace glint::app
