// What glint checks on a glTF file's own JSON before tinygltf reads it, because tinygltf would
// otherwise fail in its own words or read past its data: the extensions the file requires, and
// that every buffer view lies within its buffer (tinygltf 2.7 hands an image's view to stb_image
// unchecked).
#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace glint::scene {

// Throws glint::Error "glTF VERSION is not supported (glint reads glTF 2.0)" when asset.version
// says another major version: a glTF 1.0 file's objects are keyed by name where 2.0 has arrays, and
// would otherwise be refused for its first such property.
void checkGltfVersion(const nlohmann::json& document);

// Whether glint reads this extension (docs/scenes.md): the ones a file may require, and the ones a
// file that merely uses is not warned about.
bool glintReadsExtension(const std::string& name);

// Throws glint::Error "requires extension NAME, which glint does not support" for the first
// required extension glint cannot honour (KHR_draco_mesh_compression, EXT_meshopt_compression,
// KHR_texture_basisu, ...): without it the data means something else.
void checkRequiredExtensions(const nlohmann::json& document);

// Throws glint::Error naming the buffer view, its byte range and its buffer's length when a view
// reaches past the end of its buffer (or names a buffer that does not exist).
void checkBufferViewRanges(const nlohmann::json& document);

}  // namespace glint::scene
