#include "gl/frame_timer.h"

#include <chrono>

#include "gl/context.h"

namespace glint::gl {

FrameTimer::FrameTimer() {
  if (!currentContextInfo().softwareRasteriser) glCreateQueries(GL_TIME_ELAPSED, 1, &query_);
}

FrameTimer::~FrameTimer() {
  if (query_) glDeleteQueries(1, &query_);
}

double FrameTimer::milliseconds(const std::function<void()>& draw) {
  glFinish();
  if (query_) {
    glBeginQuery(GL_TIME_ELAPSED, query_);
    draw();
    glEndQuery(GL_TIME_ELAPSED);
    GLuint64 nanoseconds = 0;
    glGetQueryObjectui64v(query_, GL_QUERY_RESULT, &nanoseconds);
    return static_cast<double>(nanoseconds) * 1e-6;
  }
  const auto start = std::chrono::steady_clock::now();
  draw();
  glFinish();
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace glint::gl
