// The page's renderer (web/page/glint.js calls these): the desktop renderer of src/gl/ on a WebGL2
// canvas, the built-in scenes and the glTF loader of src/scene/, the dictionary in glint's own
// file format. Every function returns 0 on success and -1 on failure, with glint_error() saying
// why in one line; a failure leaves the page's scene and settings as they were.
#include <emscripten/emscripten.h>
#include <emscripten/html5.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "gl/dictionary_texture.h"
#include "gl/display.h"
#include "gl/renderer.h"
#include "gl/shader.h"
#include "glint/dictionary.h"
#include "glint/error.h"
#include "scene/builtin_scenes.h"
#include "scene/camera_moves.h"
#include "scene/gltf_loader.h"
#include "scene/view_controls.h"

using namespace glint;

namespace {

struct Page {
  std::optional<Dictionary> dictionary;
  // The scene and its renderer are replaced together; the renderer keeps a reference to the scene.
  std::unique_ptr<scene::Scene> scene;
  std::unique_ptr<gl::Renderer> renderer;
  std::unique_ptr<gl::DisplayPass> display;
  scene::ViewControls controls;
  glm::vec3 pivot{0.0f};
  // WebGL2 has no cube-map arrays for the point lights' shadow maps: the page draws no shadows.
  gl::FrameSettings frame = [] {
    gl::FrameSettings settings;
    settings.shadows = false;
    return settings;
  }();
  float exposure = 1.0f;  // the page's multiplier of the scene's exposure
};

Page page;
std::string lastError;

// Runs `step`, turning an exception into -1 and the message glint_error() returns.
template <typename Step>
int guarded(Step step) {
  try {
    step();
    return 0;
  } catch (const std::exception& e) {
    lastError = e.what();
  } catch (...) {
    lastError = "unknown error";
  }
  return -1;
}

void requireScene() {
  if (!page.renderer) throw Error("no scene loaded");
}

// Makes `loaded` the page's scene, with its default camera; the previous scene stays if the
// renderer cannot be made (a shader or texture that this WebGL refuses).
void showScene(scene::Scene loaded) {
  if (!page.dictionary) throw Error("the dictionary is not loaded");
  auto next = std::make_unique<scene::Scene>(std::move(loaded));
  auto renderer = std::make_unique<gl::Renderer>(*next, *page.dictionary);
  page.renderer = std::move(renderer);
  page.scene = std::move(next);
  page.pivot = scene::lightPivot(*page.scene);
  page.controls = scene::viewControls(*page.scene, page.pivot);
  page.frame.camera = page.scene->cameras.at("default");
}

std::span<const std::byte> bytesOf(const std::uint8_t* data, int size) {
  return {reinterpret_cast<const std::byte*>(data), static_cast<std::size_t>(std::max(size, 0))};
}

// OpenGL errors raised since the last call, as one line (none: empty).
std::string glErrors() {
  std::string errors;
  for (GLenum e = glGetError(); e != GL_NO_ERROR; e = glGetError()) {
    errors += (errors.empty() ? "" : ", ") + std::to_string(e);
  }
  return errors;
}

}  // namespace

extern "C" {

EMSCRIPTEN_KEEPALIVE const char* glint_error() { return lastError.c_str(); }

// A WebGL2 context on the canvas of this CSS selector, with float render targets and filtering.
EMSCRIPTEN_KEEPALIVE int glint_start(const char* canvas) {
  return guarded([&] {
    EmscriptenWebGLContextAttributes attributes;
    emscripten_webgl_init_context_attributes(&attributes);
    attributes.majorVersion = 2;
    attributes.minorVersion = 0;
    attributes.alpha = false;
    attributes.depth = false;  // the renderer draws into its own target
    attributes.stencil = false;
    attributes.antialias = false;
    attributes.preserveDrawingBuffer = true;  // screenshots and read-backs of the last frame
    const EMSCRIPTEN_WEBGL_CONTEXT_HANDLE context = emscripten_webgl_create_context(canvas, &attributes);
    if (context <= 0) throw Error("this browser gives no WebGL2 context");
    emscripten_webgl_make_context_current(context);
    for (const char* extension : {"EXT_color_buffer_float", "OES_texture_float_linear"}) {
      if (!emscripten_webgl_enable_extension(context, extension)) {
        throw Error(std::string("this browser's WebGL2 lacks ") + extension + " (float render targets and filtering)");
      }
    }
    page.display = std::make_unique<gl::DisplayPass>();
  });
}

// A dictionary file written by `glint dict` (docs/dictionary.md, "File format").
EMSCRIPTEN_KEEPALIVE int glint_load_dictionary(const std::uint8_t* data, int size) {
  return guarded([&] { page.dictionary = Dictionary::deserialise(bytesOf(data, size), "dictionary"); });
}

EMSCRIPTEN_KEEPALIVE int glint_load_builtin(const char* name) {
  return guarded([&] { showScene(scene::makeBuiltinScene(name)); });
}

// A .glb, or a .gltf whose buffers and images are data URIs (a dropped file comes alone).
EMSCRIPTEN_KEEPALIVE int glint_load_gltf(const std::uint8_t* data, int size, const char* name) {
  return guarded([&] { showScene(scene::loadGltf(bytesOf(data, size), name, "")); });
}

// Draws a frame of the scene into the canvas, `width` x `height` pixels.
EMSCRIPTEN_KEEPALIVE int glint_render(int width, int height) {
  return guarded([&] {
    requireScene();
    scene::applyViewControls(*page.scene, page.controls, page.pivot, page.renderer->materials(),
                             page.renderer->lights());
    page.frame.width = width;
    page.frame.height = height;
    page.renderer->renderFrame(page.frame);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    page.display->draw(page.renderer->radianceTexture(), page.scene->exposure * page.exposure, width, height);
    const std::string errors = glErrors();
    if (!errors.empty()) throw Error("WebGL error " + errors + " while drawing the frame");
  });
}

// Waits until the GPU has drawn the frame (the page times frames around it): reading a pixel back
// waits for every command before it, where glFinish may return at once in a browser.
EMSCRIPTEN_KEEPALIVE void glint_finish() {
  std::uint8_t pixel[4];
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glReadPixels(0, 0, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, pixel);
}

// The last frame's pixels, RGBA, rows from the top: width * height * 4 bytes into `out`.
EMSCRIPTEN_KEEPALIVE int glint_read_frame(std::uint8_t* out) {
  return guarded([&] {
    requireScene();
    const int w = page.frame.width;
    const int h = page.frame.height;
    std::vector<std::uint8_t> rows(static_cast<std::size_t>(w) * h * 4);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, rows.data());
    for (int y = 0; y < h; ++y) {
      std::copy_n(rows.data() + static_cast<std::size_t>(h - 1 - y) * w * 4, static_cast<std::size_t>(w) * 4,
                  out + static_cast<std::size_t>(y) * w * 4);
    }
  });
}

// Frame settings: the BRDF (glint, cook-torrance, zirr-kaplanyan), the anti-aliasing (none, ggaa,
// ggaa+lean), the exposure multiplier.
EMSCRIPTEN_KEEPALIVE int glint_set_brdf(const char* name) {
  return guarded([&] { page.frame.brdf = specularModelFromName(name); });
}
EMSCRIPTEN_KEEPALIVE int glint_set_antialiasing(const char* name) {
  return guarded([&] { page.frame.antiAliasing = gl::antiAliasingFromString(name); });
}
EMSCRIPTEN_KEEPALIVE void glint_set_exposure(float exposure) { page.exposure = exposure; }
// A cost tier (gl::qualityPresets, `glint render --quality`): its footprint policy, anti-aliasing
// and shadow cascades.
EMSCRIPTEN_KEEPALIVE int glint_set_quality(const char* name) {
  return guarded([&] {
    const gl::QualityPreset& preset = gl::qualityPreset(name);
    page.frame.footprintPolicy = footprintPolicyFromString(preset.footprint);
    page.frame.antiAliasing = preset.antiAliasing;
    page.frame.shadowCascades = preset.shadowCascades;
  });
}
// The anti-aliasing mode the frame is drawn with, as --aa names it.
EMSCRIPTEN_KEEPALIVE const char* glint_antialiasing() { return gl::toString(page.frame.antiAliasing); }

// The scene's materials with a glint layer, as the desktop viewer lists them: the index of the
// k-th one, -1 past the last.
EMSCRIPTEN_KEEPALIVE int glint_glint_material(int k) {
  if (!page.scene) return -1;
  for (std::size_t i = 0; i < page.scene->materials.size(); ++i) {
    if (page.scene->materials[i].glint.enabled && k-- == 0) return static_cast<int>(i);
  }
  return -1;
}
EMSCRIPTEN_KEEPALIVE const char* glint_material_name(int material) {
  static std::string name;
  name = page.scene ? page.scene->materials.at(static_cast<std::size_t>(material)).name : "";
  return name.c_str();
}
// Material controls (scene/view_controls.h): 0 alpha x, 1 alpha y, 2 rho, 3 log density, 4 relative area.
EMSCRIPTEN_KEEPALIVE float glint_get_material(int material, int field) {
  const scene::MaterialControls& m = page.controls.materials.at(static_cast<std::size_t>(material));
  const float values[] = {m.alpha.x, m.alpha.y, m.rho, m.logDensity, m.relativeArea};
  return values[std::clamp(field, 0, 4)];
}
EMSCRIPTEN_KEEPALIVE void glint_set_material(int material, int field, float value) {
  scene::MaterialControls& m = page.controls.materials.at(static_cast<std::size_t>(material));
  float* fields[] = {&m.alpha.x, &m.alpha.y, &m.rho, &m.logDensity, &m.relativeArea};
  *fields[std::clamp(field, 0, 4)] = value;
}
EMSCRIPTEN_KEEPALIVE int glint_light_count() { return page.scene ? static_cast<int>(page.controls.lights.size()) : 0; }
// Light controls: 0 azimuth, 1 elevation (radians), 2 strength.
EMSCRIPTEN_KEEPALIVE float glint_get_light(int light, int field) {
  const scene::LightControls& l = page.controls.lights.at(static_cast<std::size_t>(light));
  const float values[] = {l.azimuth, l.elevation, l.strength};
  return values[std::clamp(field, 0, 2)];
}
EMSCRIPTEN_KEEPALIVE void glint_set_light(int light, int field, float value) {
  scene::LightControls& l = page.controls.lights.at(static_cast<std::size_t>(light));
  float* fields[] = {&l.azimuth, &l.elevation, &l.strength};
  *fields[std::clamp(field, 0, 2)] = value;
}

// Camera moves of the desktop viewer (scene/camera_moves.h): orbit by angles in radians, zoom by
// a factor of the distance; reset to the scene's default camera.
EMSCRIPTEN_KEEPALIVE void glint_orbit(float yaw, float pitch) {
  page.frame.camera = scene::orbitCamera(page.frame.camera, yaw, pitch);
}
EMSCRIPTEN_KEEPALIVE void glint_zoom(float factor) { page.frame.camera = scene::zoomCamera(page.frame.camera, factor); }
EMSCRIPTEN_KEEPALIVE void glint_reset_camera() {
  if (page.scene) page.frame.camera = page.scene->cameras.at("default");
}

// The WebGL2 half of the CPU-versus-GPU kernel test: `count` cases of eight vec4s each (the layout
// of shaders/kernel_eval.glsl's KernelInput) evaluated by shaders/kernel_eval.frag, one per pixel
// of an RGBA32F target, into `out` (four floats a case: f, D, P22, Cook-Torrance f). With
// `filtered` the P-SDF is the anti-aliased one.
EMSCRIPTEN_KEEPALIVE int glint_evaluate_kernel(const float* inputs, int count, int filtered, float* out) {
  return guarded([&] {
    if (!page.dictionary) throw Error("the dictionary is not loaded");
    constexpr int kCasesPerRow = 256;
    const int rows = (count + kCasesPerRow - 1) / kCasesPerRow;
    std::vector<float> padded(static_cast<std::size_t>(rows) * kCasesPerRow * 32, 0.0f);
    std::copy_n(inputs, static_cast<std::size_t>(count) * 32, padded.data());
    gl::ShaderProgram program({{GL_VERTEX_SHADER, "fullscreen.vert"}, {GL_FRAGMENT_SHADER, "kernel_eval.frag"}},
                              {{"GLINT_FILTERED", filtered ? "1" : "0"}});
    gl::DictionaryTexture dictionary(*page.dictionary);
    GLuint input = 0;
    GLuint target = 0;
    GLuint framebuffer = 0;
    GLuint vertexArray = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &input);
    glTextureStorage2D(input, 1, GL_RGBA32F, 8 * kCasesPerRow, rows);
    glTextureSubImage2D(input, 0, 0, 0, 8 * kCasesPerRow, rows, GL_RGBA, GL_FLOAT, padded.data());
    glCreateTextures(GL_TEXTURE_2D, 1, &target);
    glTextureStorage2D(target, 1, GL_RGBA32F, kCasesPerRow, rows);
    glCreateFramebuffers(1, &framebuffer);
    glNamedFramebufferTexture(framebuffer, GL_COLOR_ATTACHMENT0, target, 0);
    glCreateVertexArrays(1, &vertexArray);
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    glViewport(0, 0, kCasesPerRow, rows);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_STENCIL_TEST);
    glUseProgram(program.id());
    dictionary.bind(program);
    glBindTextureUnit(1, input);
    glBindVertexArray(vertexArray);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    std::vector<float> values(static_cast<std::size_t>(rows) * kCasesPerRow * 4);
    glReadPixels(0, 0, kCasesPerRow, rows, GL_RGBA, GL_FLOAT, values.data());
    std::copy_n(values.data(), static_cast<std::size_t>(count) * 4, out);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDeleteVertexArrays(1, &vertexArray);
    glDeleteFramebuffers(1, &framebuffer);
    glDeleteTextures(1, &target);
    glDeleteTextures(1, &input);
    const std::string errors = glErrors();
    if (!errors.empty()) throw Error("WebGL error " + errors + " while evaluating the kernel");
  });
}

}  // extern "C"
