// glTF files made by the repository itself, for the tests that load, break or render glTF: a
// small scene that uses every texture slot and most of what glTF carries, written with the
// glTF writer, either as one file or laid out as separate files (.gltf, .bin, one PNG per image),
// as exporters commonly write them. The third-party assets of ../shared are optional; the tests
// that need one skip without it (sharedAsset).
#pragma once

#include <filesystem>
#include <functional>
#include <string>

#include <nlohmann/json.hpp>

#include "scene/scene.h"

namespace glint::test {

// A textured UV sphere on a quad: material 0 "textured" uses a base colour, metallic-roughness,
// normal, occlusion and emissive texture (five 8 x 8 images, textures 0 to 4 in that order), a glint
// layer whose roughness texture is the metallic-roughness one, and a texture transform on its base
// colour; material 1 "plain" has no texture and vertex colours on its quad. A point light, a spot
// with a range and a directional light; a perspective "default" and an orthographic "plan" camera.
scene::Scene texturedTestScene();

// Writes `scene` in `folder` as separate files: STEM.gltf, STEM.bin (the whole buffer) and
// image0.png, image1.png, ... (each image's PNG, referred to by uri). Returns the .gltf's path.
std::filesystem::path writeSeparateGltf(const scene::Scene& scene, const std::filesystem::path& folder,
                                        const std::string& stem);

// Reads, edits and writes back the JSON of a .gltf file.
void editGltfJson(const std::filesystem::path& path, const std::function<void(nlohmann::json&)>& edit);

// A vector as `glint render` takes one on its command line, "x,y,z" to float precision.
std::string triple(glm::vec3 v);
// The command-line options that place `camera` (a perspective one): --look-from, --look-at, --up
// and --fov, each with a leading space.
std::string cameraOptions(const scene::Camera& camera);

// A third-party asset under ../shared (e.g. "scenes/damaged-helmet/DamagedHelmet.glb"), or an empty
// path when it is absent: callers GTEST_SKIP() with sharedAssetMissing(relative).
std::filesystem::path sharedAsset(const std::string& relative);
std::string sharedAssetMissing(const std::string& relative);

}  // namespace glint::test
