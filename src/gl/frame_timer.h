// Frame times the way each driver can give them: GL_TIME_ELAPSED queries on GPU drivers; on Mesa
// llvmpipe, where those queries are meaningless (they time about one tile, and the first can
// return the machine's uptime), the wall clock around glFinish.
#pragma once

#include <functional>

#include <glad/gl.h>

namespace glint::gl {

class FrameTimer {
 public:
  // Uses timer queries unless the current context is a software rasteriser.
  FrameTimer();
  ~FrameTimer();
  FrameTimer(const FrameTimer&) = delete;
  FrameTimer& operator=(const FrameTimer&) = delete;

  // Runs `draw` and returns its time in milliseconds; waits for the GPU first, so earlier work
  // is not counted.
  double milliseconds(const std::function<void()>& draw);
  bool usesGpuQueries() const { return query_ != 0; }
  const char* method() const { return query_ ? "gpu-query" : "wall-finish"; }

 private:
  GLuint query_ = 0;
};

}  // namespace glint::gl
