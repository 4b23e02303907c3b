// glTF 2.0 (.gltf with its buffers and images, or .glb) to a Scene, through tinygltf.
// docs/scenes.md describes what is read, what is ignored, and the glint parameters
// (EXT_materials_glint, or the older extras.glint).
#pragma once

#include <cstddef>
#include <filesystem>
#include <span>
#include <string>

#include "scene/scene.h"

namespace glint::scene {

// Loads the default scene (else scene 0, else every root node) with node transforms baked into the
// vertices; missing normals (flat), uvs (zero) and tangents (generated) are filled in; materials
// become metal-roughness materials with textures decoded to RGBA8 and glint layers from
// EXT_materials_glint or `extras.glint` (gltf_glint.h). Cameras come from the bounding box
// (standardCameras) and lighting is the default (addDefaultLighting). Any problem throws Error, one line naming the file; nothing is half loaded.
Scene loadGltf(const std::filesystem::path& path);
// The same on a file's bytes already read: `name` becomes the scene's name, relative URIs are
// read from `baseDirectory`; errors do not name a file (loadGltf adds its path).
Scene loadGltf(std::span<const std::byte> bytes, const std::string& name, const std::filesystem::path& baseDirectory);

}  // namespace glint::scene
