// The Shadertoy bundle (`glint shader-bundle --shadertoy`) in a small harness that supplies what
// Shadertoy does: its GLSL ES 3.00 header (iResolution, iTime, iFrame, iMouse, iChannel0..3), the
// Common tab before each pass, mainImage called for every pixel, Buffer A rendered into a float
// texture that the Image pass reads as iChannel0. Checked: Buffer A holds the kernel's procedural
// dictionary as the CPU computes it, and the Image pass shows glints over the smooth lobe.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <glad/gl.h>
#include <gtest/gtest.h>

#include "gl/shader.h"
#include "gl_support.h"
#include "glint/error.h"
#include "glint/image_io.h"
#include "glint/kernel/procedural_dictionary.h"
#include "test_support.h"

namespace glint {
namespace {

using namespace glint::test;

constexpr int kWidth = 512;  // Buffer A needs 256 x 160 pixels for its 40,960 texel pairs
constexpr int kHeight = 288;

// Shadertoy's header, the Common tab, the pass, and a main that calls mainImage.
std::string shadertoyFragment(const std::string& common, const std::string& pass, const std::string& defines) {
  return "#version 300 es\nprecision highp float;\nprecision highp int;\nprecision highp sampler2D;\n"
         "uniform vec3 iResolution;\nuniform float iTime;\nuniform float iTimeDelta;\nuniform int iFrame;\n"
         "uniform vec4 iMouse;\nuniform sampler2D iChannel0;\nuniform sampler2D iChannel1;\n"
         "uniform sampler2D iChannel2;\nuniform sampler2D iChannel3;\n" +
         defines + common + "\n" + pass +
         "\nout vec4 shadertoyColour;\nvoid main() {\n  mainImage(shadertoyColour, gl_FragCoord.xy);\n}\n";
}

// One pass drawn over a kWidth x kHeight RGBA32F target, iChannel0 bound to `channel0` (0: none).
std::vector<float> runPass(const std::string& fragment, const std::string& name, GLuint target, GLuint channel0) {
  const std::string vertex =
      "#version 300 es\nvoid main() {\n  vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));\n"
      "  gl_Position = vec4(2.0 * p - 1.0, 0.0, 1.0);\n}\n";
  const GLuint program = gl::linkProgram({gl::compileStage(GL_VERTEX_SHADER, vertex, "the harness's vertex shader"),
                                           gl::compileStage(GL_FRAGMENT_SHADER, fragment, name)},
                                          name);
  GLuint framebuffer = 0;
  glCreateFramebuffers(1, &framebuffer);
  glNamedFramebufferTexture(framebuffer, GL_COLOR_ATTACHMENT0, target, 0);
  GLuint vertexArray = 0;
  glCreateVertexArrays(1, &vertexArray);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
  glViewport(0, 0, kWidth, kHeight);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glUseProgram(program);
  glUniform3f(glGetUniformLocation(program, "iResolution"), float(kWidth), float(kHeight), 1.0f);
  glUniform1f(glGetUniformLocation(program, "iTime"), 2.0f);
  glUniform1i(glGetUniformLocation(program, "iFrame"), 120);
  glUniform1i(glGetUniformLocation(program, "iChannel0"), 0);
  glBindTextureUnit(0, channel0);
  glBindVertexArray(vertexArray);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  std::vector<float> pixels(static_cast<std::size_t>(kWidth) * kHeight * 4);
  glReadPixels(0, 0, kWidth, kHeight, GL_RGBA, GL_FLOAT, pixels.data());
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glDeleteVertexArrays(1, &vertexArray);
  glDeleteFramebuffers(1, &framebuffer);
  glDeleteProgram(program);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR)) << name;
  return pixels;
}

GLuint floatTarget() {
  GLuint texture = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &texture);
  glTextureStorage2D(texture, 1, GL_RGBA32F, kWidth, kHeight);
  return texture;
}

double luminanceAt(const std::vector<float>& rgba, int i) {
  return 0.2126 * rgba[4 * i] + 0.7152 * rgba[4 * i + 1] + 0.0722 * rgba[4 * i + 2];
}

TEST(ShadertoyGl, TheBundleRunsInShadertoysHarnessAndShowsGlints) {
  const std::filesystem::path folder = temporaryFolder("shadertoy");
  const RunResult written = runGlint(folder, "shader-bundle --shadertoy -o toy");
  ASSERT_EQ(written.exitCode, 0) << written.err;
  const std::string common = slurp(folder / "toy" / "common.glsl");
  const std::string bufferA = slurp(folder / "toy" / "buffer_a.glsl");
  const std::string image = slurp(folder / "toy" / "image.glsl");
  for (const std::string* text : {&common, &bufferA, &image}) {
    ASSERT_FALSE(text->empty());
    EXPECT_EQ(text->find("#include"), std::string::npos) << "Shadertoy has no includes";
  }
  useGlContext();
  const GLuint dictionary = floatTarget();
  const GLuint picture = floatTarget();
  const std::vector<float> texels = runPass(shadertoyFragment(common, bufferA, ""), "Buffer A", dictionary, 0);

  // Buffer A against the CPU kernel at every 97th texel pair (GLSL ES arithmetic against C++'s,
  // exp and erfinv on both sides: 1e-4 relative, with 1e-6 absolute for the near-zero tails).
  int compared = 0;
  for (int index = 0; index < 10 * 64 * 64; index += 97) {
    const int k = index % 64;
    const int distribution = (index / 64) % 64;
    const int level = index / (64 * 64);
    const int pixel = (index / 256) * kWidth + index % 256;
    for (int j = 0; j < 2; ++j) {
      const float cpu = k + j < 64 ? kernel::glintProceduralDictionaryTexel(level, distribution, k + j, 64, 0.5f, 0.02f, 1u)
                                   : 0.0f;
      const float gpu = texels[4 * static_cast<std::size_t>(pixel) + j];
      EXPECT_NEAR(gpu, cpu, 1e-4f * std::abs(cpu) + 1e-6f) << "level " << level << " distribution " << distribution
                                                           << " texel " << k + j;
      ++compared;
    }
  }
  EXPECT_GT(compared, 800);

  // The Image pass, and the same with the smooth lobe the glints converge to. Glints: sphere pixels
  // brighter than twice the smooth image; they must be a visible share, while the sphere's mean
  // stays near the smooth lobe's (measured 0.89x, 2026-12-03; bound 0.7x-1.4x: the pattern is sparse, a
  // few hundred glint pixels).
  const std::vector<float> glints = runPass(shadertoyFragment(common, image, ""), "Image", picture, dictionary);
  const std::vector<float> smooth =
      runPass(shadertoyFragment(common, image, "#define GLINT_SHADERTOY_SMOOTH 1\n"), "Image (smooth)", picture, dictionary);
  int sphere = 0;
  int sparkling = 0;
  double glintSum = 0.0;
  double smoothSum = 0.0;
  for (int i = 0; i < kWidth * kHeight; ++i) {
    const double g = luminanceAt(glints, i);
    const double s = luminanceAt(smooth, i);
    if (g == s) continue;  // the background, drawn alike; also sphere pixels without glints or lobe
    ++sphere;
    sparkling += g > 2.0 * s + 0.02;
    glintSum += g;
    smoothSum += s;
  }
  std::printf("Shadertoy harness: %d sphere pixels differ from the smooth lobe, %d (%.2f%%) above twice it; mean %.4f "
              "against %.4f\n",
              sphere, sparkling, 100.0 * sparkling / std::max(sphere, 1), glintSum / std::max(sphere, 1),
              smoothSum / std::max(sphere, 1));
  EXPECT_GT(sphere, 10000);
  EXPECT_GT(sparkling, 200);
  EXPECT_GT(glintSum, 0.7 * smoothSum);
  EXPECT_LT(glintSum, 1.4 * smoothSum);
  ImageRgbF shown;
  shown.width = kWidth;
  shown.height = kHeight;
  for (int y = kHeight - 1; y >= 0; --y) {
    for (int x = 0; x < kWidth; ++x) {
      const float* p = &glints[4 * (static_cast<std::size_t>(y) * kWidth + x)];
      shown.pixels.push_back(glm::vec3(srgbToLinear(p[0]), srgbToLinear(p[1]), srgbToLinear(p[2])));
    }
  }
  writePngSrgb(folder / "shadertoy.png", shown);
  glDeleteTextures(1, &dictionary);
  glDeleteTextures(1, &picture);
}

TEST(ShaderBundleCli, BadArgumentsGiveOneLine) {
  const std::filesystem::path folder = temporaryFolder("shader-bundle-cli");
  expectOneLineError(runGlint(folder, "shader-bundle --language metal"), "--language must be glsl, glsl-es, vulkan or hlsl");
  expectOneLineError(runGlint(folder, "shader-bundle"), "give one of --language LANGUAGE and --shadertoy");
  expectOneLineError(runGlint(folder, "shader-bundle --language glsl --shadertoy -o x"), "give one of");
  expectOneLineError(runGlint(folder, "shader-bundle --shadertoy"), "give the folder with -o FOLDER");
  expectOneLineError(runGlint(folder, "shader-bundle --shadertoy --extended-lights -o toy"),
                     "--extended-lights goes with --language, not --shadertoy");
  EXPECT_FALSE(std::filesystem::exists(folder / "x"));
}

// The GLSL ES bundle that three.js and the page ship stays small: each header once, other
// languages' branches left out (147,556 bytes on 2026-12-08, 1,115,422 when every include repeated
// its header). Bound: 150,000 bytes, what a download of the kernel is meant to stay within.
TEST(ShaderBundleCli, TheGlslEsBundleIsAtMost150KB) {
  const std::filesystem::path folder = temporaryFolder("shader-bundle-size");
  const RunResult written = runGlint(folder, "shader-bundle --language glsl-es -o kernel.glsl");
  ASSERT_EQ(written.exitCode, 0) << written.err;
  const auto bytes = std::filesystem::file_size(folder / "kernel.glsl");
  EXPECT_GT(bytes, 50000u);  // the whole kernel, not a stub
  EXPECT_LE(bytes, 150000u);
  RecordProperty("glsl_es_bundle_bytes", std::to_string(bytes));
}

// A bundle that cannot be written leaves nothing behind: no `.partial` or temporary beside a
// folder given as the file, none of the three Shadertoy files when one of them cannot be written,
// no folder made for them, and no parent folders made for a missing one.
TEST(ShaderBundleCli, AFailedWriteLeavesNothing) {
  const std::filesystem::path folder = temporaryFolder("shader-bundle-failed");
  std::filesystem::create_directory(folder / "kernel.hlsl");
  expectOneLineError(runGlint(folder, "shader-bundle --language hlsl -o kernel.hlsl"), "kernel.hlsl: cannot write (is a directory)");
  std::filesystem::create_directories(folder / "toy" / "image.glsl");
  expectOneLineError(runGlint(folder, "shader-bundle --shadertoy -o toy"), "toy/image.glsl: cannot write (is a directory)");
  EXPECT_FALSE(std::filesystem::exists(folder / "toy" / "common.glsl"));
  EXPECT_FALSE(std::filesystem::exists(folder / "toy" / "buffer_a.glsl"));
  expectOneLineError(runGlint(folder, "shader-bundle --shadertoy -o missing/toy"), "missing/toy: cannot make the folder");
  EXPECT_FALSE(std::filesystem::exists(folder / "missing"));
  std::vector<std::string> left;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(folder)) {
    const std::string name = entry.path().filename().string();
    if (name.find(".partial") != std::string::npos || name.find(".tmp") != std::string::npos) left.push_back(name);
  }
  EXPECT_TRUE(left.empty()) << left.front();
}

}  // namespace
}  // namespace glint
