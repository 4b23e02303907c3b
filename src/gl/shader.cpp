#include "gl/shader.h"

#include <algorithm>
#include <regex>
#include <set>
#include <sstream>
#include <vector>

#include "glint/error.h"

namespace glint::gl {

namespace {

// The source string number of a file: its place in `files`, from 1.
int sourceString(const std::string& name, std::vector<std::string>& files) {
  const auto known = std::find(files.begin(), files.end(), name);
  if (known != files.end()) return static_cast<int>(known - files.begin()) + 1;
  files.push_back(name);
  return static_cast<int>(files.size());
}

// Line n of source string S is numbered S * kLinesPerSource + n: Mesa reports every compile error
// in source string 0 (its parser does not keep the number #line sets), so the line carries the
// file too. Source string 0, the version and defines, keeps its own numbers.
constexpr int kLinesPerSource = 100000;

std::string lineDirective(int line, int source) {
  return "#line " + std::to_string(source * kLinesPerSource + line) + " " + std::to_string(source) + "\n";
}

// What expanding one program has seen: the files on the include stack (an include of one of them is
// a cycle), the files already written out, and the conditional blocks open at the current line.
struct ExpansionState {
  std::set<std::string> stack;
  std::set<std::string> written;
  std::vector<bool> openBlocks;  // per open #if: true for an include guard
};

// True when every open block is an include guard, so that a file written here is compiled for sure
// (its guards were not yet defined): a later include of it would only expand its guard's empty
// block, and writes nothing.
bool unconditional(const ExpansionState& state) {
  return std::all_of(state.openBlocks.begin(), state.openBlocks.end(), [](bool guard) { return guard; });
}

void expand(const std::string& name, const std::map<std::string, std::string>& sources, ExpansionState& state,
            ExpandedSource& out) {
  const auto file = sources.find(name);
  if (file == sources.end()) throw Error("shader source '" + name + "' is not embedded");
  if (!state.stack.insert(name).second) throw Error("shader source '" + name + "' includes itself");
  if (unconditional(state)) state.written.insert(name);
  static const std::regex quoted(R"re(^\s*#\s*include\s+"(?:[^"]*/)?([^"/]+)"\s*$)re");
  static const std::regex angled(R"(^\s*#\s*include\s+<[^>]*>\s*$)");
  // A #line inside a conditional block that is skipped is itself skipped, while the block's lines
  // still count: after each #else, #elif and #endif the numbering is set again, so that it is right
  // wherever code is compiled, whichever blocks an include sat in.
  static const std::regex conditional(R"(^\s*#\s*(else|elif|endif)\b.*$)");
  static const std::regex opening(R"(^\s*#\s*if(n?def)?\b\s*(\w*).*$)");
  static const std::regex closing(R"(^\s*#\s*endif\b.*$)");
  static const std::regex definition(R"(^\s*#\s*define\s+(\w+)\s*$)");
  const int source = sourceString(name, out.files);
  out.text += lineDirective(1, source);
  std::vector<std::string> lines;
  {
    std::istringstream stream(file->second);
    for (std::string line; std::getline(stream, line);) lines.push_back(line);
  }
  std::smatch match;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const std::string& line = lines[i];
    const int number = static_cast<int>(i) + 1;
    if (std::regex_match(line, match, quoted)) {
      const std::string included = match[1];
      // An include guard (the header's own #ifndef) makes every include after the first an empty
      // block: the file is written once, at its first include outside any other conditional.
      if (state.stack.count(included) || !state.written.count(included)) expand(included, sources, state, out);
      out.text += lineDirective(number + 1, source);
      continue;
    }
    if (std::regex_match(line, match, opening)) {
      // "#ifndef X" followed by "#define X": an include guard.
      std::smatch defined;
      const bool guard = match[1] == "ndef" && i + 1 < lines.size() && std::regex_match(lines[i + 1], defined, definition) &&
                         defined[1] == match[2];
      state.openBlocks.push_back(guard);
    } else if (std::regex_match(line, closing) && !state.openBlocks.empty()) {
      state.openBlocks.pop_back();
    }
    if (!std::regex_match(line, angled)) out.text += line;
    out.text += '\n';
    if (std::regex_match(line, conditional)) out.text += lineDirective(number + 1, source);
  }
  state.stack.erase(name);
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

ExpandedSource expandIncludes(const std::string& name, const std::map<std::string, std::string>& sources) {
  ExpansionState state;
  ExpandedSource out;
  expand(name, sources, state, out);
  return out;
}

ExpandedSource expandIncludesAfter(const std::string& first, const std::string& name,
                                   const std::map<std::string, std::string>& sources) {
  ExpansionState state;
  ExpandedSource before;
  expand(first, sources, state, before);
  ExpandedSource out;
  out.files = before.files;  // the source strings keep their numbers
  expand(name, sources, state, out);
  return out;
}

std::string locateInFiles(const std::string& log, const std::vector<std::string>& files) {
  // "S:N" followed by "(" or ":" (Mesa's "0:12(5): error", ANGLE's and glslang's "ERROR: 0:12:"), or
  // "S(N)" followed by " :" (NVIDIA's "0(12) : error"), at the start of a line or after a space.
  static const std::regex location(R"((^|\s)(\d+)(?::(\d+)(?=[(:])|\((\d+)\)(?=\s*:)))");
  std::string out;
  auto last = log.cbegin();
  for (std::sregex_iterator it(log.begin(), log.end(), location), end; it != end; ++it) {
    const std::smatch& m = *it;
    const long long line = std::stoll(m[3].matched ? m.str(3) : m.str(4));
    const long long source = line >= kLinesPerSource ? line / kLinesPerSource : std::stoll(m[2]);
    const std::string name = source == 0                                             ? "(version and defines)"
                             : source <= static_cast<long long>(files.size()) ? files[source - 1]
                                                                              : "";
    out.append(last, m[0].first);
    out += name.empty() ? m.str(0) : m.str(1) + name + ":" + std::to_string(line % kLinesPerSource);
    last = m[0].second;
  }
  out.append(last, log.cend());
  return out;
}

GLuint compileStage(GLenum type, const std::string& source, const std::string& name,
                    const std::vector<std::string>& files) {
  const GLuint shader = glCreateShader(type);
  const char* text = source.c_str();
  glShaderSource(shader, 1, &text, nullptr);
  glCompileShader(shader);
  GLint ok = GL_FALSE;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[4096] = {};
    glGetShaderInfoLog(shader, sizeof log, nullptr, log);
    glDeleteShader(shader);
    throw Error("shader " + name + " does not compile: " + oneLine(locateInFiles(log, files)));
  }
  return shader;
}

GLuint linkProgram(const std::vector<GLuint>& stages, const std::string& name) {
  const GLuint program = glCreateProgram();
  for (GLuint shader : stages) glAttachShader(program, shader);
  glLinkProgram(program);
  for (GLuint shader : stages) glDeleteShader(shader);
  GLint ok = GL_FALSE;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[4096] = {};
    glGetProgramInfoLog(program, sizeof log, nullptr, log);
    glDeleteProgram(program);
    throw Error("shader program " + name + " does not link: " + oneLine(log));
  }
  return program;
}

ShaderProgram::ShaderProgram(const std::vector<std::pair<GLenum, std::string>>& stages,
                             const std::vector<std::pair<std::string, std::string>>& defines,
                             const std::map<std::string, std::string>& sources) {
  std::string header = kVersionHeader;
  for (const auto& [name, value] : defines) header += "#define " + name + " " + value + "\n";
  std::vector<GLuint> shaders;
#ifdef GLINT_GLSL_ES
  Bindings bindings;
#endif
  for (const auto& [type, name] : stages) {
    const ExpandedSource expanded = expandIncludes(name, sources);
    std::string source = header + expanded.text;
#ifdef GLINT_GLSL_ES
    takeBindings(source, bindings);
#endif
    try {
      shaders.push_back(compileStage(type, source, name, expanded.files));
    } catch (const Error&) {
      for (GLuint shader : shaders) glDeleteShader(shader);
      throw;
    }
  }
  id_ = linkProgram(shaders, stages.front().second);
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
