// The JSON types of the glTF properties glint reads, checked on the file's own JSON before tinygltf
// parses it: tinygltf 2.7 (Debian's) takes a mistyped optional property for absent and keeps its
// default, so "doubleSided": "yes" would load as single-sided and "byteOffset": "12" as 0.
#ifndef GLINT_SCENE_GLTF_FIELD_TYPES_H
#define GLINT_SCENE_GLTF_FIELD_TYPES_H

#include <cstddef>
#include <optional>
#include <span>
#include <string>

#include <nlohmann/json.hpp>

namespace glint::scene {

// The JSON of a .gltf file's bytes or of a .glb's JSON chunk; nullopt when it is truncated or its
// JSON does not parse (tinygltf then reports the problem in its own words).
std::optional<nlohmann::json> readGltfJson(std::span<const std::byte> bytes);

// How a message shows a value after "got": the value itself where it is short (2, true, the string
// "yes"), else its kind (a string, an array, an object).
std::string describeJsonValue(const nlohmann::json& value);

// Throws glint::Error "PATH must be TYPE, got VALUE" (e.g. "materials[2].doubleSided must be true
// or false, got the string \"yes\"") for the first property glint reads whose JSON type is not the
// one the glTF 2.0 schema (and KHR_lights_punctual's) gives it, or that tinygltf would misread (an
// integer written as 3.5, or beyond a 32-bit int; whole numbers such as 3.0 are made integers by
// wholeNumberIndicesToIntegers first). Absent properties are fine. Also refuses JSON
// nested more than 256 levels deep, which tinygltf's recursive parsing of extras cannot survive.
void checkGltfFieldTypes(const nlohmann::json& document);

// Rewrites the indices, counts and offsets glint reads that the file writes as whole numbers in
// floating point ("children": [1.0], valid glTF: JSON has one number type) as integers, which is
// how tinygltf must see them to read them at all; returns whether anything changed. Fractional or
// out-of-range values are left for checkGltfFieldTypes to refuse.
bool wholeNumberIndicesToIntegers(nlohmann::json& document);

}  // namespace glint::scene

#endif
