// Shader assembly (gl/shader.h): the files a stage includes are marked with #line directives, so
// that a compile error names the file and line it is in, not a line of the expanded text.
#include <map>
#include <string>

#include <gtest/gtest.h>

#include "gl/shader.h"
#include "gl_support.h"
#include "glint/error.h"

namespace glint {
namespace {

using namespace glint::test;

// The message of the Error a program of these fragment sources throws (with the embedded files,
// so that the kernel's headers can be included), or "" when it compiles.
std::string compileError(const std::map<std::string, std::string>& extra) {
  useGlContext();
  std::map<std::string, std::string> sources = gl::embeddedFiles();
  sources.insert(extra.begin(), extra.end());
  try {
    gl::ShaderProgram program({{GL_VERTEX_SHADER, "fullscreen.vert"}, {GL_FRAGMENT_SHADER, "main.frag"}}, {}, sources);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(ShaderGl, AnErrorInAnIncludedFileNamesThatFileAndLine) {
  const std::string message = compileError({
      {"main.frag",
       "// line 1\n"
       "#include \"microfacet.h\"\n"
       "#include \"broken.glsl\"\n"
       "layout(location = 0) out vec4 colour;\n"
       "void main() { colour = vec4(brokenValue()); }\n"},
      {"broken.glsl",
       "// line 1\n"
       "float brokenValue() {\n"
       "  return GLINT_PI;\n"
       "  float x = undeclaredName;\n"  // line 4
       "}\n"},
  });
  EXPECT_NE(message.find("broken.glsl:4"), std::string::npos) << message;
}

// An include inside a block the preprocessor skips (its #line directives skipped too, its lines
// counted): the main file's lines after it keep their own numbers.
TEST(ShaderGl, AnErrorAfterASkippedIncludeNamesTheMainFileAndLine) {
  const std::string message = compileError({
      {"main.frag",
       "#include \"microfacet.h\"\n"
       "#if 0\n"
       "#include \"tonemap.h\"\n"
       "#endif\n"
       "layout(location = 0) out vec4 colour;\n"
       "void main() {\n"
       "  colour = vec4(undeclaredName);\n"  // line 7
       "}\n"},
  });
  EXPECT_NE(message.find("main.frag:7"), std::string::npos) << message;
}

// Line n of file S is numbered S * 100000 + n (gl/shader.h); the prepended version and defines are
// source string 0, with their own numbers.
TEST(ShaderLog, LocationsAreWrittenAsFileAndLine) {
  const std::vector<std::string> files = {"forward.frag", "glint_brdf.h"};
  // Mesa (which reports source string 0 for every error), ANGLE and glslang, NVIDIA.
  EXPECT_EQ(gl::locateInFiles("0:12(5): error: `x' undeclared\n0:200040(3): error: y", files),
            "(version and defines):12(5): error: `x' undeclared\nglint_brdf.h:40(3): error: y");
  EXPECT_EQ(gl::locateInFiles("ERROR: 1:100007: 'x' : undeclared identifier", files),
            "ERROR: forward.frag:7: 'x' : undeclared identifier");
  EXPECT_EQ(gl::locateInFiles("2(200033) : error C1008: undefined variable", files),
            "glint_brdf.h:33 : error C1008: undefined variable");
  // A file past the list, and numbers that are no location, stay as they are.
  EXPECT_EQ(gl::locateInFiles("0:900003(1): error: at 12:30 (x)", files), "0:900003(1): error: at 12:30 (x)");
}

}  // namespace
}  // namespace glint
