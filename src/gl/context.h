// OpenGL 4.5 core contexts: headless through EGL (Mesa llvmpipe surfaceless, or a GPU driver's
// EGL device) and windowed through GLFW. Creating one makes it current and loads GL with glad.
#pragma once

#include <memory>
#include <string>

struct GLFWwindow;

namespace glint::gl {

// What the current context runs on, from GL_RENDERER / GL_VERSION.
struct ContextInfo {
  std::string renderer;
  std::string version;
  bool softwareRasteriser;  // llvmpipe / softpipe: GPU timer queries are meaningless there
};
ContextInfo currentContextInfo();

class HeadlessContext {
 public:
  // Throws glint::Error with one line ("no OpenGL 4.5 context: ...") when none can be made.
  HeadlessContext();
  ~HeadlessContext();
  HeadlessContext(const HeadlessContext&) = delete;
  HeadlessContext& operator=(const HeadlessContext&) = delete;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

class WindowContext {
 public:
  // Throws glint::Error when there is no display or no 4.5 context.
  WindowContext(int width, int height, const std::string& title);
  ~WindowContext();
  WindowContext(const WindowContext&) = delete;
  WindowContext& operator=(const WindowContext&) = delete;
  GLFWwindow* window() const { return window_; }

 private:
  GLFWwindow* window_ = nullptr;
};

}  // namespace glint::gl
