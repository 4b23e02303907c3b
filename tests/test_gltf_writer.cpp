// The glTF writer (scene/gltf_writer.h): every built-in scene and a scene that uses every texture
// slot, extension and light type read back by the loader as the same scene, every glint field
// through EXT_materials_glint; errors leave no file.
// Rendering an exported file against its built-in scene: tests/test_render_cli.cpp.
#include <cmath>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "glint/error.h"
#include "scene/builtin_scenes.h"
#include "scene/gltf_loader.h"
#include "scene/gltf_writer.h"
#include "scene_support.h"
#include "test_support.h"

namespace glint::scene {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// The loader normalises normals in double and takes tangents through Gram-Schmidt again: a unit
// vector written as floats comes back within a few float ulps of itself.
constexpr float kUnitVectorTolerance = 1e-6f;

void expectSameTexture(const Scene& a, int ia, const Scene& b, int ib, const char* slot) {
  SCOPED_TRACE(slot);
  ASSERT_EQ(ia < 0, ib < 0);
  if (ia < 0) return;
  const Texture& ta = a.textures[static_cast<std::size_t>(ia)];
  const Texture& tb = b.textures[static_cast<std::size_t>(ib)];
  EXPECT_EQ(ta.width, tb.width);
  EXPECT_EQ(ta.height, tb.height);
  EXPECT_EQ(ta.srgb, tb.srgb);
  EXPECT_TRUE(ta.rgba == tb.rgba) << "texels differ";
  EXPECT_TRUE(ta.sampler == tb.sampler) << "samplers differ";
}

void expectSameUv(const UvTransform& a, const UvTransform& b) {
  EXPECT_EQ(a.offset, b.offset);
  EXPECT_EQ(a.rotation, b.rotation);
  EXPECT_EQ(a.scale, b.scale);
}

// `loaded` (the file written from `original`, read back) is `original`, save the environment and
// the exposure, which glTF cannot hold, and unit vectors, which come back within
// kUnitVectorTolerance.
void expectSameScene(const Scene& original, const Scene& loaded) {
  ASSERT_EQ(loaded.meshes.size(), original.meshes.size());
  for (std::size_t m = 0; m < original.meshes.size(); ++m) {
    const Mesh& a = original.meshes[m];
    const Mesh& b = loaded.meshes[m];
    SCOPED_TRACE(a.name);
    EXPECT_EQ(a.name, b.name);
    EXPECT_EQ(a.material, b.material);
    EXPECT_EQ(a.indices, b.indices);
    ASSERT_EQ(a.vertices.size(), b.vertices.size());
    int different = 0;
    for (std::size_t i = 0; i < a.vertices.size(); ++i) {
      const Vertex& u = a.vertices[i];
      const Vertex& v = b.vertices[i];
      const bool same = u.position == v.position && u.uv == v.uv && u.colour == v.colour &&
                        glm::length(u.normal - v.normal) <= kUnitVectorTolerance &&
                        glm::length(glm::vec3(u.tangent) - glm::vec3(v.tangent)) <= kUnitVectorTolerance &&
                        u.tangent.w == v.tangent.w;
      different += same ? 0 : 1;
    }
    EXPECT_EQ(different, 0) << "vertices that did not come back";
  }
  ASSERT_EQ(loaded.materials.size(), original.materials.size());
  for (std::size_t m = 0; m < original.materials.size(); ++m) {
    const Material& a = original.materials[m];
    const Material& b = loaded.materials[m];
    SCOPED_TRACE(a.name);
    EXPECT_EQ(a.name, b.name);
    EXPECT_EQ(a.baseColour, b.baseColour);
    EXPECT_EQ(a.metallic, b.metallic);
    EXPECT_EQ(a.roughness, b.roughness);
    EXPECT_EQ(a.normalScale, b.normalScale);
    EXPECT_EQ(a.emissive, b.emissive);
    EXPECT_EQ(a.occlusionStrength, b.occlusionStrength);
    EXPECT_EQ(a.doubleSided, b.doubleSided);
    EXPECT_EQ(a.alphaMode, b.alphaMode);
    EXPECT_EQ(a.alphaCutoff, b.alphaCutoff);
    expectSameTexture(original, a.baseColourTexture, loaded, b.baseColourTexture, "base colour");
    expectSameTexture(original, a.metallicRoughnessTexture, loaded, b.metallicRoughnessTexture, "metallic roughness");
    expectSameTexture(original, a.normalTexture, loaded, b.normalTexture, "normal");
    expectSameTexture(original, a.occlusionTexture, loaded, b.occlusionTexture, "occlusion");
    expectSameTexture(original, a.emissiveTexture, loaded, b.emissiveTexture, "emissive");
    expectSameUv(a.baseColourUv, b.baseColourUv);
    expectSameUv(a.metallicRoughnessUv, b.metallicRoughnessUv);
    expectSameUv(a.normalUv, b.normalUv);
    expectSameUv(a.occlusionUv, b.occlusionUv);
    expectSameUv(a.emissiveUv, b.emissiveUv);
    EXPECT_EQ(a.clearcoat.factor, b.clearcoat.factor);
    EXPECT_EQ(a.clearcoat.roughness, b.clearcoat.roughness);
    EXPECT_EQ(a.clearcoat.normalScale, b.clearcoat.normalScale);
    expectSameTexture(original, a.clearcoat.texture, loaded, b.clearcoat.texture, "clearcoat");
    expectSameTexture(original, a.clearcoat.roughnessTexture, loaded, b.clearcoat.roughnessTexture, "clearcoat roughness");
    expectSameTexture(original, a.clearcoat.normalTexture, loaded, b.clearcoat.normalTexture, "clearcoat normal");
    expectSameUv(a.clearcoat.uv, b.clearcoat.uv);
    expectSameUv(a.clearcoat.roughnessUv, b.clearcoat.roughnessUv);
    expectSameUv(a.clearcoat.normalUv, b.clearcoat.normalUv);
    EXPECT_EQ(a.specular.ndf, b.specular.ndf);
    EXPECT_EQ(a.specular.masking, b.specular.masking);
    EXPECT_EQ(a.specular.multipleScattering, b.specular.multipleScattering);
    const GlintLayer& g = a.glint;
    const GlintLayer& h = b.glint;
    ASSERT_EQ(g.enabled, h.enabled);
    if (!g.enabled) continue;
    EXPECT_EQ(g.alpha, h.alpha);
    EXPECT_EQ(g.rho, h.rho);
    EXPECT_EQ(g.logDensity, h.logDensity);
    EXPECT_EQ(g.relativeArea, h.relativeArea);
    EXPECT_EQ(g.densityRandomisation, h.densityRandomisation);
    EXPECT_EQ(g.maxAnisotropy, h.maxAnisotropy);
    EXPECT_EQ(g.patternSeed, h.patternSeed);
    EXPECT_EQ(g.uvScale, h.uvScale);
    EXPECT_EQ(g.colouredCells, h.colouredCells);
    EXPECT_EQ(g.lod, h.lod);
    EXPECT_EQ(g.logDensityRange, h.logDensityRange);
    expectSameTexture(original, g.roughnessTexture, loaded, h.roughnessTexture, "glint roughness");
    expectSameTexture(original, g.logDensityTexture, loaded, h.logDensityTexture, "glint log density");
    expectSameTexture(original, g.relativeAreaTexture, loaded, h.relativeAreaTexture, "glint relative area");
  }
  ASSERT_EQ(loaded.lights.size(), original.lights.size());
  for (std::size_t l = 0; l < original.lights.size(); ++l) {
    const Light& a = original.lights[l];
    const Light& b = loaded.lights[l];
    SCOPED_TRACE("light " + std::to_string(l));
    EXPECT_EQ(a.type, b.type);
    EXPECT_EQ(a.intensity, b.intensity);
    EXPECT_EQ(a.range, b.range);
    if (a.positional()) EXPECT_EQ(a.position, b.position);
    if (a.type == Light::Type::Spot) {
      EXPECT_EQ(a.innerConeAngle, b.innerConeAngle);
      EXPECT_EQ(a.outerConeAngle, b.outerConeAngle);
    }
    if (a.type != Light::Type::Point) EXPECT_LE(glm::length(a.spotAxis() - b.spotAxis()), kUnitVectorTolerance);
    if (a.type == Light::Type::Directional) EXPECT_LE(glm::length(a.direction - b.direction), kUnitVectorTolerance);
  }
  ASSERT_EQ(loaded.cameras.size(), original.cameras.size());
  for (const auto& [name, a] : original.cameras) {
    SCOPED_TRACE("camera " + name);
    ASSERT_TRUE(loaded.cameras.contains(name));
    const Camera& b = loaded.cameras.at(name);
    EXPECT_EQ(a.position, b.position);
    EXPECT_EQ(a.projection, b.projection);
    EXPECT_EQ(a.verticalFovDegrees, b.verticalFovDegrees);
    EXPECT_EQ(a.orthographicHalfHeight, b.orthographicHalfHeight);
    // The loader puts the target on the view ray (at the scene centre's distance) and takes +y of
    // the camera's node as its up: the same view, with up made perpendicular to it.
    const glm::vec3 forwardA = glm::normalize(a.target - a.position);
    const glm::vec3 forwardB = glm::normalize(b.target - b.position);
    EXPECT_LE(glm::length(forwardA - forwardB), kUnitVectorTolerance);
    const glm::vec3 rightA = glm::normalize(glm::cross(forwardA, a.up));
    const glm::vec3 rightB = glm::normalize(glm::cross(forwardB, b.up));
    EXPECT_LE(glm::length(rightA - rightB), kUnitVectorTolerance);
  }
  EXPECT_TRUE(loaded.unreadFeatures.empty());
  EXPECT_TRUE(loaded.notes.empty());
}

TEST(GltfWriter, EveryBuiltinSceneReadsBackAsItself) {
  const fs::path folder = test::temporaryFolder("gltf_writer_builtin");
  for (const std::string& name : builtinSceneNames()) {
    SCOPED_TRACE(name);
    const Scene original = makeBuiltinScene(name);
    const fs::path path = folder / (name + ".glb");
    writeGltf(path, original);
    const Scene loaded = loadGltf(path);
    EXPECT_EQ(loaded.name, name);
    expectSameScene(original, loaded);
  }
}

TEST(GltfWriter, EveryTextureSlotExtensionAndLightReadsBack) {
  const Scene original = test::texturedTestScene();
  const fs::path folder = test::temporaryFolder("gltf_writer_textured");
  for (const char* file : {"textured.glb", "textured.gltf"}) {
    SCOPED_TRACE(file);
    writeGltf(folder / file, original);
    expectSameScene(original, loadGltf(folder / file));
  }
  // The laid-out form the tests break (scene_support.h) is the same scene too.
  expectSameScene(original, loadGltf(test::writeSeparateGltf(original, folder, "separate")));
  // What the extensions and extras look like in the file.
  const json document = json::parse(std::ifstream(folder / "textured.gltf"));
  EXPECT_EQ(document["extensionsUsed"], json({"KHR_texture_transform", "KHR_materials_emissive_strength",
                                              "KHR_materials_clearcoat", "EXT_materials_glint", "KHR_lights_punctual"}));
  const json& coat = document["materials"][0]["extensions"]["KHR_materials_clearcoat"];
  EXPECT_EQ(coat["clearcoatFactor"], 0.8);
  EXPECT_EQ(coat["clearcoatRoughnessFactor"], 0.15);
  EXPECT_EQ(coat["clearcoatNormalTexture"]["scale"], 0.5);
  EXPECT_TRUE(coat["clearcoatTexture"]["extensions"].contains("KHR_texture_transform"));
  EXPECT_FALSE(document["materials"][1].value("extensions", json::object()).contains("KHR_materials_clearcoat"));
  const json& glint = document["materials"][0]["extensions"]["EXT_materials_glint"];
  EXPECT_EQ(glint["alpha"], json({0.3, 0.2}));
  EXPECT_EQ(glint["logDensity"], 18.5);
  EXPECT_EQ(glint["patternSeed"], 3000000000.0);
  EXPECT_EQ(glint["roughnessTexture"], json({{"index", 1}}));
  EXPECT_FALSE(document["materials"][0].contains("extras"));
  // A material without a glint layer carries no glint extras, but the test scene's lobe is the
  // paper's, not glTF's: said in extras.glint_specular.
  EXPECT_EQ(document["materials"][1]["extras"],
            json({{"glint_specular", {{"ndf", "beckmann"}, {"masking", "v-cavity"}, {"multiple_scattering", false}}}}));
  EXPECT_EQ(document["materials"][0]["extensions"]["KHR_materials_emissive_strength"]["emissiveStrength"], 4.0);
  EXPECT_TRUE(document["meshes"][1]["primitives"][0]["attributes"].contains("COLOR_0"));
  EXPECT_FALSE(document["meshes"][0]["primitives"][0]["attributes"].contains("COLOR_0"));  // all white
  EXPECT_EQ(document["images"][0]["mimeType"], "image/png");
  // An embedded image keeps its texture's name (an external one is known by its file name).
  const Scene loaded = loadGltf(folder / "textured.glb");
  for (std::size_t t = 0; t < original.textures.size(); ++t) EXPECT_EQ(loaded.textures[t].name, original.textures[t].name);
}

// Every field of a glint layer and its specular target, none at its default, goes through
// EXT_materials_glint and comes back; glTF's target on a layer too. The extension is used, not
// required: a viewer without it still opens the file and draws the core material.
TEST(GltfWriter, EveryGlintFieldRoundTripsThroughTheExtension) {
  Scene original = test::texturedTestScene();
  GlintLayer& layer = original.materials[0].glint;
  layer.alpha = glm::vec2(0.25f, 0.125f);
  layer.rho = -0.5f;
  layer.logDensity = 21.25f;
  layer.relativeArea = 0.75f;
  layer.densityRandomisation = 3.5f;
  layer.maxAnisotropy = 12.0f;
  layer.patternSeed = 4294967295u;
  layer.uvScale = 2.5f;
  layer.colouredCells = true;
  layer.lod = kernel::GLINT_LOD_CONSISTENT;
  layer.logDensityRange = glm::vec2(12.0f, 33.0f);
  layer.roughnessTexture = 1;  // the linear textures: metallic-roughness, normal, occlusion
  layer.logDensityTexture = 2;
  layer.relativeAreaTexture = 3;
  original.materials[0].specular = {kernel::GLINT_NDF_BECKMANN, kernel::GLINT_MASKING_VCAVITY, false};
  original.materials[1].glint.enabled = true;
  original.materials[1].glint.lod = kernel::GLINT_LOD_TREE;  // the third construction, on the other layer
  original.materials[1].specular = kGltfSpecular;
  const fs::path folder = test::temporaryFolder("gltf_writer_glint_fields");
  for (const char* file : {"fields.glb", "fields.gltf"}) {
    SCOPED_TRACE(file);
    writeGltf(folder / file, original);
    expectSameScene(original, loadGltf(folder / file));
  }
  const json document = json::parse(std::ifstream(folder / "fields.gltf"));
  EXPECT_FALSE(document.contains("extensionsRequired"));
  const json expected = {{"ndf", "beckmann"},
                         {"masking", "v-cavity"},
                         {"multipleScattering", false},
                         {"alpha", {0.25, 0.125}},
                         {"rho", -0.5},
                         {"logDensity", 21.25},
                         {"relativeArea", 0.75},
                         {"densityRandomization", 3.5},
                         {"maxAnisotropy", 12.0},
                         {"patternSeed", 4294967295.0},
                         {"uvScale", 2.5},
                         {"randomColors", true},
                         {"lod", "consistent"},
                         {"logDensityRange", {12.0, 33.0}},
                         {"roughnessTexture", {{"index", 1}}},
                         {"logDensityTexture", {{"index", 2}}},
                         {"relativeAreaTexture", {{"index", 3}}}};
  EXPECT_EQ(document["materials"][0]["extensions"]["EXT_materials_glint"], expected);
  EXPECT_EQ(document["materials"][1]["extensions"]["EXT_materials_glint"]["ndf"], "ggx");
  EXPECT_EQ(document["materials"][1]["extensions"]["EXT_materials_glint"]["masking"], "smith");
  EXPECT_EQ(document["materials"][1]["extensions"]["EXT_materials_glint"]["multipleScattering"], true);
  EXPECT_EQ(document["materials"][1]["extensions"]["EXT_materials_glint"]["lod"], "tree");
  for (const json& material : document["materials"]) EXPECT_FALSE(material.contains("extras")) << material.dump();
}

// A file written from a loaded file is the loaded scene again.
TEST(GltfWriter, ALoadedFileWritesBackAsItself) {
  const fs::path folder = test::temporaryFolder("gltf_writer_again");
  writeGltf(folder / "first.glb", test::texturedTestScene());
  const Scene first = loadGltf(folder / "first.glb");
  writeGltf(folder / "second.gltf", first);
  expectSameScene(first, loadGltf(folder / "second.gltf"));
}

// What glint made for a loaded file (the two lights it invents for a file without lights, the
// bounding-box presets and the "default" that stands for the file's first camera) is not written
// back as if the file had it; --with-defaults writes it.
TEST(GltfWriter, NothingInventedIsWrittenUnlessAsked) {
  const fs::path folder = test::temporaryFolder("gltf_writer_invented");
  Scene bare = makeBuiltinScene("sphere");
  bare.lights.clear();
  bare.cameras.clear();
  writeGltf(folder / "bare.glb", bare);
  const Scene loaded = loadGltf(folder / "bare.glb");
  ASSERT_TRUE(loaded.defaultLights);
  ASSERT_EQ(loaded.lights.size(), 2u);
  ASSERT_EQ(loaded.cameras.size(), 5u);  // default, front, side, top, close
  const auto parsed = [&](const char* file) { return json::parse(std::ifstream(folder / file)); };
  writeGltf(folder / "again.gltf", loaded);
  const json again = parsed("again.gltf");
  EXPECT_FALSE(again.contains("cameras")) << again.dump().substr(0, 200);
  EXPECT_FALSE(again.contains("extensions") && again["extensions"].contains("KHR_lights_punctual"));
  expectSameScene(loaded, loadGltf(folder / "again.gltf"));  // glint lights and frames it the same
  writeGltf(folder / "defaults.gltf", loaded, true);
  const json defaults = parsed("defaults.gltf");
  EXPECT_EQ(defaults["cameras"].size(), 5u);
  EXPECT_EQ(defaults["extensions"]["KHR_lights_punctual"]["lights"].size(), 2u);

  // A file's cameras: written once each (not again as "default"), its first camera first, so that
  // it is the default view when read back, whatever the names' order.
  Scene framed = bare;
  framed.cameras["zenith"] = Camera{{0.0f, 4.0f, 0.5f}, glm::vec3(0.0f), {0, 1, 0}};
  framed.cameras["apse"] = Camera{{3.0f, 0.5f, 0.0f}, glm::vec3(0.0f), {0, 1, 0}};
  framed.cameras["default"] = framed.cameras["zenith"];  // as the loader names a file's first camera
  writeGltf(folder / "framed.gltf", framed);
  const json cameras = parsed("framed.gltf")["cameras"];
  ASSERT_EQ(cameras.size(), 2u);
  EXPECT_EQ(cameras[0]["name"], "zenith");
  const Scene reread = loadGltf(folder / "framed.gltf");
  EXPECT_EQ(reread.cameras.at("default").position, glm::vec3(0.0f, 4.0f, 0.5f));
}

TEST(GltfWriter, SaysWhatGltfCannotHold) {
  Scene scene = makeBuiltinScene("carpaint");
  EXPECT_EQ(gltfLosses(scene), std::vector<std::string>{"the environment (an environment map)"});
  scene.environment = Environment{};
  scene.exposure = 2.0f;
  EXPECT_EQ(gltfLosses(scene), (std::vector<std::string>{"the environment (a uniform ambient light)", "the exposure 2"}));
}

using test::errorOf;
TEST(GltfWriter, ErrorsNameTheFileAndLeaveNone) {
  const fs::path folder = test::temporaryFolder("gltf_writer_errors");
  const Scene sphere = makeBuiltinScene("sphere");
  EXPECT_EQ(errorOf([&] { writeGltf(folder / "sphere.obj", sphere); }),
            (folder / "sphere.obj").string() + ": a glTF file must end in .glb or .gltf");
  EXPECT_NE(errorOf([&] { writeGltf(folder / "missing" / "sphere.glb", sphere); }).find("cannot create"), std::string::npos);
  Scene broken = sphere;
  broken.meshes[0].material = 3;
  EXPECT_EQ(errorOf([&] { writeGltf(folder / "broken.glb", broken); }),
            (folder / "broken.glb").string() + ": mesh 'sphere': material 3 does not exist");
  broken = sphere;
  broken.meshes.clear();
  EXPECT_NE(errorOf([&] { writeGltf(folder / "empty.glb", broken); }).find("no triangles"), std::string::npos);
  EXPECT_TRUE(fs::is_empty(folder)) << "a file or a temporary was left behind";
}

}  // namespace
}  // namespace glint::scene
