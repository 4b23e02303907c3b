// An OpenGL 4.5 program that shades a glinty sphere with glint's installed GLSL kernel
// (find_package(glint)), headless through EGL, to an EXR or PNG image:
//
//   glint_opengl OUTPUT.{png,exr} [--dictionary FILE] [--size N]
//
// --dictionary reads a file written by `glint dict` (glint::Dictionary::load); without it the
// dictionary is generated at start (the same default parameters). The EXR holds linear radiance;
// the PNG the same values encoded as sRGB, clamped to 1.
//
// The scene is `glint render sphere`'s (glint's built-in sphere: the mesh, camera, light, sky and
// material below), so that the install test can compare the two images pixel by pixel.
//
// How a host renderer brings glint's kernel into its own OpenGL program:
//   - GLSL: sphere.frag includes glint_kernel.h from glint's installed shader folder
//     (glint_SHADER_DIR), made named strings of GL_ARB_shading_language_include here, and defines
//     the kernel's dictionary hook over a storage buffer of the dictionary's texels.
//   - The glint layer's material: a glint::kernel::GlintMaterial filled in C++ is the std140 block
//     the shader reads, byte for byte (kernel/glint_material.h).
//   - The footprint: the glint uv's screen derivatives, dFdx and dFdy in the fragment shader.
//   - OpenGL functions through libepoxy, which also dispatches EGL.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <epoxy/egl.h>
#include <epoxy/gl.h>
#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <glint/dictionary.h>
#include <glint/error.h>
#include <glint/image_io.h>
#include <glint/kernel/glint_material.h>

namespace {

using glm::vec2;
using glm::vec3;
using glm::vec4;

// glint's built-in sphere scene: a unit sphere at the origin seen from +z (it spans 70% of the
// frame's height), a point light up and to the right of the camera, a dim uniform sky.
constexpr vec3 kCameraPosition{0.0f, 0.0f, 3.6f};
constexpr float kVerticalFovDegrees = 45.0f;
constexpr vec3 kLightPosition{3.0f, 3.0f, 5.0f};
constexpr vec3 kLightIntensity{60.0f};  // W/sr
constexpr vec3 kSkyRadiance{0.02f};
constexpr vec3 kBaseColour{0.6f, 0.05f, 0.05f};  // the Lambertian part; the specular is the glint layer

// The glint layer: alpha 0.5 (Beckmann, V-cavity: the 2020 paper's), e^13 microfacets per unit of
// glint uv, the glint uv four times the mesh's, glint's other defaults.
glint::kernel::GlintMaterial glintLayer() {
  glint::kernel::GlintMaterial m{};  // zero padding
  m.alpha = vec2(0.5f);
  m.rho = 0.0f;
  m.logDensity = 13.0f;
  m.relativeArea = 1.0f;
  m.densityRandomisation = 2.0f;
  m.maxAnisotropy = 8.0f;
  m.patternSeed = 0;
  m.logDensityRange = vec2(15.0f, 35.0f);  // unused: no log-density texture
  m.uvScale = 4.0f;
  m.hasLogDensityTexture = 0;
  m.ndf = glint::kernel::GLINT_NDF_BECKMANN;
  m.masking = glint::kernel::GLINT_MASKING_VCAVITY;
  m.lod = glint::kernel::GLINT_LOD_PAPER;
  m.colouredCells = 0;
  m.multipleScattering = 0;
  m.enabled = 1;
  return m;
}

struct Vertex {
  vec3 position;
  vec3 normal;
  vec4 tangent;  // xyz along increasing u, w the bitangent's sign
  vec2 uv;
};

struct Mesh {
  std::vector<Vertex> vertices;
  std::vector<std::uint32_t> indices;
};

// A UV sphere of `segments` x `rings` quads: uv = (phi / 2 pi, theta / pi), theta from the +y pole,
// phi = 0 at +z growing towards +x; two triangles a quad, those with a corner at a pole dropped
// where two corners coincide. Each vertex's tangent is the area-weighted mean of its triangles'
// dp/du made perpendicular to the normal. These are the mesh and tangents of glint's built-in
// sphere, vertex for vertex, so that both programs rasterise the same triangles.
Mesh uvSphere(int segments, int rings) {
  constexpr float kTwoPi = 2.0f * std::numbers::pi_v<float>;
  Mesh mesh;
  for (int j = 0; j <= rings; ++j) {
    const float t = static_cast<float>(j) / static_cast<float>(rings);
    for (int i = 0; i <= segments; ++i) {
      const float s = static_cast<float>(i) / static_cast<float>(segments);
      const float phi = kTwoPi * s;
      const float theta = std::numbers::pi_v<float> * t;
      const float sinTheta = (t <= 0.0f || t >= 1.0f) ? 0.0f : std::sin(theta);  // the poles' exact zeros
      const vec3 direction(sinTheta * std::sin(phi), std::cos(theta), sinTheta * std::cos(phi));
      mesh.vertices.push_back({direction, glm::normalize(direction), vec4(0.0f), vec2(s, t)});
    }
  }
  auto at = [segments](int i, int j) { return static_cast<std::uint32_t>(j * (segments + 1) + i); };
  auto addTriangle = [&mesh](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    const Vertex &va = mesh.vertices[a], &vb = mesh.vertices[b], &vc = mesh.vertices[c];
    if (va.position == vb.position || vb.position == vc.position || vc.position == va.position) return;
    // Counter-clockwise seen from outside: the front faces.
    const vec3 geometric = glm::cross(vb.position - va.position, vc.position - va.position);
    if (glm::dot(geometric, va.normal + vb.normal + vc.normal) < 0.0f) std::swap(b, c);
    mesh.indices.insert(mesh.indices.end(), {a, b, c});
  };
  for (int j = 0; j < rings; ++j) {
    for (int i = 0; i < segments; ++i) {
      addTriangle(at(i, j), at(i + 1, j), at(i + 1, j + 1));
      addTriangle(at(i, j), at(i + 1, j + 1), at(i, j + 1));
    }
  }
  // dp/du and dp/dv of each triangle, from [e1 e2] = [dp/du dp/dv] [d1 d2], summed per vertex by area.
  std::vector<vec3> dpdu(mesh.vertices.size(), vec3(0.0f)), dpdv(mesh.vertices.size(), vec3(0.0f));
  for (std::size_t k = 0; k < mesh.indices.size(); k += 3) {
    const std::uint32_t corner[3] = {mesh.indices[k], mesh.indices[k + 1], mesh.indices[k + 2]};
    const Vertex &v0 = mesh.vertices[corner[0]], &v1 = mesh.vertices[corner[1]], &v2 = mesh.vertices[corner[2]];
    const vec3 e1 = v1.position - v0.position, e2 = v2.position - v0.position;
    const vec2 d1 = v1.uv - v0.uv, d2 = v2.uv - v0.uv;
    const float det = d1.x * d2.y - d2.x * d1.y;
    const vec3 du = (e1 * d2.y - e2 * d1.y) / det;
    const vec3 dv = (e2 * d1.x - e1 * d2.x) / det;
    const float area = 0.5f * glm::length(glm::cross(e1, e2));
    for (std::uint32_t c : corner) {
      dpdu[c] += du * area;
      dpdv[c] += dv * area;
    }
  }
  for (std::size_t k = 0; k < mesh.vertices.size(); ++k) {
    Vertex& v = mesh.vertices[k];
    vec3 t = dpdu[k] - v.normal * glm::dot(v.normal, dpdu[k]);
    t /= std::sqrt(glm::dot(t, t));
    // glTF's handedness: the bitangent cross(n, t) * w points towards decreasing v.
    v.tangent = vec4(t, glm::dot(glm::cross(v.normal, t), -dpdv[k]) < 0.0f ? -1.0f : 1.0f);
  }
  return mesh;
}

std::string readText(const std::filesystem::path& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw glint::Error(path.string() + ": cannot read the file");
  std::ostringstream text;
  text << file.rdbuf();
  return text.str();
}

// A headless OpenGL 4.5 core context, current while this lives: EGL's surfaceless platform (Mesa,
// llvmpipe included, no X), else the first EGL device (a GPU driver's), as glint's renderer does.
class HeadlessContext {
 public:
  HeadlessContext() {
    std::vector<EGLDisplay> candidates;
    if (epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_MESA_platform_surfaceless")) {
      candidates.push_back(eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr));
    }
    if (epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_EXT_platform_device")) {
      EGLDeviceEXT device;
      EGLint count = 0;
      if (eglQueryDevicesEXT(1, &device, &count) && count > 0) {
        candidates.push_back(eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, device, nullptr));
      }
    }
    for (EGLDisplay display : candidates) {
      if (display != EGL_NO_DISPLAY && eglInitialize(display, nullptr, nullptr)) {
        display_ = display;
        break;
      }
    }
    if (display_ == EGL_NO_DISPLAY) throw glint::Error("no OpenGL: no surfaceless or device EGL display");
    const EGLint configAttributes[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT,
                                       EGL_NONE};
    const EGLint contextAttributes[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                                        EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
    EGLConfig config;
    EGLint configs = 0;
    if (!eglBindAPI(EGL_OPENGL_API) || !eglChooseConfig(display_, configAttributes, &config, 1, &configs) ||
        configs == 0 ||
        (context_ = eglCreateContext(display_, config, EGL_NO_CONTEXT, contextAttributes)) == EGL_NO_CONTEXT ||
        !eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_)) {
      eglTerminate(display_);
      throw glint::Error("no OpenGL: EGL cannot make a surfaceless OpenGL 4.5 core context");
    }
  }
  ~HeadlessContext() {
    eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(display_, context_);
    eglTerminate(display_);
  }
  HeadlessContext(const HeadlessContext&) = delete;
  HeadlessContext& operator=(const HeadlessContext&) = delete;

 private:
  EGLDisplay display_ = EGL_NO_DISPLAY;
  EGLContext context_ = EGL_NO_CONTEXT;
};

// Makes every kernel header of glint's installed shader folder the named string /glint/NAME, so
// that `#include "glint_kernel.h"` and the kernel's own includes resolve with /glint as the path.
void registerGlintHeaders(const std::filesystem::path& shaderDir) {
  if (!epoxy_has_gl_extension("GL_ARB_shading_language_include")) {
    throw glint::Error("this OpenGL has no GL_ARB_shading_language_include, which resolves the shaders' #include");
  }
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(shaderDir)) {
    if (entry.path().extension() != ".h") continue;
    const std::string name = "/glint/" + entry.path().filename().string();
    const std::string text = readText(entry.path());
    glNamedStringARB(GL_SHADER_INCLUDE_ARB, -1, name.c_str(), static_cast<GLint>(text.size()), text.c_str());
    ++count;
  }
  if (count == 0) throw glint::Error(shaderDir.string() + ": no kernel headers (*.h) in glint's shader folder");
}

GLuint compileShader(GLenum stage, const std::filesystem::path& path) {
  const std::string text = readText(path);
  const char* source = text.c_str();
  const char* includePath = "/glint";
  const GLuint shader = glCreateShader(stage);
  glShaderSource(shader, 1, &source, nullptr);
  glCompileShaderIncludeARB(shader, 1, &includePath, nullptr);
  GLint ok = GL_FALSE;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[4096] = {};
    glGetShaderInfoLog(shader, sizeof log, nullptr, log);
    throw glint::Error(path.string() + ": does not compile:\n" + log);
  }
  return shader;
}

GLuint linkProgram(const std::filesystem::path& vertex, const std::filesystem::path& fragment) {
  const GLuint program = glCreateProgram();
  const GLuint shaders[2] = {compileShader(GL_VERTEX_SHADER, vertex), compileShader(GL_FRAGMENT_SHADER, fragment)};
  for (GLuint shader : shaders) glAttachShader(program, shader);
  glLinkProgram(program);
  for (GLuint shader : shaders) glDeleteShader(shader);
  GLint ok = GL_FALSE;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[4096] = {};
    glGetProgramInfoLog(program, sizeof log, nullptr, log);
    throw glint::Error(fragment.string() + ": does not link:\n" + log);
  }
  return program;
}

struct Options {
  std::string output;
  std::string dictionary;
  int size = 256;
};

int run(const Options& options) {
  const glint::Dictionary dictionary = options.dictionary.empty()
                                           ? glint::generateDictionary(glint::DictionaryParameters{})
                                           : glint::Dictionary::load(options.dictionary);
  const Mesh sphere = uvSphere(128, 64);
  HeadlessContext context;
  registerGlintHeaders(GLINT_INSTALLED_SHADER_DIR);
  const std::filesystem::path exampleShaders = EXAMPLE_SHADER_DIR;
  const GLuint program = linkProgram(exampleShaders / "sphere.vert", exampleShaders / "sphere.frag");

  // The sphere's vertices, attributes 0 to 3 as sphere.vert declares them.
  GLuint buffers[4];  // vertices, indices, material, dictionary
  glCreateBuffers(4, buffers);
  glNamedBufferStorage(buffers[0], static_cast<GLsizeiptr>(sphere.vertices.size() * sizeof(Vertex)),
                       sphere.vertices.data(), 0);
  glNamedBufferStorage(buffers[1], static_cast<GLsizeiptr>(sphere.indices.size() * sizeof(std::uint32_t)),
                       sphere.indices.data(), 0);
  GLuint vertexArray;
  glCreateVertexArrays(1, &vertexArray);
  glVertexArrayVertexBuffer(vertexArray, 0, buffers[0], 0, sizeof(Vertex));
  glVertexArrayElementBuffer(vertexArray, buffers[1]);
  const struct { GLint size; GLuint offset; } attributes[] = {
      {3, offsetof(Vertex, position)}, {3, offsetof(Vertex, normal)},
      {4, offsetof(Vertex, tangent)},  {2, offsetof(Vertex, uv)}};
  for (GLuint location = 0; location < 4; ++location) {
    glEnableVertexArrayAttrib(vertexArray, location);
    glVertexArrayAttribFormat(vertexArray, location, attributes[location].size, GL_FLOAT, GL_FALSE,
                              attributes[location].offset);
    glVertexArrayAttribBinding(vertexArray, location, 0);
  }

  // The glint layer (uniform block 0) and the dictionary's texels (storage buffer 0).
  const glint::kernel::GlintMaterial material = glintLayer();
  glNamedBufferStorage(buffers[2], sizeof material, &material, 0);
  glBindBufferBase(GL_UNIFORM_BUFFER, 0, buffers[2]);
  const auto texels = dictionary.texels();
  glNamedBufferStorage(buffers[3], static_cast<GLsizeiptr>(texels.size_bytes()), texels.data(), 0);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, buffers[3]);

  const int size = options.size;
  // The near and far planes change only the depth: clip x, y and w, and so the image, are those of
  // glint's renderer, whose planes fit the scene's bounds.
  const glm::mat4 viewProjection = glm::perspective(glm::radians(kVerticalFovDegrees), 1.0f, 1.0f, 10.0f) *
                                   glm::lookAt(kCameraPosition, vec3(0.0f), vec3(0, 1, 0));
  const glint::DictionaryParameters& shape = dictionary.parameters();
  auto uniform = [program](const char* name) { return glGetUniformLocation(program, name); };
  glProgramUniformMatrix4fv(program, uniform("uViewProjection"), 1, GL_FALSE, &viewProjection[0][0]);
  glProgramUniform3fv(program, uniform("uCameraPosition"), 1, &kCameraPosition.x);
  glProgramUniform3fv(program, uniform("uLightPosition"), 1, &kLightPosition.x);
  glProgramUniform3fv(program, uniform("uLightIntensity"), 1, &kLightIntensity.x);
  glProgramUniform3fv(program, uniform("uSkyRadiance"), 1, &kSkyRadiance.x);
  glProgramUniform3fv(program, uniform("uBaseColour"), 1, &kBaseColour.x);
  glProgramUniform3i(program, uniform("uGlintDictionaryShape"), shape.numLevels, shape.numDistributions,
                     shape.texelsPerDistribution);
  glProgramUniform1f(program, uniform("uGlintDictionaryAlpha"), shape.alpha);

  // A float render target: radiance, linear, unclamped.
  GLuint renderbuffers[2];
  glCreateRenderbuffers(2, renderbuffers);
  glNamedRenderbufferStorage(renderbuffers[0], GL_RGBA32F, size, size);
  glNamedRenderbufferStorage(renderbuffers[1], GL_DEPTH_COMPONENT24, size, size);
  GLuint framebuffer;
  glCreateFramebuffers(1, &framebuffer);
  glNamedFramebufferRenderbuffer(framebuffer, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, renderbuffers[0]);
  glNamedFramebufferRenderbuffer(framebuffer, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, renderbuffers[1]);
  if (glCheckNamedFramebufferStatus(framebuffer, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
    throw glint::Error("OpenGL cannot render to an RGBA32F target");
  }

  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
  glViewport(0, 0, size, size);
  const vec4 sky(kSkyRadiance, 1.0f);  // the background: the sky seen directly
  glClearNamedFramebufferfv(framebuffer, GL_COLOR, 0, &sky.x);
  const float farthest = 1.0f;
  glClearNamedFramebufferfv(framebuffer, GL_DEPTH, 0, &farthest);
  glEnable(GL_DEPTH_TEST);
  glEnable(GL_CULL_FACE);
  glUseProgram(program);
  glBindVertexArray(vertexArray);
  glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(sphere.indices.size()), GL_UNSIGNED_INT, nullptr);
  std::vector<float> rgba(static_cast<std::size_t>(size) * size * 4);
  glReadPixels(0, 0, size, size, GL_RGBA, GL_FLOAT, rgba.data());
  if (const GLenum error = glGetError(); error != GL_NO_ERROR) {
    throw glint::Error("OpenGL error " + std::to_string(error) + " while rendering");
  }
  glint::writeImage(options.output, glint::fromRgbaFloat(size, size, rgba.data(), true));  // GL's rows run bottom up
  std::fprintf(stderr, "glint_opengl: wrote %s (%dx%d, %s)\n", options.output.c_str(), size, size,
               reinterpret_cast<const char*>(glGetString(GL_RENDERER)));
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const char* usage = "usage: glint_opengl OUTPUT.{png,exr} [--dictionary FILE] [--size N]";
  Options options;
  try {
    for (int i = 1; i < argc; ++i) {
      const std::string argument = argv[i];
      auto value = [&]() -> std::string {
        if (i + 1 >= argc) throw glint::Error(argument + " needs a value");
        return argv[++i];
      };
      if (argument == "-h" || argument == "--help") {
        std::printf("%s\n", usage);
        return 0;
      } else if (argument == "--dictionary") {
        options.dictionary = value();
      } else if (argument == "--size") {
        const std::string text = value();
        char* end = nullptr;
        const long n = std::strtol(text.c_str(), &end, 10);
        if (text.empty() || *end != '\0' || n < 8 || n > 4096) {
          throw glint::Error("--size must be a whole number in [8, 4096], got '" + text + "'");
        }
        options.size = static_cast<int>(n);
      } else if (argument[0] != '-' && options.output.empty()) {
        options.output = argument;
      } else {
        throw glint::Error("unknown argument '" + argument + "'");
      }
    }
    if (options.output.empty()) throw glint::Error(usage);
    glint::requireImageExtension(options.output);  // before the work, not after it
    return run(options);
  } catch (const glint::Error& e) {
    std::fprintf(stderr, "glint_opengl: error: %s\n", e.what());
    return 1;
  }
}
