// glTF 2.0 (.gltf with its buffers and images, or .glb) to a Scene, through tinygltf.
// docs/scenes.md describes what is read, what is ignored, and the glint parameters in extras.
#pragma once

#include <filesystem>

#include "scene/scene.h"

namespace glint::scene {

// Loads the default scene (else scene 0, else every root node) with node transforms baked into the
// vertices; missing normals (flat), uvs (zero) and tangents (generated) are filled in; materials
// become metal-roughness materials with textures decoded to RGBA8 and glint layers from
// `extras.glint`. Cameras come from the bounding box (standardCameras) and lighting is the default
// (addDefaultLighting). Any problem throws Error, one line naming the file; nothing is half loaded.
Scene loadGltf(const std::filesystem::path& path);

}  // namespace glint::scene
