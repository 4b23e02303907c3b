// A glTF material's glint layer in its two forms: the EXT_materials_glint extension
// (extensions/EXT_materials_glint/README.md), which `glint export` writes, and extras.glint, the
// older form that glint still reads (docs/scenes.md, "Glint parameters in glTF"). The loader
// (gltf_loader.cpp) and the writer (gltf_writer.cpp) take the fields' names from here.
#pragma once

#include <array>
#include <cstddef>
#include <functional>
#include <string>

#include <nlohmann/json.hpp>

#include "glint/bsdf.h"
#include "glint/glint_fields.h"
#include "scene/scene.h"

namespace glint::scene {

inline constexpr const char* kGlintExtensionName = "EXT_materials_glint";

// How a form names the fields: the extension in glTF's camelCase (US spelling, as glTF's
// "baseColorFactor"), extras.glint (and extras.glint_specular) in snake_case.
enum class GlintSpelling { Extension, Extras };

// The field's name in `spelling` ("relativeArea" or "relative_area"), from glint_fields.h.
const char* glintFieldName(GlintField field, GlintSpelling spelling);

// The fields of a material's specular target (Material::specular), not of its glint layer: ndf,
// masking and multipleScattering, which extras.glint_specular holds alone.
inline constexpr std::array kSpecularTargetFields = {GlintField::Ndf, GlintField::Masking, GlintField::MultipleScattering};
constexpr bool isSpecularTargetField(GlintField field) {
  for (GlintField target : kSpecularTargetFields) {
    if (field == target) return true;
  }
  return false;
}

// What reading a layer needs of the loader: the file's textures and where to note what it does not
// apply.
struct GlintTextureSource {
  std::size_t textureCount = 0;  // the file's textures
  // The scene texture of the file's texture `index` (< textureCount), decoded as linear data; -1
  // when that texture has no image glint reads. Throws Error for an image it cannot decode.
  std::function<int(int index)> sceneTexture;
  // Notes what a texture reference asks for that glint does not do (a texCoord other than 0, a
  // texture transform), `field` naming it as the file does.
  std::function<void(const std::string& what, const std::string& field)> noteUnread;
};

// A layer and the material's specular target as a glTF material's glint fields give them.
struct GltfGlint {
  GlintLayer layer;
  MicrofacetTarget specular;
};

// Reads the layer from `fields` (the extension's object, or extras.glint) in `spelling`, for a
// material of perceptual roughness `roughness` whose specular target is `specular` unless the
// fields say otherwise. Every field is optional: alpha defaults to alphaFromRoughness(roughness),
// the others to GlintLayer's and `specular`'s values. Booleans may be written 0 or 1, as some
// tools re-export them. Textures are glTF textureInfo objects in the extension, texture indices in
// extras.glint. Throws Error naming the first wrong field as the file spells it: an unknown field,
// a value of the wrong type, or out of the kernel's range (validateGlintLayer, the one place the
// ranges are defined), e.g. "relativeArea must be in (0, 1], got 2".
GltfGlint readGlintLayer(const nlohmann::json& fields, GlintSpelling spelling, float roughness, MicrofacetTarget specular,
                         const GlintTextureSource& textures);

// extras.glint_specular: the specular target (ndf, masking, multiple_scattering) of a material
// without a glint layer. Throws Error as readGlintLayer does.
MicrofacetTarget readGlintSpecularTarget(const nlohmann::json& fields, MicrofacetTarget specular);

// EXT_materials_glint's JSON schema (draft 2020-12, in the style of glTF's own schemas), written from
// the one table of the layer's fields (glint_fields.h): `glint extension-schema` writes it, and
// extensions/EXT_materials_glint/schema/material.EXT_materials_glint.schema.json is its output.
std::string glintExtensionSchema();

}  // namespace glint::scene
