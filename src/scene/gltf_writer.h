// A Scene to glTF 2.0 (.glb, or .gltf with its data embedded), through tinygltf's writer: what
// loadGltf (gltf_loader.h) reads back as the same scene. docs/scenes.md, "Writing glTF", says what
// is written and what glTF cannot hold.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "scene/scene.h"

namespace glint::scene {

// The file's encoding: binary glTF (one .glb file, the buffer in its BIN chunk) or glTF JSON with
// the buffer embedded as a base64 data URI (one self-contained .gltf file).
enum class GltfEncoding { Binary, Json };

// The scene as a glTF 2.0 document: one mesh and node per Mesh (in world space, identity
// transforms) with POSITION, NORMAL, TANGENT, TEXCOORD_0 and, when any vertex is not white, COLOR_0;
// the metal-roughness materials with their glint layer as EXT_materials_glint (in extensionsUsed,
// not extensionsRequired; docs/scenes.md, "Glint parameters in glTF"), KHR_texture_transform and
// KHR_materials_emissive_strength where used; every texture as an embedded PNG; the lights as
// KHR_lights_punctual; the scene's own cameras by name. What glint made for the scene rather than
// took from it (the lights addDefaultLighting invents for a file without lights, Scene::defaultLights;
// the bounding box's preset cameras, standardCameras, where unchanged; "default" where it is
// another camera's view) is left out unless `withDefaults`: a reader lights and frames the
// file as it chooses, and glint makes them again when it loads the file. Throws Error for what glTF or the loader cannot take (a mesh index out of range, a texture of
// the wrong size, a colour outside [0, 1]).
std::vector<std::byte> encodeGltf(const Scene& scene, GltfEncoding encoding, bool withDefaults = false);

// What encodeGltf writes of the scene's lights and cameras: the lights and the cameras (name and
// camera) in the order of their nodes, the camera that "default" stands for first.
std::vector<Light> writtenLights(const Scene& scene, bool withDefaults);
std::vector<std::pair<std::string, Camera>> writtenCameras(const Scene& scene, bool withDefaults);

// What of `scene` a glTF file cannot hold and a file written by encodeGltf therefore loses, one
// phrase each: the environment (always: glTF has none), an exposure other than 1.
std::vector<std::string> gltfLosses(const Scene& scene);

// encodeGltf in the encoding the name asks for (.glb or .gltf, case-insensitive; otherwise Error),
// written all-or-nothing (writeFileAtomically): on any error no file appears under `path`.
void writeGltf(const std::filesystem::path& path, const Scene& scene, bool withDefaults = false);

}  // namespace glint::scene
