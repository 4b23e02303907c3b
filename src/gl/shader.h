// GLSL programs built from the embedded sources (shaders/ and the kernel headers of
// src/glint/kernel, embedded at build time by cmake/embed_files.cmake).
#pragma once

#include <map>
#include <string>
#include <utility>
#include <vector>

#include <glad/gl.h>

namespace glint::gl {

// Every embedded file by name (no folders): "glint_brdf.h", "forward.frag", ...
const std::map<std::string, std::string>& embeddedFiles();

// The source of an embedded file with its `#include "name"` lines replaced by the named embedded
// files (recursively; the kernel's include guards work in GLSL too) and `#include <...>` lines,
// which only the C++ side of the kernel uses, removed. Throws Error for an unknown name.
std::string expandIncludes(const std::string& name);

class ShaderProgram {
 public:
  // Compiles and links the stages {type, embedded file name}; `defines` are prepended as
  // `#define NAME VALUE`. Throws Error with the first lines of the GL info log on failure.
  ShaderProgram(const std::vector<std::pair<GLenum, std::string>>& stages,
                const std::vector<std::pair<std::string, std::string>>& defines = {});
  ~ShaderProgram();
  ShaderProgram(ShaderProgram&& other) noexcept : id_(std::exchange(other.id_, 0)) {}
  ShaderProgram& operator=(ShaderProgram&& other) noexcept;
  ShaderProgram(const ShaderProgram&) = delete;
  ShaderProgram& operator=(const ShaderProgram&) = delete;

  GLuint id() const { return id_; }
  GLint uniform(const char* name) const { return glGetUniformLocation(id_, name); }

 private:
  GLuint id_ = 0;
};

}  // namespace glint::gl
