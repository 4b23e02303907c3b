#include "gl/shader.h"

#include <regex>
#include <set>
#include <sstream>

#include "glint/error.h"

namespace glint::gl {

namespace {

std::string expand(const std::string& name, std::set<std::string>& stack) {
  const auto& files = embeddedFiles();
  const auto file = files.find(name);
  if (file == files.end()) throw Error("shader source '" + name + "' is not embedded");
  if (!stack.insert(name).second) throw Error("shader source '" + name + "' includes itself");
  static const std::regex quoted(R"re(^\s*#\s*include\s+"(?:[^"]*/)?([^"/]+)"\s*$)re");
  static const std::regex angled(R"(^\s*#\s*include\s+<[^>]*>\s*$)");
  std::istringstream lines(file->second);
  std::string out;
  std::smatch match;
  for (std::string line; std::getline(lines, line);) {
    if (std::regex_match(line, match, quoted)) {
      out += expand(match[1], stack);
    } else if (!std::regex_match(line, angled)) {
      out += line;
    }
    out += '\n';
  }
  stack.erase(name);
  return out;
}

// GL info logs run over several lines; an error message is one.
std::string oneLine(std::string log) {
  while (!log.empty() && (log.back() == '\n' || log.back() == '\0')) log.pop_back();
  for (char& c : log) {
    if (c == '\n') c = ' ';
  }
  return log.size() > 600 ? log.substr(0, 600) + "..." : log;
}

#ifdef GLINT_GLSL_ES
// WebGL2 (web/): GLSL ES 3.00, with every type at high precision as in desktop GLSL (uint hashing
// needs highp int; samplers have no default precision for some types).
constexpr const char* kVersionHeader =
    "#version 300 es\nprecision highp float;\nprecision highp int;\nprecision highp sampler2D;\n";

// GLSL ES 3.00 has no layout(binding = N) (ES 3.10): the qualifiers are taken out of the source
// and each sampler is given its unit, each uniform block its binding, after linking, as the
// desktop shaders bind them.
struct Bindings {
  std::vector<std::pair<std::string, GLint>> samplers;  // sampler name, texture unit
  std::vector<std::pair<std::string, GLuint>> blocks;   // uniform block name, buffer binding
};

void takeBindings(std::string& source, Bindings& bindings) {
  static const std::regex sampler(R"re(layout\s*\(\s*binding\s*=\s*(\d+)\s*\)\s*(uniform\s+\w+\s+(\w+)\s*;))re");
  static const std::regex block(R"re(layout\s*\(\s*std140\s*,\s*binding\s*=\s*(\d+)\s*\)\s*uniform\s+(\w+))re");
  for (std::sregex_iterator it(source.begin(), source.end(), sampler), end; it != end; ++it) {
    bindings.samplers.emplace_back((*it)[3], std::stoi((*it)[1]));
  }
  for (std::sregex_iterator it(source.begin(), source.end(), block), end; it != end; ++it) {
    bindings.blocks.emplace_back((*it)[2], static_cast<GLuint>(std::stoul((*it)[1])));
  }
  source = std::regex_replace(std::regex_replace(source, sampler, "$2"), block, "layout(std140) uniform $2");
}
#else
constexpr const char* kVersionHeader = "#version 450 core\n";
#endif

}  // namespace

std::string expandIncludes(const std::string& name) {
  std::set<std::string> stack;
  return expand(name, stack);
}

ShaderProgram::ShaderProgram(const std::vector<std::pair<GLenum, std::string>>& stages,
                             const std::vector<std::pair<std::string, std::string>>& defines) {
  std::string header = kVersionHeader;
  for (const auto& [name, value] : defines) header += "#define " + name + " " + value + "\n";
  std::vector<GLuint> shaders;
  auto cleanUp = [&] {
    for (GLuint shader : shaders) glDeleteShader(shader);
  };
#ifdef GLINT_GLSL_ES
  Bindings bindings;
#endif
  for (const auto& [type, name] : stages) {
    std::string source = header + expandIncludes(name);
#ifdef GLINT_GLSL_ES
    takeBindings(source, bindings);
#endif
    const GLuint shader = glCreateShader(type);
    shaders.push_back(shader);
    const char* text = source.c_str();
    glShaderSource(shader, 1, &text, nullptr);
    glCompileShader(shader);
    GLint ok = GL_FALSE;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
      char log[4096] = {};
      glGetShaderInfoLog(shader, sizeof log, nullptr, log);
      cleanUp();
      throw Error("shader " + name + " does not compile: " + oneLine(log));
    }
  }
  id_ = glCreateProgram();
  for (GLuint shader : shaders) glAttachShader(id_, shader);
  glLinkProgram(id_);
  cleanUp();
  GLint ok = GL_FALSE;
  glGetProgramiv(id_, GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[4096] = {};
    glGetProgramInfoLog(id_, sizeof log, nullptr, log);
    glDeleteProgram(id_);
    id_ = 0;
    throw Error("shader program " + stages.front().second + " does not link: " + oneLine(log));
  }
#ifdef GLINT_GLSL_ES
  glUseProgram(id_);
  for (const auto& [sampler, unit] : bindings.samplers) glUniform1i(uniform(sampler.c_str()), unit);
  for (const auto& [block, binding] : bindings.blocks) {
    const GLuint index = glGetUniformBlockIndex(id_, block.c_str());
    if (index != GL_INVALID_INDEX) glUniformBlockBinding(id_, index, binding);
  }
#endif
}

ShaderProgram::~ShaderProgram() {
  if (id_) glDeleteProgram(id_);
}

ShaderProgram& ShaderProgram::operator=(ShaderProgram&& other) noexcept {
  if (this != &other) {
    if (id_) glDeleteProgram(id_);
    id_ = std::exchange(other.id_, 0);
  }
  return *this;
}

}  // namespace glint::gl
