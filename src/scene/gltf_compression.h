// Compressed glTF meshes, decoded before the loader reads them: KHR_draco_mesh_compression (Google's
// Draco, through Debian's libdraco). Each compressed primitive's stream is decoded, and its accessors
// (the attributes the extension names, and the indices) are pointed at the decoded values, floats and
// 32-bit indices in a buffer of their own, so that the loader reads them as any other accessor.
// The page's WebAssembly build has no Draco (GLINT_DRACO 0): there a file that requires it is refused
// by name, as any extension glint does not read.
#pragma once

#include <string>

#include <nlohmann/json_fwd.hpp>

namespace tinygltf {
class Model;
}

namespace glint::scene {

// Whether this build decodes KHR_draco_mesh_compression.
bool decodesDraco();

// On the file's JSON, before tinygltf reads it: a Draco primitive's indices accessor has no buffer
// view (the extension's data is the stream), which tinygltf refuses. Each such primitive's
// "indices" is moved into its extension object (as "glintIndices"), and decodeCompressedMeshes
// puts it back with the decoded indices. Returns whether anything moved.
bool setAsideDracoIndices(nlohmann::json& document);

// Decodes every compressed primitive of `model` in place. Throws Error naming the mesh, the
// primitive and the problem (a corrupt stream, an attribute the stream lacks, a count that is not
// the accessor's).
void decodeCompressedMeshes(tinygltf::Model& model);

}  // namespace glint::scene
