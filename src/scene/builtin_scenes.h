// Procedural scenes that need no files (docs/scenes.md, "Built-in scenes"): the authors' red glint
// sphere, a varnished parquet floor, car paint, a showroom combining them with glittering stone
// and curtains, two grazing views of a large glittering plane, an arctic snow field with a
// tiling normal map, a snowman and a silver ornament under a low sun, and two scenes at the scale of
// the paper's performance table: an arcaded atrium (Sponza's 262k triangles) and a car (the 2CV's
// 705k). Deterministic: the same name gives the same bytes on every run.
#pragma once

#include <string>
#include <vector>

#include "scene/scene.h"

namespace glint::scene {

// The scene `glint render` draws when none is named.
inline constexpr const char* kDefaultScene = "showroom";

// "sphere", "parquet", "carpaint", "showroom", "grazing-smooth", "grazing-rough", "arctic", "atrium",
// "car".
std::vector<std::string> builtinSceneNames();
bool isBuiltinScene(const std::string& name);
// Throws Error listing the built-in names for an unknown name.
Scene makeBuiltinScene(const std::string& name);

// The built-in scenes' procedural sky (blue zenith, pale horizon, grey ground), 128 x 64.
Environment skyEnvironment(float intensity);

// A built-in name, else a glTF file (.gltf or .glb, loadGltf). Throws Error
// "unknown scene 'x' (built-in: sphere, ...) and no such file" when it is neither.
Scene loadScene(const std::string& nameOrPath);
// The name loadScene gives that scene, without loading it: the built-in name, else the file's
// name without its folder and extension (what `glint render` names its output after).
std::string sceneName(const std::string& nameOrPath);

}  // namespace glint::scene
