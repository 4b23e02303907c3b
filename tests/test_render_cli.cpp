// `glint render`, `glint export` and `glint view` as a user runs them: glTF files the repository
// writes (and the third-party helmet when ../shared has it), every built-in scene, exported scenes
// rendering as the built-in ones, and one-line errors (and no output file) for broken scenes and
// bad options.
#include <array>
#include <fstream>
#include <functional>
#include <regex>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "glint/image_io.h"
#include "scene/builtin_scenes.h"
#include "scene/geometry.h"
#include "scene/gltf_writer.h"
#include "scene_support.h"
#include "test_support.h"

namespace glint {
namespace {

using namespace glint::test;


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
  const std::filesystem::path helmetFile = sharedAsset("scenes/damaged-helmet/DamagedHelmet.glb");
  if (helmetFile.empty()) GTEST_SKIP() << sharedAssetMissing("scenes/damaged-helmet");
  const auto folder = temporaryFolder("render_helmet");
  const std::string helmet = "'" + helmetFile.string() + "'";
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

// Without -o, render and trace name their output after the scene, in the current folder (not beside
// a glTF file), and say in one line what they wrote.
TEST(RenderCli, WithoutAnOutputTheImageIsNamedAfterTheScene) {
  const auto folder = temporaryFolder("render_default_output");
  RunResult result = runGlint(folder, "render sphere --size 32x32");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_EQ(result.err.rfind("glint: wrote sphere.png (sphere, 32x32", 0), 0u) << result.err;
  EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
  expectPlausibleImage(folder / "sphere.png", 32, 32);
  result = runGlint(folder, "render --size 32x32 --brdf cook-torrance");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  expectPlausibleImage(folder / "showroom.png", 32, 32);  // the default scene
  std::filesystem::create_directory(folder / "scene");
  writeSeparateGltf(texturedTestScene(), folder / "scene", "textured");
  result = runGlint(folder, "render scene/textured.gltf --size 32x32");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_NE(result.err.find("glint: wrote textured.png ("), std::string::npos) << result.err;
  expectPlausibleImage(folder / "textured.png", 32, 32);
  EXPECT_FALSE(std::filesystem::exists(folder / "scene" / "textured.png"));

  const auto traced = temporaryFolder("trace_default_output");
  result = runGlint(traced, "trace parquet --size 16x16 --spp 1");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_EQ(result.err.rfind("glint: wrote parquet.exr and parquet.png (parquet, 16x16", 0), 0u) << result.err;
  expectPlausibleImage(traced / "parquet.exr", 16, 16);
  expectPlausibleImage(traced / "parquet.png", 16, 16);
}

// An exported file, rendered plainly and with a glint layer put on its plain floor by the command
// line (also from a camera preset): plausible, and the layer shows.
TEST(RenderCli, RendersAnExportedFileWithAndWithoutAddedGlints) {
  const auto folder = temporaryFolder("render_exported");
  RunResult result = runGlint(folder, "export carpaint -o car.glb");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  result = runGlint(folder, "render car.glb -o car.exr --size 96x64");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  expectPlausibleImage(folder / "car.exr", 96, 64);
  // Sparse, sharp glints (the overrides apply to every layer, the car's too) on the floor.
  const std::string sparse = " --log-density 12 --alpha 0.2";
  result = runGlint(folder, "render car.glb -o sparse.exr --size 96x64" + sparse);
  ASSERT_EQ(result.exitCode, 0) << result.err;
  result = runGlint(folder, "render car.glb -o glint.exr --size 96x64 --glint-material floor" + sparse);
  ASSERT_EQ(result.exitCode, 0) << result.err;
  expectPlausibleImage(folder / "glint.exr", 96, 64);
  result = runGlint(folder, "render car.glb -o close.exr --size 96x64 --glint-material floor --camera close");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  expectPlausibleImage(folder / "close.exr", 96, 64);
  EXPECT_GT(compareImages(readImage(folder / "glint.exr"), readImage(folder / "sparse.exr")).relmse, 1e-4)
      << "a glint layer on the floor changed nothing";
}

// A file of one quad of `material`, 2 m along x and 2 |halfV| along halfV, without cameras or lights.
void writeQuadFile(const std::filesystem::path& path, const scene::Material& material, glm::vec3 halfV) {
  scene::Scene s;
  s.name = path.stem().string();
  s.materials.push_back(material);
  s.meshes.push_back(scene::makeQuad(s.name, 0, glm::vec3(0.0f), glm::vec3(1.0f, 0.0f, 0.0f), halfV));
  scene::writeGltf(path, s);
}

// A model lying in the xz plane (a floor, a mat), a file without cameras or lights: the default view
// sees it from above, not edge-on from the front, so the picture is not empty.
TEST(RenderCli, AFlatModelsDefaultViewSeesIt) {
  const auto folder = temporaryFolder("render_flat");
  scene::Material grey;
  grey.name = "grey";
  writeQuadFile(folder / "mat.glb", grey, glm::vec3(0.0f, 0.0f, 0.6f));
  const RunResult result = runGlint(folder, "render mat.glb -o mat.exr --size 64x64 --env-intensity 0 --shadows off");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  const ImageRgbF image = readImage(folder / "mat.exr");
  int lit = 0;
  for (const glm::vec3& pixel : image.pixels) lit += pixel.x + pixel.y + pixel.z > 0.0f ? 1 : 0;
  // The 2 x 1.2 m mat fills about 0.45 of the view's height and width at the preset's distance.
  EXPECT_GT(lit, 64 * 64 / 10) << lit << " pixels show the mat";
}

// A rectangle light's quad, added after the scene is built, moves its bounds: the presets glint made
// before are still glint's, and export leaves them out (the sphere's own default camera stays).
TEST(RenderCli, ExportWithARectangleLightWritesOnlyTheScenesCameras) {
  const auto folder = temporaryFolder("export_rect");
  const RunResult result = runGlint(folder, "export sphere --rect-light 2,3,2,1.5,1,20 -o lit.gltf");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  const nlohmann::json document = nlohmann::json::parse(std::ifstream(folder / "lit.gltf"));
  ASSERT_EQ(document["cameras"].size(), 1u) << document["cameras"].dump();
  EXPECT_EQ(document["cameras"][0]["name"], "default");
}

// The warning for what glint approximates names the file, as every other warning does.
TEST(RenderCli, TheBlendWarningNamesTheFile) {
  const auto folder = temporaryFolder("render_blend");
  scene::Material veil;
  veil.name = "veil";
  veil.alphaMode = scene::Material::AlphaMode::Blend;
  writeQuadFile(folder / "veil.glb", veil, glm::vec3(0.0f, 1.0f, 0.0f));
  const RunResult result = runGlint(folder, "render veil.glb -o veil.png --size 32x32");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_NE(result.err.find("glint: warning: veil.glb: material 'veil' has alphaMode BLEND"), std::string::npos) << result.err;
}

// A metal UV sphere of radius 1 without a glint layer, its uv (phi / 2 pi, theta / pi) times
// `uvExtent` (1: 0.28 uv units per metre, about what a textured asset's atlas gives), a point light
// beside the camera and the camera at 3.6 m, written as glTF by the repository's own writer.
std::filesystem::path writePlainSphere(const std::filesystem::path& folder, const std::string& stem, float uvExtent) {
  scene::Scene s;
  s.name = stem;
  scene::Material metal;
  metal.name = "metal";
  metal.baseColour = glm::vec4(0.9f, 0.9f, 0.9f, 1.0f);
  metal.metallic = 1.0f;
  metal.roughness = 0.5f;  // alpha 0.25
  s.materials.push_back(metal);
  s.meshes.push_back(scene::makeUvSphere("ball", 0, glm::vec3(0.0f), 1.0f, 96, 48, glm::vec2(uvExtent)));
  scene::Light light;
  light.position = glm::vec3(0.8f, 0.8f, 4.0f);
  light.intensity = glm::vec3(20.0f);
  s.lights.push_back(light);
  s.cameras = scene::standardCameras(s.boundsMin(), s.boundsMax());
  s.cameras["default"].position = glm::vec3(0.0f, 0.0f, 3.6f);
  const std::filesystem::path path = folder / (stem + ".glb");
  scene::writeGltf(path, s);
  return path;
}

// The glint layer's sparkle: the RMSE of glint against Cook-Torrance with the same roughness over
// the sphere's pixels, relative to their mean (as RenderGl.DefaultDensityShowsGlints measures).
double sparkle(const ImageRgbF& glint, const ImageRgbF& smooth) {
  double squares = 0.0, sum = 0.0;
  int pixels = 0;
  for (std::size_t i = 0; i < glint.pixels.size(); ++i) {
    const double c = (smooth.pixels[i].r + smooth.pixels[i].g + smooth.pixels[i].b) / 3.0;
    if (!(c > 0.05)) continue;  // the background (0.02 ambient grey, lit by nothing) and the dark rim
    const double g = (glint.pixels[i].r + glint.pixels[i].g + glint.pixels[i].b) / 3.0;
    squares += (g - c) * (g - c);
    sum += c;
    ++pixels;
  }
  return pixels > 0 ? std::sqrt(squares / pixels) / (sum / pixels) : 0.0;
}

TEST(RenderCli, GlintMaterialShowsGlintsAtAnyUvScale) {
  // `--glint-material '*'` on a material without glint parameters: the default log density follows
  // the material's uv area per square metre (scene::visibleGlintDensity), so the layer sparkles
  // whatever the uv scale, and the command says which density it used. The fixed 27 was smooth
  // at an asset's usual uv scale and glinted only where the uv ran 1,000 times slower.
  // The paper's Beckmann target (--ndf beckmann), for which these densities were measured: a glTF
  // file's default GGX target keeps a cell-to-cell variation of roughness at 27 (sparkle 0.151 on
  // the atlas, measured 2026-12-02; docs/method.md section 6.1).
  const auto folder = temporaryFolder("render_glint_material");
  const std::string size = " --size 128x128 --aa none --ndf beckmann";
  RunResult result;
  for (float uvExtent : {1.0f, 1e-3f}) {
    const std::string stem = uvExtent == 1.0f ? "atlas" : "slow";
    SCOPED_TRACE(stem);
    const std::string file = writePlainSphere(folder, stem, uvExtent).filename().string();
    result = runGlint(folder, "render " + file + " -o smooth.exr --brdf cook-torrance --glint-material '*'" + size);
    ASSERT_EQ(result.exitCode, 0) << result.err;
    result = runGlint(folder, "render " + file + " -o derived.exr --glint-material '*'" + size);
    ASSERT_EQ(result.exitCode, 0) << result.err;
    const std::regex said(R"(glint: log density of the new glint layers, about 100 microfacets per pixel at the default )"
                          R"(camera \(512 pixels high\): 'metal' ([0-9.]+) \([0-9.e+-]+ uv units per metre\); )"
                          R"(--log-density D sets another\n)");
    std::smatch match;
    ASSERT_TRUE(std::regex_search(result.err, match, said)) << result.err;
    const std::string density = match[1].str();  // a copy: `result` is reused below, and match points into it
    const scene::Scene loaded = scene::loadScene((folder / file).string());
    EXPECT_FLOAT_EQ(std::stof(density), scene::visibleGlintDensity(loaded, 0).logDensity);
    result = runGlint(folder, "render " + file + " -o fixed.exr --glint-material '*' --log-density 27" + size);
    ASSERT_EQ(result.exitCode, 0) << result.err;
    EXPECT_EQ(result.err.find("log density of the new"), std::string::npos) << "--log-density set it: " << result.err;
    const ImageRgbF smooth = readImage(folder / "smooth.exr");
    const double derived = sparkle(readImage(folder / "derived.exr"), smooth);
    const double fixed = sparkle(readImage(folder / "fixed.exr"), smooth);
    std::printf("%s (uv x %g): log density %s, sparkle %.3f; at 27, %.3f\n", stem.c_str(), uvExtent,
                density.c_str(), derived, fixed);
    EXPECT_GT(derived, 0.05);
    if (uvExtent == 1.0f) EXPECT_LT(fixed, 0.05) << "27 was expected to look smooth at this uv scale";
  }
}

// The round trip: an exported built-in scene renders as the built-in scene, under the same sky
// (glTF has no environment: --sky gives both the same). The loader normalises normals in double and
// puts each camera's target on its view ray at another distance, so a few float ulps of direction
// differ: at 96 x 96 the relative MSE measured 0 (parquet) to 3.9e-9 (carpaint), under the bound
// 1e-8; the same files with their glint layers left out measured 1.1e-3 to 2.9e-2 (the car, the
// atrium and the arctic drawn with Cook-Torrance instead: 3.0e-2, 1.3, 10.9). The atrium's
// many silhouettes are the exception: those ulps move a pixel centre across an edge in 2 of its
// 9,216 pixels (relative MSE 3.1e-6), so it is drawn from its default camera given on the command
// line to both (4.1e-11): its file's camera is the other scenes' kind, which they check.
TEST(ExportCli, ExportedBuiltinScenesRenderAsTheBuiltinOnes) {
  const auto folder = temporaryFolder("export_round_trip");
  for (const std::string name : {"sphere", "parquet", "carpaint", "showroom", "arctic", "atrium", "car"}) {
    SCOPED_TRACE(name);
    const std::string camera =
        name == "atrium" ? cameraOptions(scene::makeBuiltinScene(name).cameras.at("default")) : std::string();
    const std::string file = name + (name == "showroom" ? ".gltf" : ".glb");
    RunResult result = runGlint(folder, "export " + name + " -o " + file);
    ASSERT_EQ(result.exitCode, 0) << result.err;
    EXPECT_NE(result.err.find("glint: warning: " + file + " leaves out what glTF cannot hold: the environment"),
              std::string::npos)
        << result.err;
    EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 2) << result.err;  // the warning, "wrote"
    for (const std::string& scene : {name, file}) {
      result = runGlint(folder, "render " + scene + " --sky 0.2" + camera + " -o " + scene + ".exr --size 96x96");
      ASSERT_EQ(result.exitCode, 0) << result.err;
    }
    const ImageRgbF builtin = readImage(folder / (name + ".exr"));
    const ImageError error = compareImages(readImage(folder / (file + ".exr")), builtin);
    EXPECT_LE(error.relmse, 1e-8) << "rmse " << error.rmse;
    expectPlausibleImage(folder / (file + ".exr"), 96, 96);
  }
}

// --pattern-seed: another realisation of the same glints. Seed 0 is the built-in scenes' own; another
// seed moves the glints but keeps their statistics; export writes it into the file, whose render is
// the option's.
TEST(RenderCli, PatternSeedDrawsAnotherRealisationOfTheSameGlints) {
  const auto folder = temporaryFolder("pattern_seed");
  const std::string size = " --size 96x96 --sky 0.2";
  for (const auto& [seed, image] : {std::pair<std::string, std::string>{"", "own.exr"}, {" --pattern-seed 0", "zero.exr"},
                                    {" --pattern-seed 7919", "other.exr"}}) {
    const RunResult result = runGlint(folder, "render sphere" + size + seed + " -o " + image);
    ASSERT_EQ(result.exitCode, 0) << result.err;
  }
  const RunResult exported = runGlint(folder, "export sphere --pattern-seed 7919 -o seeded.glb");
  ASSERT_EQ(exported.exitCode, 0) << exported.err;
  const RunResult rendered = runGlint(folder, "render seeded.glb" + size + " -o seeded.exr");
  ASSERT_EQ(rendered.exitCode, 0) << rendered.err;
  const ImageRgbF own = readImage(folder / "own.exr");
  const ImageRgbF other = readImage(folder / "other.exr");
  EXPECT_EQ(compareImages(readImage(folder / "zero.exr"), own).rmse, 0.0);
  // As ExportedBuiltinScenesRenderAsTheBuiltinOnes: the file's vertices are rounded to floats.
  EXPECT_LE(compareImages(readImage(folder / "seeded.exr"), other).relmse, 1e-8);
  // Another seed moves the glints: many pixels change (2,406 of 9,216 measured), the image's mean
  // does not (0.07% measured; 2% allows for the sphere's few hundred glinting pixels).
  int changed = 0;
  double ownSum = 0.0;
  double otherSum = 0.0;
  for (std::size_t p = 0; p < own.pixels.size(); ++p) {
    changed += own.pixels[p] != other.pixels[p];
    ownSum += own.pixels[p].x + own.pixels[p].y + own.pixels[p].z;
    otherSum += other.pixels[p].x + other.pixels[p].y + other.pixels[p].z;
  }
  EXPECT_GT(changed, static_cast<int>(own.pixels.size()) / 10);
  EXPECT_NEAR(otherSum / ownSum, 1.0, 0.02);
  for (const char* bad : {"-1", "4294967296"}) {
    const RunResult result = runGlint(folder, std::string("render sphere --size 16x16 -o bad.png --pattern-seed ") + bad);
    expectOneLineError(result, "--pattern-seed must be a whole number in [0, 4294967295]");
    EXPECT_FALSE(std::filesystem::exists(folder / "bad.png"));
  }
}

TEST(ExportCli, ExportsALoadedFileAndAddsGlintLayers) {
  const auto folder = temporaryFolder("export_loaded");
  const std::string input = writeSeparateGltf(scene::makeBuiltinScene("carpaint"), folder, "car").string();
  const RunResult result = runGlint(folder, "export '" + input + "' -o glinting.glb --glint-material floor --log-density 20");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  const std::string json = slurp(folder / "glinting.glb");
  EXPECT_NE(json.find(R"("name":"floor")"), std::string::npos);
  // Both materials now carry a layer, each with the overridden density.
  std::size_t layers = 0;
  for (std::size_t at = json.find(R"("logDensity":20.0)"); at != std::string::npos; at = json.find(R"("logDensity":20.0)", at + 1)) {
    ++layers;
  }
  EXPECT_EQ(layers, 2u) << json.substr(0, 2000);
}

TEST(ExportCli, ErrorsGiveOneLineAndNoFile) {
  const auto folder = temporaryFolder("export_errors");
  auto expectExportFails = [&](const std::string& arguments, const std::string& output, const std::string& problem) {
    expectOneLineError(runGlint(folder, "export " + arguments + " -o " + output), problem);
    EXPECT_FALSE(std::filesystem::exists(folder / output)) << output;
  };
  expectExportFails("castle", "castle.glb", "unknown scene 'castle'");
  expectExportFails("sphere", "missing/sphere.glb", "missing/sphere.glb: cannot create");
  expectExportFails("sphere", "sphere.obj", "sphere.obj: a glTF file must end in .glb or .gltf");
  expectExportFails("sphere --glint-material Nope", "sphere.glb", "no material 'Nope'");
  expectExportFails("sphere --relative-area 2", "sphere.glb", "relative_area");
  std::filesystem::create_directory(folder / "taken.glb");  // a folder where the file would go
  expectOneLineError(runGlint(folder, "export sphere -o taken.glb"), "taken.glb: cannot write");
  EXPECT_TRUE(std::filesystem::is_empty(folder / "taken.glb"));
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    EXPECT_EQ(entry.path().string().find(".tmp"), std::string::npos) << "left behind: " << entry.path();
  }
}

// How often `text` occurs in `within`.
std::size_t occurrences(const std::string& within, const std::string& text) {
  std::size_t count = 0;
  for (std::size_t at = within.find(text); at != std::string::npos; at = within.find(text, at + 1)) ++count;
  return count;
}

// The glint layer's two forms through the command: a bad value in EXT_materials_glint or in
// extras.glint is one line naming the file, the material and the field, and no file is written;
// 0 and 1 are booleans; a file with extras.glint alone gets one line suggesting a re-export, one
// with both forms one warning line.
TEST(ExportCli, GlintLayerFormsErrorsAndNotes) {
  const auto folder = temporaryFolder("export_glint_forms");
  writeSeparateGltf(texturedTestScene(), folder, "textured");
  const std::filesystem::path path = folder / "textured.gltf";
  const nlohmann::json original = nlohmann::json::parse(slurp(path));
  auto withMaterial = [&](const std::function<void(nlohmann::json&)>& edit) {
    nlohmann::json document = original;
    edit(document["materials"][0]);
    std::ofstream(path) << document.dump();
  };
  auto exportFile = [&] { return runGlint(folder, "export textured.gltf -o out.gltf"); };
  const std::string where = "glint: error: textured.gltf: material 0 'textured': ";
  for (const nlohmann::json& bad : {nlohmann::json(2), nlohmann::json("yes"), nlohmann::json(0.5)}) {
    SCOPED_TRACE(bad.dump());
    const std::string got = bad.is_string() ? "the string " + bad.dump() : bad.dump();
    withMaterial([&](nlohmann::json& m) { m["extensions"]["EXT_materials_glint"]["randomColors"] = bad; });
    expectOneLineError(exportFile(), where + "EXT_materials_glint: randomColors must be true or false (or 0 or 1), got " + got);
    EXPECT_FALSE(std::filesystem::exists(folder / "out.gltf"));
    withMaterial([&](nlohmann::json& m) {
      m["extensions"].erase("EXT_materials_glint");
      m["extras"]["glint"] = {{"random_colours", bad}};
    });
    expectOneLineError(exportFile(), where + "extras.glint: random_colours must be true or false (or 0 or 1), got " + got);
    EXPECT_FALSE(std::filesystem::exists(folder / "out.gltf"));
  }

  withMaterial([](nlohmann::json& m) {
    m["extensions"]["EXT_materials_glint"]["randomColors"] = 1;
    m["extensions"]["EXT_materials_glint"]["multipleScattering"] = 0;
  });
  RunResult result = exportFile();
  ASSERT_EQ(result.exitCode, 0) << result.err;
  const nlohmann::json written = nlohmann::json::parse(slurp(folder / "out.gltf"));
  EXPECT_EQ(written["materials"][0]["extensions"]["EXT_materials_glint"]["randomColors"], true);
  EXPECT_EQ(written["materials"][0]["extensions"]["EXT_materials_glint"]["multipleScattering"], false);
  EXPECT_EQ(occurrences(result.err, "extras.glint"), 0u) << result.err;

  withMaterial([](nlohmann::json& m) {
    m["extensions"].erase("EXT_materials_glint");
    m["extras"]["glint"] = {{"log_density", 20}};
  });
  result = exportFile();
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_EQ(occurrences(result.err, "extras.glint"), 1u) << result.err;
  EXPECT_NE(result.err.find("glint: textured.gltf: glint layers read from extras.glint, the older form (material 0 "
                            "'textured'); glint export writes them as EXT_materials_glint\n"),
            std::string::npos)
      << result.err;
  // What it wrote is the extension, with the extras' value.
  EXPECT_EQ(nlohmann::json::parse(slurp(folder / "out.gltf"))["materials"][0]["extensions"]["EXT_materials_glint"]["logDensity"],
            20.0);

  withMaterial([](nlohmann::json& m) { m["extras"]["glint"] = {{"log_density", 20}}; });
  result = exportFile();
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_EQ(occurrences(result.err, "extras.glint"), 1u) << result.err;
  EXPECT_NE(result.err.find("glint: warning: textured.gltf: extras.glint is not read where a material has "
                            "EXT_materials_glint, whose values win (material 0 'textured')\n"),
            std::string::npos)
      << result.err;
}

// The test scene laid out as separate files (scene/textured.gltf, textured.bin, image0.png for the
// base colour, ...) in a fresh folder; `damage` breaks the copy.
std::filesystem::path brokenScene(const std::string& name, const std::function<void(const std::filesystem::path&)>& damage) {
  const auto folder = temporaryFolder("broken_" + name);
  std::filesystem::create_directory(folder / "scene");
  writeSeparateGltf(texturedTestScene(), folder / "scene", "textured");
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
  auto missingBuffer = brokenScene("buffer", [](const auto& f) { std::filesystem::remove(f / "textured.bin"); });
  expectRenderFails(missingBuffer, "scene/textured.gltf", "textured.bin");
  auto badJson = brokenScene("json", [](const auto& f) { replaceInFile(f / "textured.gltf", "{", "{,"); });
  expectRenderFails(badJson, "scene/textured.gltf", "textured.gltf");
  auto missingTexture = brokenScene("texture", [](const auto& f) { std::filesystem::remove(f / "image0.png"); });
  expectRenderFails(missingTexture, "scene/textured.gltf", "image0.png");
  const auto folder = temporaryFolder("render_errors");
  std::ofstream(folder / "empty.glb") << "";
  expectRenderFails(folder, "empty.glb", "empty.glb");
  writeSeparateGltf(texturedTestScene(), folder, "textured");
  expectRenderFails(folder, "textured.gltf --glint-material Nope", "no material 'Nope'");
  expectRenderFails(folder, "castle", "unknown scene 'castle'");
  expectRenderFails(folder, "sphere --camera drone", "no camera 'drone'");
  expectRenderFails(folder, "sphere --brdf phong", "unknown BRDF 'phong'");
  expectRenderFails(folder, "sphere --size 0x10", "--size");
  expectRenderFails(folder, "sphere --log-density nan", "log_density");
  expectRenderFails(folder, "sphere --relative-area 2", "relative_area");
  expectRenderFails(folder, "sphere --lod fast", "--lod must be \"paper\", \"consistent\" or \"tree\", got \"fast\"");
  expectRenderFails(folder, "sphere --dict missing.gdict", "missing.gdict: cannot open");
  expectRenderFails(folder, "sphere --shadows maybe", "--shadows must be on or off, got 'maybe'");
  expectRenderFails(folder, "sphere --shadow-cascades 0", "--shadow-cascades must be from 1 to 4, got 0");
  expectRenderFails(folder, "sphere --shadow-cascades 5", "--shadow-cascades must be from 1 to 4, got 5");
  expectRenderFails(folder, "sphere --msaa 3", "--msaa must be a power of two");
  expectRenderFails(folder, "sphere --msaa 4096", "--msaa must be a power of two");
  const RunResult wrongExtension = runGlint(folder, "render sphere -o out.jpg --size 32x32");
  expectOneLineError(wrongExtension, "out.jpg: the output must end in .png or .exr");
}

// A full disk (/dev/full, reached by a name with the image's extension) stops the command with one
// line naming the file and the system's reason, a non-zero exit and no file left behind.
TEST(RenderCli, AFullDiskSaysSoNamingTheFile) {
  if (!std::filesystem::is_character_file("/dev/full")) GTEST_SKIP() << "needs /dev/full (Linux)";
  const auto folder = temporaryFolder("render_full_disk");
  for (const char* name : {"full.png", "full.exr"}) {
    std::filesystem::create_symlink("/dev/full", folder / name);
    expectOneLineError(runGlint(folder, std::string("render sphere --size 16x16 -o ") + name),
                       std::string(name) + ": cannot write (No space left on device)");
  }
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    EXPECT_EQ(entry.path().string().find(".tmp"), std::string::npos) << "left behind: " << entry.path();
  }
}

// A texture whose bytes are no image, in a file of its own or as a data URI: the error names the
// glTF file, the image by index and file, and the reason (here glint's check before the decoder:
// neither is PNG or JPEG).
TEST(RenderCli, ATextureThatIsNotAnImageIsNamed) {
  const auto inFile = brokenScene("garbage_texture", [](const auto& f) {
    std::ofstream(f / "image0.png", std::ios::binary) << "these bytes are not a picture";
  });
  expectRenderFails(inFile, "scene/textured.gltf",
                    "scene/textured.gltf: image 0 'image0.png': not a PNG or JPEG image (the formats glTF 2.0 allows)");
  const auto inDataUri = brokenScene("garbage_data_uri", [](const auto& f) {
    editGltfJson(f / "textured.gltf", [](nlohmann::json& d) {
      nlohmann::json image = nlohmann::json::object();
      image["uri"] = "data:image/png;base64,aGVsbG8gd29ybGQ=";  // "hello world"
      d["images"][1] = image;
    });
  });
  expectRenderFails(inDataUri, "scene/textured.gltf", "scene/textured.gltf: image 1: not a PNG or JPEG image");
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
  const auto folder = brokenScene("unread", [](const auto& f) {
    editGltfJson(f / "textured.gltf", [](nlohmann::json& d) {
      d["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["texCoord"] = 1;
      d["extensionsUsed"].push_back("KHR_materials_sheen");
    });
  });
  const RunResult result = runGlint(folder, "render scene/textured.gltf -o out.png --size 32x32");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_NE(result.err.find("glint: warning: scene/textured.gltf: extension KHR_materials_sheen is not read\n"),
            std::string::npos)
      << result.err;
  EXPECT_NE(result.err.find("glint: warning: scene/textured.gltf: textures on a texCoord other than 0 are mapped with "
                            "TEXCOORD_0 (material 0 'textured' baseColorTexture)\n"),
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
  expectOneLineError(runGlint(folder, "view sphere --width 10 --frames 1"), "--width and --height must be in [64, 8192], got 10x720");
  expectOneLineError(runGlint(folder, "view sphere --screenshot shot.png"), "--screenshot needs --frames N");
  // The screenshot is a PNG, whatever name it is given: another extension is refused, not written
  // as PNG bytes under it; so is a name without a place, before a window opens.
  expectOneLineError(runGlint(folder, "view sphere --frames 1 --screenshot shot.exr"), "shot.exr: the screenshot must end in .png");
  expectOneLineError(runGlint(folder, "view sphere --frames 1 --screenshot nodir/shot.png"), "nodir/shot.png: cannot create");
  EXPECT_FALSE(std::filesystem::exists(folder / "shot.exr"));
}

// The viewer opens on exactly what `glint render` draws: for every built-in scene but the two at the
// paper's scale, which add nothing to it but time (and a camera other than the default, footprint
// policies and cascade counts the panel starts from, and each cost tier), its first frame with the
// panel hidden equals render's PNG of the same scene, camera, options and size, pixel for pixel
// (both go through kernel/tonemap.h's display transform and its rounding to 8 bits). One virtual X
// server runs all the viewers.
TEST(ViewCli, FirstFrameEqualsRenderForEveryBuiltinScene) {
  ASSERT_EQ(std::system("command -v xvfb-run > /dev/null"), 0) << "xvfb-run is missing (scripts/deps installs it)";
  const auto folder = temporaryFolder("view_equals_render");
  std::vector<std::array<std::string, 3>> cases;  // scene, camera, options of both
  for (const std::string& name : smallBuiltinSceneNames()) cases.push_back({name, "default", ""});
  cases.push_back({"arctic", "ornament", " --shadow-cascades 1"});
  cases.push_back({"grazing-rough", "default", " --footprint cells=24"});  // one of the panel's policies
  cases.push_back({"grazing-rough", "default", " --footprint cells=32"});  // one it adds
  // Each cost tier (docs/cli.md, "Cost tiers"): the viewer starts from the tier's footprint,
  // anti-aliasing and cascades as render takes them.
  for (const char* tier : {"low", "medium", "high", "exact"}) cases.push_back({"carpaint", "default", std::string(" --quality ") + tier});
  std::string views;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const auto& [name, camera, extra] = cases[i];
    const std::string shot = std::to_string(i) + ".png";
    const RunResult render =
        runGlint(folder, "render " + name + " --camera " + camera + extra + " --size 128x96 -o render" + shot);
    ASSERT_EQ(render.exitCode, 0) << render.err;
    views += std::string(views.empty() ? "" : " && ") + "'" GLINT_EXECUTABLE "' view " + name + " --camera " + camera +
             extra + " --width 128 --height 96 --frames 1 --hide-panel --screenshot view" + shot;
  }
  const std::string command = "cd '" + folder.string() + "' && xvfb-run -a -s '-screen 0 640x480x24' sh -c \"" + views +
                              "\" 2> stderr.txt";
  ASSERT_EQ(std::system(command.c_str()), 0) << slurp(folder / "stderr.txt");
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const std::string label = cases[i][0] + " --camera " + cases[i][1] + cases[i][2];
    const ImageRgbF rendered = readImage(folder / ("render" + std::to_string(i) + ".png"));
    const ImageRgbF viewed = readImage(folder / ("view" + std::to_string(i) + ".png"));
    ASSERT_EQ(viewed.width, rendered.width) << label;
    ASSERT_EQ(viewed.height, rendered.height) << label;
    int differing = 0;
    int maxLevels = 0;
    for (std::size_t p = 0; p < rendered.pixels.size(); ++p) {
      int levels = 0;
      for (int c = 0; c < 3; ++c) {
        levels = std::max(levels, std::abs(linearToSrgb8(viewed.pixels[p][c]) - linearToSrgb8(rendered.pixels[p][c])));
      }
      differing += levels > 0;
      maxLevels = std::max(maxLevels, levels);
    }
    EXPECT_EQ(differing, 0) << label << ": " << differing << " of " << rendered.pixels.size()
                            << " pixels differ, by up to " << maxLevels << " levels of 255";
  }
}

}  // namespace
}  // namespace glint
