// The glint layer's parameters, defined once: each field's names (in code, in EXT_materials_glint,
// in extras.glint and `glint eval`), its type, its default, its range and one line of meaning.
// Everything else reads this table: the scene's layer (scene::GlintLayer's defaults), the model's
// defaults and validation (defaultGlintParameters, validateGlintParameters), the glTF reader and
// writer (scene/gltf_glint.cpp, scene/gltf_writer.cpp), `glint eval`, and the extension's JSON
// schema (`glint extension-schema` writes it; extensions/EXT_materials_glint/schema holds its
// output, tested equal). The three.js package and the Blender add-on check their field tables
// against that schema in their own tests.
//
// Each row names the field's member of the kernel's material block (kernel::GlintMaterial), which
// scene::GlintLayer is: the reader, the writer, `glint eval` and the defaults reach the member
// through the row, never by its name.
//
// Adding a parameter: a row here, a member in the kernel's GlintParameters (kernel/glint_parameters.h)
// and GlintMaterial (kernel/glint_material.h) and where the kernel uses it (docs/architecture.md,
// "Adding a material parameter").
#pragma once

#include <array>
#include <cstddef>
#include <limits>
#include <string_view>
#include <type_traits>
#include <variant>

#include "glint/kernel/glint_brdf.h"
#include "glint/kernel/glint_material.h"
#include "glint/kernel/microfacet_targets.h"

namespace glint {

// A glint layer's fields, in the order the extension's schema lists them.
enum class GlintField {
  Ndf,
  Masking,
  MultipleScattering,
  Alpha,
  Rho,
  LogDensity,
  RelativeArea,
  DensityRandomization,
  MaxAnisotropy,
  PatternSeed,
  UvScale,
  RandomColors,
  Lod,
  LogDensityRange,
  RoughnessTexture,
  LogDensityTexture,
  RelativeAreaTexture,
};
inline constexpr std::size_t kGlintFieldCount = 17;

// What a field holds. Number and Pair are 32-bit floats (a pair: two, each in the range); Integer a
// whole number; Choice one of a few names (stored as the index of the name, the kernel's constant);
// Texture a glTF textureInfo.
enum class GlintFieldKind { Number, Pair, Integer, Boolean, Choice, Texture };

// The field's member of the material block, by kind: Number float, Pair vec2, Integer and Boolean
// uint, Choice int; none for a texture (the scene's layer holds its index).
using GlintMaterialMember = std::variant<std::monostate, float kernel::GlintMaterial::*, glm::vec2 kernel::GlintMaterial::*,
                                         kernel::uint kernel::GlintMaterial::*, int kernel::GlintMaterial::*>;

struct GlintFieldSpec {
  GlintField field;
  const char* extension;  // EXT_materials_glint's name: glTF's camelCase, US spelling
  const char* extras;     // extras.glint's and `glint eval`'s name: snake_case
  GlintFieldKind kind;
  bool hasDefault;        // false: alpha (the material's roughness squared) and the textures (none)
  double defaultValue;    // Number, Integer, Boolean (0 or 1), Choice (the index of the name); Pair: both
  double defaultSecond;   // Pair: the second value
  double minimum;         // Number, Pair, Integer
  double maximum;
  bool exclusiveMinimum;  // the range is (minimum, maximum]
  std::array<const char*, 3> choices;  // Choice: the names, at the kernel's constants (nullptr past the last)
  const char* meaning;    // one or two sentences, as the extension's schema describes the field
  GlintMaterialMember member;
  // A Number the model takes as it is: its member of kernel::GlintParameters, which
  // validateGlintParameters checks against the range (nullptr for the others).
  float kernel::GlintParameters::*parameter = nullptr;
};

// The smallest positive and the largest 32-bit float: uvScale's range (it multiplies uv, so any
// positive float is meaningful).
inline constexpr double kSmallestPositiveFloat = 1.401298464324817e-45;
inline constexpr double kLargestFloat = 3.4028234663852886e38;

// clang-format off
inline constexpr std::array<GlintFieldSpec, kGlintFieldCount> kGlintFields = {{
  {GlintField::Ndf, "ndf", "ndf", GlintFieldKind::Choice, true, kernel::GLINT_NDF_GGX, 0, 0, 0, false,
   {"beckmann", "ggx", nullptr},
   "The smooth normal distribution that the glints converge to, and the material's lobe where glints are not rendered.",
   &kernel::GlintMaterial::ndf},
  {GlintField::Masking, "masking", "masking", GlintFieldKind::Choice, true, kernel::GLINT_MASKING_SMITH, 0, 0, 0, false,
   {"v-cavity", "smith", nullptr},
   "The masking-shadowing function of the specular lobe: height-correlated Smith, or the V-cavity model.",
   &kernel::GlintMaterial::masking},
  {GlintField::MultipleScattering, "multipleScattering", "multiple_scattering", GlintFieldKind::Boolean, true, 1, 0, 0, 0, false,
   {}, "Whether the energy that single scattering loses on rough surfaces is added back by a smooth compensation lobe.",
   &kernel::GlintMaterial::multipleScattering},
  {GlintField::Alpha, "alpha", "alpha", GlintFieldKind::Pair, false, 0, 0, 0.005, 2.0, false, {},
   "The roughness of the lobe the glints converge to, [alpha along the tangent, alpha along the bitangent]. When absent: "
   "the square of the material's roughnessFactor, at least 0.01, in both directions.",
   &kernel::GlintMaterial::alpha},
  {GlintField::Rho, "rho", "rho", GlintFieldKind::Number, true, 0.0, 0, -0.99, 0.99, false, {},
   "The correlation of the target distribution's slopes in the tangent frame: its highlights stretch along a diagonal of the frame.",
   &kernel::GlintMaterial::rho, &kernel::GlintParameters::rho},
  {GlintField::LogDensity, "logDensity", "log_density", GlintFieldKind::Number, true, 17.0, 0, 0.0, 100.0, false, {},
   "The natural logarithm of the number of microfacets per unit area of glint uv (TEXCOORD_0 times uvScale). Replaced by "
   "logDensityTexture where that is given.",
   &kernel::GlintMaterial::logDensity, &kernel::GlintParameters::logDensity},
  {GlintField::RelativeArea, "relativeArea", "relative_area", GlintFieldKind::Number, true, 1.0, 0, 0.0, 1.0, true, {},
   "The fraction of the surface's cells that hold microfacets.",
   &kernel::GlintMaterial::relativeArea, &kernel::GlintParameters::relativeArea},
  {GlintField::DensityRandomization, "densityRandomization", "density_randomisation", GlintFieldKind::Number, true, 2.0, 0,
   0.0, 10.0, false, {},
   "How much the number of microfacets varies from cell to cell (0: every cell holds the same number).",
   &kernel::GlintMaterial::densityRandomisation, &kernel::GlintParameters::densityRandomisation},
  {GlintField::MaxAnisotropy, "maxAnisotropy", "max_anisotropy", GlintFieldKind::Number, true, 8.0, 0, 1.0, 64.0, false, {},
   "The largest ratio of a pixel footprint's axes that the glint lookup keeps; longer footprints are widened to it.",
   &kernel::GlintMaterial::maxAnisotropy, &kernel::GlintParameters::maxAnisotropy},
  {GlintField::PatternSeed, "patternSeed", "pattern_seed", GlintFieldKind::Integer, true, 0, 0, 0, 4294967295.0, false, {},
   "Chooses another glint pattern with the same statistics.",
   &kernel::GlintMaterial::patternSeed},
  {GlintField::UvScale, "uvScale", "uv_scale", GlintFieldKind::Number, true, 1.0, 0, kSmallestPositiveFloat, kLargestFloat,
   false, {}, "The glint uv is TEXCOORD_0 times this factor; the density is per unit area of glint uv.",
   &kernel::GlintMaterial::uvScale},
  {GlintField::RandomColors, "randomColors", "random_colours", GlintFieldKind::Boolean, true, 0, 0, 0, 0, false, {},
   "Whether each cell's glints get a random colour, white on average, as the flakes of a car paint.",
   &kernel::GlintMaterial::colouredCells},
  {GlintField::Lod, "lod", "lod", GlintFieldKind::Choice, true, kernel::GLINT_LOD_PAPER, 0, 0, 0, false,
   {"paper", "consistent", "tree"},
   "How a cell's glints relate to those of the cells one level of detail finer: paper, each cell has its own (Chermain et "
   "al. 2020); consistent, a cell's glints are shared out among its four children, so that fewer glints vanish and appear "
   "as the footprint grows; tree, every cell below a level set by the density is the mean of its four children, so that "
   "glints stay put as the footprint grows.",
   &kernel::GlintMaterial::lod},
  {GlintField::LogDensityRange, "logDensityRange", "log_density_range", GlintFieldKind::Pair, true, 15.0, 35.0, 0.0, 100.0,
   false, {},
   "The log densities that logDensityTexture's red channel maps onto: 0 to the first, 1 to the second, linearly between.",
   &kernel::GlintMaterial::logDensityRange},
  {GlintField::RoughnessTexture, "roughnessTexture", "roughness_texture", GlintFieldKind::Texture, false, 0, 0, 0, 0, false,
   {}, "A texture whose red channel (linear) multiplies alpha; the product is clamped to [0.01, 2].",
   std::monostate{}},
  {GlintField::LogDensityTexture, "logDensityTexture", "log_density_texture", GlintFieldKind::Texture, false, 0, 0, 0, 0,
   false, {}, "A texture whose red channel (linear, 0 to 1) maps onto logDensityRange and replaces logDensity.",
   std::monostate{}},
  {GlintField::RelativeAreaTexture, "relativeAreaTexture", "relative_area_texture", GlintFieldKind::Texture, false, 0, 0,
   0, 0, false, {},
   "A texture whose red channel (linear) multiplies relativeArea; the product is clamped to [0.0001, 1].",
   std::monostate{}},
}};
// clang-format on

// The row of `field`.
constexpr const GlintFieldSpec& glintField(GlintField field) {
  for (const GlintFieldSpec& spec : kGlintFields) {
    if (spec.field == field) return spec;
  }
  return kGlintFields[0];  // unreachable: every field has a row (checked below)
}

namespace detail {
constexpr bool everyFieldOnceInOrder() {
  for (std::size_t i = 0; i < kGlintFieldCount; ++i) {
    if (static_cast<std::size_t>(kGlintFields[i].field) != i) return false;
  }
  return true;
}
}  // namespace detail
static_assert(detail::everyFieldOnceInOrder(), "kGlintFields: one row per GlintField, in the enum's order");

// The material block with every field's default: the scene's layer before a file sets it, the
// model's defaults. alpha has no default in the extension (a file's is its roughness squared):
// here 0.5, the roughness of a layer made without a file. The layer is off (enabled 0) and has no
// log-density texture.
inline kernel::GlintMaterial glintDefaultMaterial() {
  kernel::GlintMaterial material{};
  material.alpha = glm::vec2(0.5f);
  for (const GlintFieldSpec& spec : kGlintFields) {
    if (!spec.hasDefault) continue;
    std::visit(
        [&](auto member) {
          using Member = decltype(member);
          if constexpr (std::is_same_v<Member, float kernel::GlintMaterial::*>) {
            material.*member = static_cast<float>(spec.defaultValue);
          } else if constexpr (std::is_same_v<Member, glm::vec2 kernel::GlintMaterial::*>) {
            material.*member = glm::vec2(static_cast<float>(spec.defaultValue), static_cast<float>(spec.defaultSecond));
          } else if constexpr (std::is_same_v<Member, kernel::uint kernel::GlintMaterial::*>) {
            material.*member = static_cast<kernel::uint>(spec.defaultValue);
          } else if constexpr (std::is_same_v<Member, int kernel::GlintMaterial::*>) {
            material.*member = static_cast<int>(spec.defaultValue);
          }
        },
        spec.member);
  }
  return material;
}

// A field's default as the type that holds it.
constexpr float glintDefaultFloat(GlintField field) { return static_cast<float>(glintField(field).defaultValue); }
constexpr int glintDefaultChoice(GlintField field) { return static_cast<int>(glintField(field).defaultValue); }
constexpr bool glintDefaultBoolean(GlintField field) { return glintField(field).defaultValue != 0.0; }

// The name of a Choice field's value (the kernel's constant), "" for one out of range; and the value
// of a name, -1 for a name the field does not have.
constexpr const char* glintChoiceName(GlintField field, int value) {
  const auto& choices = glintField(field).choices;
  return value >= 0 && value < static_cast<int>(choices.size()) && choices[value] != nullptr ? choices[value] : "";
}
constexpr int glintChoiceValue(GlintField field, std::string_view name) {
  const auto& choices = glintField(field).choices;
  for (std::size_t i = 0; i < choices.size(); ++i) {
    if (choices[i] != nullptr && name == choices[i]) return static_cast<int>(i);
  }
  return -1;
}

}  // namespace glint
