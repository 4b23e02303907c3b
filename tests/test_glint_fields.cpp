// The glint layer's one table of fields (src/glint/glint_fields.h) and what is made of it: the
// extension's schema in the repository is what `glint extension-schema` writes; the scene's layer,
// the model's defaults, validation, the glTF reader and `glint eval` take their defaults, ranges and
// names from the table. (The three.js package checks its fields against the schema in
// web/three/test/bad-input.mjs, the Blender add-on in tests/blender.)
#include <cmath>
#include <filesystem>
#include <limits>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "glint/bsdf.h"
#include "glint/error.h"
#include "glint/glint_fields.h"
#include "scene/gltf_glint.h"
#include "scene/scene.h"
#include "test_support.h"

namespace glint {
namespace {

using nlohmann::json;
using namespace glint::test;

const std::filesystem::path kSchemaFile = std::filesystem::path(GLINT_SOURCE_DIR) /
                                          "extensions/EXT_materials_glint/schema/material.EXT_materials_glint.schema.json";

TEST(GlintFields, TheRepositorysSchemaIsWhatGlintWritesFromTheTable) {
  EXPECT_TRUE(slurp(kSchemaFile) == scene::glintExtensionSchema())
      << kSchemaFile << " differs from `glint extension-schema`: write it with glint extension-schema -o " << kSchemaFile;
}

TEST(GlintFields, EveryFieldIsInTheSchemaWithItsDefaultAndRange) {
  const json schema = json::parse(slurp(kSchemaFile));
  const json& properties = schema.at("properties");
  EXPECT_EQ(properties.size(), kGlintFieldCount + 2);  // and extensions, extras
  for (const GlintFieldSpec& spec : kGlintFields) {
    SCOPED_TRACE(spec.extension);
    ASSERT_TRUE(properties.contains(spec.extension));
    const json& property = properties.at(spec.extension);
    EXPECT_EQ(property.at("description"), spec.meaning);
    EXPECT_EQ(property.contains("default"), spec.hasDefault);
    if (spec.kind == GlintFieldKind::Number || spec.kind == GlintFieldKind::Integer || spec.kind == GlintFieldKind::Pair) {
      const json& range = spec.kind == GlintFieldKind::Pair ? property.at("items") : property;
      EXPECT_EQ(range.at(spec.exclusiveMinimum ? "exclusiveMinimum" : "minimum").get<double>(), spec.minimum);
      EXPECT_EQ(range.at("maximum").get<double>(), spec.maximum);
    }
  }
}

TEST(GlintFields, TheScenesLayerAndTheModelDefaultToTheTable) {
  const scene::GlintLayer layer;
  EXPECT_EQ(layer.rho, glintField(GlintField::Rho).defaultValue);
  EXPECT_EQ(layer.logDensity, glintField(GlintField::LogDensity).defaultValue);
  EXPECT_EQ(layer.relativeArea, glintField(GlintField::RelativeArea).defaultValue);
  EXPECT_EQ(layer.densityRandomisation, glintField(GlintField::DensityRandomization).defaultValue);
  EXPECT_EQ(layer.maxAnisotropy, glintField(GlintField::MaxAnisotropy).defaultValue);
  EXPECT_EQ(layer.patternSeed, glintField(GlintField::PatternSeed).defaultValue);
  EXPECT_EQ(layer.uvScale, glintField(GlintField::UvScale).defaultValue);
  EXPECT_EQ(layer.colouredCells, glintField(GlintField::RandomColors).defaultValue != 0.0);
  EXPECT_EQ(layer.lod, glintField(GlintField::Lod).defaultValue);
  EXPECT_EQ(layer.logDensityRange.x, glintField(GlintField::LogDensityRange).defaultValue);
  EXPECT_EQ(layer.logDensityRange.y, glintField(GlintField::LogDensityRange).defaultSecond);
  const GlintParameters model = defaultGlintParameters();
  EXPECT_EQ(model.logDensity, layer.logDensity);
  EXPECT_EQ(model.densityRandomisation, layer.densityRandomisation);
  EXPECT_EQ(model.maxAnisotropy, layer.maxAnisotropy);
  EXPECT_EQ(model.relativeArea, layer.relativeArea);
  // glTF's specular target is the extension's default.
  EXPECT_EQ(scene::kGltfSpecular.ndf, glintField(GlintField::Ndf).defaultValue);
  EXPECT_EQ(scene::kGltfSpecular.masking, glintField(GlintField::Masking).defaultValue);
  EXPECT_EQ(scene::kGltfSpecular.multipleScattering, glintField(GlintField::MultipleScattering).defaultValue != 0.0);
}

// Each number's range as the reader applies it: the ends accepted (an exclusive minimum refused),
// a step past them refused with the table's bounds in the message.
TEST(GlintFields, TheGltfReaderTakesEachRangeFromTheTable) {
  const scene::GlintTextureSource noTextures{0, [](int) { return -1; }, [](const std::string&, const std::string&) {}};
  auto read = [&](const std::string& name, const json& value) {
    scene::readGlintLayer(json{{name, value}}, scene::GlintSpelling::Extension, 0.5f, scene::kGltfSpecular, noTextures);
  };
  for (const GlintFieldSpec& spec : kGlintFields) {
    if (spec.kind != GlintFieldKind::Number && spec.kind != GlintFieldKind::Pair && spec.kind != GlintFieldKind::Integer) {
      continue;
    }
    SCOPED_TRACE(spec.extension);
    auto value = [&](double v) { return spec.kind == GlintFieldKind::Pair ? json::array({v, v}) : json(v); };
    if (spec.kind == GlintFieldKind::Integer) {
      EXPECT_NO_THROW(read(spec.extension, static_cast<std::uint64_t>(spec.minimum)));
      EXPECT_NO_THROW(read(spec.extension, static_cast<std::uint64_t>(spec.maximum)));
      EXPECT_THROW(read(spec.extension, static_cast<std::uint64_t>(spec.maximum) + 1), Error);
      continue;
    }
    // One float step past each end (the reader holds 32-bit floats).
    const auto low = static_cast<float>(spec.minimum);
    const auto high = static_cast<float>(spec.maximum);
    const double below = std::nextafter(low, -std::numeric_limits<float>::infinity());
    const double above = std::nextafter(high, std::numeric_limits<float>::infinity());
    if (spec.exclusiveMinimum) {
      EXPECT_THROW(read(spec.extension, value(low)), Error);
    } else {
      EXPECT_NO_THROW(read(spec.extension, value(low)));
    }
    EXPECT_NO_THROW(read(spec.extension, value(high)));
    if (std::isfinite(above)) EXPECT_THROW(read(spec.extension, value(above)), Error);
    if (below >= -std::numeric_limits<float>::max() && !(spec.minimum > 0.0 && below <= 0.0 && spec.exclusiveMinimum)) {
      EXPECT_THROW(read(spec.extension, value(below)), Error);
    }
  }
}

TEST(GlintFields, ChoiceNamesAndTheKernelsConstantsAreTheTables) {
  EXPECT_EQ(ndfFromName("ndf", "ggx"), kernel::GLINT_NDF_GGX);
  EXPECT_EQ(ndfFromName("ndf", "beckmann"), kernel::GLINT_NDF_BECKMANN);
  EXPECT_EQ(maskingFromName("masking", "smith"), kernel::GLINT_MASKING_SMITH);
  EXPECT_EQ(maskingFromName("masking", "v-cavity"), kernel::GLINT_MASKING_VCAVITY);
  EXPECT_EQ(lodFromName("lod", "tree"), kernel::GLINT_LOD_TREE);
  EXPECT_EQ(std::string(lodName(kernel::GLINT_LOD_CONSISTENT)), "consistent");
  EXPECT_EQ(errorOf([] { lodFromName("lod", "tre"); }), "lod must be \"paper\", \"consistent\" or \"tree\", got \"tre\"");
  EXPECT_EQ(errorOf([] { ndfFromName("ndf", "phong"); }), "ndf must be \"beckmann\" or \"ggx\", got \"phong\"");
}

TEST(GlintFieldsCli, ExtensionSchemaWritesTheRepositorysSchema) {
  const std::filesystem::path folder = temporaryFolder("extension_schema");
  const RunResult toStdout = runGlint(folder, "extension-schema");
  ASSERT_EQ(toStdout.exitCode, 0) << toStdout.err;
  EXPECT_TRUE(toStdout.out == slurp(kSchemaFile));
  const RunResult toFile = runGlint(folder, "extension-schema -o schema.json");
  ASSERT_EQ(toFile.exitCode, 0) << toFile.err;
  EXPECT_TRUE(slurp(folder / "schema.json") == slurp(kSchemaFile));
  expectOneLineError(runGlint(folder, "extension-schema -o missing/schema.json"), "missing/schema.json");
}

}  // namespace
}  // namespace glint
