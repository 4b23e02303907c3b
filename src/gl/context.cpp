#include "gl/context.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <glad/gl.h>
#include <GLFW/glfw3.h>

#include <cstring>
#include <vector>

#include "glint/error.h"

namespace glint::gl {

namespace {

std::string eglErrorName(EGLint code) {
  switch (code) {
    case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS: return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
    case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER: return "EGL_BAD_PARAMETER";
    default: return "EGL error " + std::to_string(code);
  }
}

GLADapiproc eglLoader(const char* name) { return reinterpret_cast<GLADapiproc>(eglGetProcAddress(name)); }

// Initialises an EGL display that can make a surfaceless 4.5 core context: Mesa's surfaceless
// platform first (llvmpipe, no X), then the first EGL device (GPU drivers such as NVIDIA's).
EGLDisplay openDisplay(std::string& tried) {
  auto getPlatformDisplay =
      reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
  if (!getPlatformDisplay) {
    tried = "eglGetPlatformDisplayEXT is missing";
    return EGL_NO_DISPLAY;
  }
  const char* clientExtensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  const std::string extensions = clientExtensions ? clientExtensions : "";
  std::vector<EGLDisplay> candidates;
  if (extensions.find("EGL_MESA_platform_surfaceless") != std::string::npos) {
    candidates.push_back(getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr));
  }
  auto queryDevices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
  if (queryDevices && extensions.find("EGL_EXT_platform_device") != std::string::npos) {
    EGLDeviceEXT devices[8];
    EGLint count = 0;
    if (queryDevices(8, devices, &count)) {
      for (EGLint i = 0; i < count; ++i) {
        candidates.push_back(getPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr));
      }
    }
  }
  for (EGLDisplay display : candidates) {
    if (display == EGL_NO_DISPLAY) continue;
    EGLint major = 0;
    EGLint minor = 0;
    if (eglInitialize(display, &major, &minor)) return display;
    tried += (tried.empty() ? "" : ", ") + eglErrorName(eglGetError());
  }
  if (tried.empty()) tried = "no surfaceless or device EGL platform";
  return EGL_NO_DISPLAY;
}

}  // namespace

struct HeadlessContext::State {
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;
};

HeadlessContext::HeadlessContext() : state_(std::make_unique<State>()) {
  std::string tried;
  state_->display = openDisplay(tried);
  if (state_->display == EGL_NO_DISPLAY) throw Error("no OpenGL 4.5 context: cannot open an EGL display (" + tried + ")");
  auto fail = [this](const std::string& what) {
    const std::string message = "no OpenGL 4.5 context: " + what + " (" + eglErrorName(eglGetError()) + ")";
    eglTerminate(state_->display);
    return Error(message);
  };
  if (!eglBindAPI(EGL_OPENGL_API)) throw fail("eglBindAPI(OpenGL)");
  const EGLint configAttributes[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
  EGLConfig config;
  EGLint configs = 0;
  if (!eglChooseConfig(state_->display, configAttributes, &config, 1, &configs) || configs == 0) {
    throw fail("no EGL config for OpenGL");
  }
  const EGLint contextAttributes[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                                      EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
  state_->context = eglCreateContext(state_->display, config, EGL_NO_CONTEXT, contextAttributes);
  if (state_->context == EGL_NO_CONTEXT) throw fail("eglCreateContext(4.5 core)");
  if (!eglMakeCurrent(state_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, state_->context)) {
    eglDestroyContext(state_->display, state_->context);
    throw fail("eglMakeCurrent without a surface");
  }
  if (!gladLoadGL(eglLoader)) {
    eglDestroyContext(state_->display, state_->context);
    throw fail("loading OpenGL 4.5 functions");
  }
}

HeadlessContext::~HeadlessContext() {
  eglMakeCurrent(state_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  eglDestroyContext(state_->display, state_->context);
  eglTerminate(state_->display);
}

WindowContext::WindowContext(int width, int height, const std::string& title) {
  if (!glfwInit()) throw Error("no window: GLFW cannot initialise (is DISPLAY set? try xvfb-run)");
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
  if (!window_) {
    const char* description = nullptr;
    glfwGetError(&description);
    const std::string reason = description ? description : "unknown reason";
    glfwTerminate();
    throw Error("no window: cannot create an OpenGL 4.5 core window (" + reason + ")");
  }
  glfwMakeContextCurrent(window_);
  if (!gladLoadGL(glfwGetProcAddress)) {
    glfwDestroyWindow(window_);
    glfwTerminate();
    throw Error("no window: cannot load OpenGL 4.5 functions");
  }
}

WindowContext::~WindowContext() {
  glfwDestroyWindow(window_);
  glfwTerminate();
}

ContextInfo currentContextInfo() {
  ContextInfo info;
  const auto* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  const auto* version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
  info.renderer = renderer ? renderer : "unknown";
  info.version = version ? version : "unknown";
  info.softwareRasteriser =
      info.renderer.find("llvmpipe") != std::string::npos || info.renderer.find("softpipe") != std::string::npos;
  return info;
}

}  // namespace glint::gl
