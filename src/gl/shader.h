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

// A stage's source with its `#include "name"` lines replaced by the named files (recursively; the
// kernel's include guards work in GLSL too) and `#include <...>` lines, which only the C++ side of
// the kernel uses, blanked out. `#line N S` directives keep the compiler's locations those of the
// files: source string S is files[S - 1] (0 is the version and defines ShaderProgram prepends),
// and its line n is numbered N = S * 100000 + n, so that a location names its file even where the
// compiler reports source string 0 for every error (Mesa).
struct ExpandedSource {
  std::string text;
  std::vector<std::string> files;
};

// Expands `name` from `sources` (every file by name). A file is written once, at its first include
// outside any conditional block but include guards; a later include of it is left out (its guard
// would make it empty). Throws Error for an unknown name or a file that includes itself.
ExpandedSource expandIncludes(const std::string& name,
                              const std::map<std::string, std::string>& sources = embeddedFiles());

// `name` expanded as it reads after `first` in the same program: the files `first` already wrote are
// left out. For a second include that a host puts after the first (`glint shader-bundle
// --extended-lights`).
ExpandedSource expandIncludesAfter(const std::string& first, const std::string& name,
                                   const std::map<std::string, std::string>& sources = embeddedFiles());

// A compiler's info log with its locations "S:N" (Mesa, ANGLE, glslang) and "S(N)" (NVIDIA)
// written as "file:n", the file and line of ExpandedSource's numbering (`files` its files).
std::string locateInFiles(const std::string& log, const std::vector<std::string>& files);

// One stage compiled from its whole text (version line included). Throws Error naming `name`,
// with the first line of the info log, its locations as file:line of `files` (ExpandedSource's).
GLuint compileStage(GLenum type, const std::string& source, const std::string& name,
                    const std::vector<std::string>& files = {});

// A program linked from compiled stages, which it deletes. Throws Error naming `name` with the
// first line of the info log.
GLuint linkProgram(const std::vector<GLuint>& stages, const std::string& name);

class ShaderProgram {
 public:
  // Compiles and links the stages {type, file name}, from the embedded files unless `sources` are
  // given; `defines` are prepended as `#define NAME VALUE`. Throws Error with the first lines of
  // the GL info log on failure, its locations as file:line.
  ShaderProgram(const std::vector<std::pair<GLenum, std::string>>& stages,
                const std::vector<std::pair<std::string, std::string>>& defines = {},
                const std::map<std::string, std::string>& sources = embeddedFiles());
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
