// One headless OpenGL 4.5 context for the whole test process (Mesa llvmpipe through EGL here and
// in CI): creating one per test would cost more than most tests.
#pragma once

#include <functional>
#include <vector>

#include <glad/gl.h>
#include <gtest/gtest.h>

#include "gl/shader.h"

namespace glint::test {

// Makes the shared context current (creating it on first use); throws glint::Error when no
// OpenGL 4.5 context can be made.
void useGlContext();

// Runs a test compute shader (local size 64, uniform uCount, inputs in the shader storage buffer
// at binding 0, one Output per input at binding 1) over `inputs`; `prepare` sets the program's
// other uniforms and textures once it is in use.
template <typename Output, typename Input>
std::vector<Output> dispatchCompute(const gl::ShaderProgram& program, const std::vector<Input>& inputs,
                                    const std::function<void()>& prepare = {}) {
  GLuint buffers[2];
  glCreateBuffers(2, buffers);
  glNamedBufferStorage(buffers[0], static_cast<GLsizeiptr>(inputs.size() * sizeof(Input)), inputs.data(), 0);
  glNamedBufferStorage(buffers[1], static_cast<GLsizeiptr>(inputs.size() * sizeof(Output)), nullptr, GL_MAP_READ_BIT);
  glUseProgram(program.id());
  if (prepare) prepare();
  glUniform1ui(program.uniform("uCount"), static_cast<GLuint>(inputs.size()));
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, buffers[0]);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, buffers[1]);
  glDispatchCompute(static_cast<GLuint>((inputs.size() + 63) / 64), 1, 1);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  std::vector<Output> outputs(inputs.size());
  glGetNamedBufferSubData(buffers[1], 0, static_cast<GLsizeiptr>(outputs.size() * sizeof(Output)), outputs.data());
  glDeleteBuffers(2, buffers);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  return outputs;
}

}  // namespace glint::test
