// `glint render` and `glint view` as a user runs them: real glTF files, every built-in scene,
// and one-line errors (and no output file) for broken scenes and bad options.
#include <fstream>
#include <regex>

#include <gtest/gtest.h>

#include "glint/image_io.h"
#include "scene/builtin_scenes.h"
#include "test_support.h"

namespace glint {
namespace {

using namespace glint::test;

std::filesystem::path suzanneFolder() { return std::filesystem::path(GLINT_SHARED_DIR) / "scenes" / "suzanne"; }
std::filesystem::path helmetFile() {
  return std::filesystem::path(GLINT_SHARED_DIR) / "scenes" / "damaged-helmet" / "DamagedHelmet.glb";
}

// A rendered image is "correct" here when it has the requested size and shows something: not
// black, not one flat colour (the golden-image tests pin the built-in scenes exactly).
void expectPlausibleImage(const std::filesystem::path& path, int width, int height) {
  const ImageRgbF image = readImage(path);
  ASSERT_EQ(image.width, width);
  ASSERT_EQ(image.height, height);
  double sum = 0.0;
  double sum2 = 0.0;
  for (const glm::vec3& p : image.pixels) {
    const double v = (p.r + p.g + p.b) / 3.0;
    sum += v;
    sum2 += v * v;
  }
  const double mean = sum / image.pixels.size();
  EXPECT_GT(mean, 0.01) << path;
  EXPECT_GT(std::sqrt(sum2 / image.pixels.size() - mean * mean), 0.01) << path;
}

TEST(RenderCli, RendersTheDamagedHelmetWithAndWithoutGlints) {
  const auto folder = temporaryFolder("render_helmet");
  const std::string helmet = "'" + helmetFile().string() + "'";
  RunResult result = runGlint(folder, "render " + helmet + " -o helmet.png --size 128x128");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  expectPlausibleImage(folder / "helmet.png", 128, 128);
  result = runGlint(folder, "render " + helmet + " -o glint.exr --size 128x96 --glint-material '*' --camera close");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  expectPlausibleImage(folder / "glint.exr", 128, 96);
}

TEST(RenderCli, RendersEveryBuiltinSceneAndTheDefault) {
  const auto folder = temporaryFolder("render_builtin");
  for (const std::string& name : scene::builtinSceneNames()) {
    const RunResult result = runGlint(folder, "render " + name + " -o " + name + ".png --size 96x64");
    ASSERT_EQ(result.exitCode, 0) << result.err;
    expectPlausibleImage(folder / (name + ".png"), 96, 64);
  }
  const RunResult result = runGlint(folder, "render -o default.png --size 64x64 --brdf cook-torrance --spp 2");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_NE(result.err.find("showroom"), std::string::npos) << result.err;
  expectPlausibleImage(folder / "default.png", 64, 64);
}

// Copies Suzanne's glTF folder and lets `damage` break the copy.
std::filesystem::path brokenSuzanne(const std::string& name, const std::function<void(const std::filesystem::path&)>& damage) {
  const auto folder = temporaryFolder("broken_" + name);
  std::filesystem::copy(suzanneFolder(), folder / "scene");
  damage(folder / "scene");
  return folder;
}

void replaceInFile(const std::filesystem::path& path, const std::string& from, const std::string& to) {
  std::string text = slurp(path);
  const auto at = text.find(from);
  ASSERT_NE(at, std::string::npos) << from;
  text.replace(at, from.size(), to);
  std::ofstream(path, std::ios::binary) << text;
}

void expectRenderFails(const std::filesystem::path& folder, const std::string& arguments, const std::string& problem) {
  const RunResult result = runGlint(folder, "render " + arguments + " -o out.png --size 32x32");
  expectOneLineError(result, problem);
  EXPECT_FALSE(std::filesystem::exists(folder / "out.png"));
}

TEST(RenderCli, BrokenScenesGiveOneLineErrorsAndNoImage) {
  auto missingBuffer = brokenSuzanne("buffer", [](const auto& f) { std::filesystem::remove(f / "Suzanne.bin"); });
  expectRenderFails(missingBuffer, "scene/Suzanne.gltf", "Suzanne.bin");
  auto badJson = brokenSuzanne("json", [](const auto& f) { replaceInFile(f / "Suzanne.gltf", "{", "{,"); });
  expectRenderFails(badJson, "scene/Suzanne.gltf", "Suzanne.gltf");
  auto missingTexture = brokenSuzanne("texture", [](const auto& f) {
    std::filesystem::remove(f / "Suzanne_BaseColor.png");
  });
  expectRenderFails(missingTexture, "scene/Suzanne.gltf", "Suzanne_BaseColor.png");
  const auto folder = temporaryFolder("render_errors");
  std::ofstream(folder / "empty.glb") << "";
  expectRenderFails(folder, "empty.glb", "empty.glb");
  expectRenderFails(folder, "'" + (suzanneFolder() / "Suzanne.gltf").string() + "' --glint-material Nope",
                    "no material 'Nope'");
  expectRenderFails(folder, "castle", "unknown scene 'castle'");
  expectRenderFails(folder, "sphere --camera drone", "no camera 'drone'");
  expectRenderFails(folder, "sphere --brdf phong", "unknown BRDF 'phong'");
  expectRenderFails(folder, "sphere --size 0x10", "--size");
  expectRenderFails(folder, "sphere --log-density nan", "log_density");
  expectRenderFails(folder, "sphere --relative-area 2", "relative_area");
  expectRenderFails(folder, "sphere --dict missing.gdict", "missing.gdict: cannot open");
  const RunResult wrongExtension = runGlint(folder, "render sphere -o out.jpg --size 32x32");
  expectOneLineError(wrongExtension, "out.jpg: the output must end in .png or .exr");
}

// A triangle lit by `lights` point lights of the file (KHR_lights_punctual).
std::filesystem::path writeTriangleWithLights(const std::filesystem::path& folder, int lights) {
  const float positions[9] = {-1, -1, 0, 1, -1, 0, 0, 1, 0};
  std::ofstream(folder / "tri.bin", std::ios::binary).write(reinterpret_cast<const char*>(positions), sizeof positions);
  std::string lightList;
  std::string lightNodes;
  std::string nodeList = "0";
  for (int i = 0; i < lights; ++i) {
    lightList += std::string(i ? "," : "") + R"({"type": "point", "intensity": 300})";
    lightNodes += R"(,{"translation": [0, 0, 2], "extensions": {"KHR_lights_punctual": {"light": )" + std::to_string(i) + "}}}";
    nodeList += "," + std::to_string(i + 1);
  }
  const std::filesystem::path path = folder / "tri.gltf";
  std::ofstream(path) << R"({"asset": {"version": "2.0"}, "extensionsUsed": ["KHR_lights_punctual"],
    "extensions": {"KHR_lights_punctual": {"lights": [)" << lightList << R"(]}},
    "buffers": [{"uri": "tri.bin", "byteLength": 36}], "bufferViews": [{"buffer": 0, "byteLength": 36}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [-1, -1, 0], "max": [1, 1, 0]}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
    "nodes": [{"mesh": 0})" << lightNodes << R"(], "scenes": [{"nodes": [)" << nodeList << R"(]}], "scene": 0})";
  return path;
}

TEST(RenderCli, SaysWhenTheRasteriserDrawsOnlySomeOfTheLights) {
  // The rasteriser draws the first 8 lights: a file with 9 renders, with a one-line warning.
  const auto folder = temporaryFolder("cli_many_lights");
  const std::string nine = writeTriangleWithLights(folder, 9).string();
  RunResult result = runGlint(folder, "render " + nine + " -o nine.png --size 32x32");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_NE(result.err.find("has 9 lights; the rasteriser draws the first 8"), std::string::npos) << result.err;
  expectPlausibleImage(folder / "nine.png", 32, 32);
  const auto fewFolder = temporaryFolder("cli_few_lights");
  const std::string two = writeTriangleWithLights(fewFolder, 2).string();
  result = runGlint(fewFolder, "render " + two + " -o two.png --size 32x32");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_EQ(result.err.find("warning"), std::string::npos) << result.err;
}

// A file that uses what glint does not render still renders, with one warning line per kind.
TEST(RenderCli, WarnsAboutWhatTheFileUsesAndGlintDoesNotRead) {
  const auto folder = brokenSuzanne("unread", [](const auto& f) {
    replaceInFile(f / "Suzanne.gltf", "\"baseColorTexture\" : {", "\"baseColorTexture\" : { \"texCoord\" : 1,");
    replaceInFile(f / "Suzanne.gltf", "\"asset\"", "\"extensionsUsed\" : [\"KHR_materials_clearcoat\"], \"asset\"");
  });
  const RunResult result = runGlint(folder, "render scene/Suzanne.gltf -o out.png --size 32x32");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_NE(result.err.find("glint: warning: scene/Suzanne.gltf: extension KHR_materials_clearcoat is not read\n"),
            std::string::npos)
      << result.err;
  EXPECT_NE(result.err.find("glint: warning: scene/Suzanne.gltf: textures on a texCoord other than 0 are mapped with "
                            "TEXCOORD_0 (material 0 'Suzanne' baseColorTexture)\n"),
            std::string::npos)
      << result.err;
  expectPlausibleImage(folder / "out.png", 32, 32);
}

TEST(BenchCli, PrintsTheJsonTable) {
  const auto folder = temporaryFolder("bench");
  const RunResult result = runGlint(folder, "bench sphere grazing-rough --size 48x32 --frames 2 --warmup 0 --json");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  for (const char* key : {"\"size\":[48,32]", "\"renderer\":", "\"timer\":\"wall-finish\"", "\"scene\":\"sphere\"",
                          "\"scene\":\"grazing-rough\"", "\"glint\":{", "\"cook-torrance\":{", "\"median_ms\":",
                          "\"min_ms\":", "\"max_ms\":", "\"ratio_glint_cook-torrance\":"}) {
    EXPECT_NE(result.out.find(key), std::string::npos) << key << " missing in " << result.out;
  }
  EXPECT_EQ(std::count(result.out.begin(), result.out.end(), '\n'), 1);  // one object, one line
  expectOneLineError(runGlint(folder, "bench sphere --frames 0"), "--frames");
  expectOneLineError(runGlint(folder, "bench atlantis"), "unknown scene 'atlantis'");
}

// The window: GLFW under a virtual X server (xvfb-run, installed by scripts/deps). Two frames,
// because Dear ImGui hides new windows on their first frame; the screenshot must show the scene
// and the sliders' panel.
TEST(ViewCli, OpensAndRendersUnderXvfb) {
  ASSERT_EQ(std::system("command -v xvfb-run > /dev/null"), 0) << "xvfb-run is missing (scripts/deps installs it)";
  const auto folder = temporaryFolder("view");
  const std::string command = "cd '" + folder.string() + "' && xvfb-run -a -s '-screen 0 640x480x24' '" GLINT_EXECUTABLE
                              "' view sphere --width 320 --height 240 --frames 2 --screenshot shot.png 2> stderr.txt";
  ASSERT_EQ(std::system(command.c_str()), 0) << slurp(folder / "stderr.txt");
  expectPlausibleImage(folder / "shot.png", 320, 240);
  const RunResult noDisplay = runGlint(folder, "view sphere --frames 1");  // runGlint keeps DISPLAY as is
  if (std::getenv("DISPLAY") == nullptr) expectOneLineError(noDisplay, "no window");
}

}  // namespace
}  // namespace glint
