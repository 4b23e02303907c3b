// Compressed glTF data, decoded before the loader reads it:
// - KHR_draco_mesh_compression (Google's Draco, through Debian's libdraco): each compressed
//   primitive's stream is decoded, and its accessors (the attributes the extension names, and the
//   indices) are pointed at the decoded values, floats and 32-bit indices in a buffer of their own;
// - EXT_meshopt_compression (meshoptimizer's codecs, through Debian's libmeshoptimizer): each
//   compressed buffer view is decoded (its vertex or index codec, then its filter) into a buffer of
//   its own, byte for byte what the view would hold uncompressed;
// so that the loader reads them as any other accessor. The page's WebAssembly build decodes
// neither (GLINT_DRACO and GLINT_MESHOPT 0): there a file that requires one is refused by name, as
// any extension glint does not read.
#pragma once

#include <string>

#include <nlohmann/json_fwd.hpp>

namespace tinygltf {
class Model;
}

namespace glint::scene {

// Whether this build decodes KHR_draco_mesh_compression, and EXT_meshopt_compression.
bool decodesDraco();
bool decodesMeshopt();

// On the file's JSON, before tinygltf reads it: a Draco primitive's indices accessor has no buffer
// view (the extension's data is the stream), which tinygltf refuses. Each such primitive's
// "indices" is moved into its extension object (as "glintIndices"), and decodeCompressedMeshes
// puts it back with the decoded indices. Returns whether anything moved.
bool setAsideDracoIndices(nlohmann::json& document);

// On the file's JSON (`binary`: of a GLB), before tinygltf reads it: a meshopt-compressed buffer
// view lies in a fallback buffer that usually has no data (no uri), which tinygltf refuses. Each
// compressed view's extension is checked (mode, filter, the stride each takes, count x byteStride
// filling the view, its stream within its buffer), the view pointed at its compressed bytes and its
// own length set aside in the extension object (as "glintFallback"); each buffer without data that
// is flagged as a fallback, or that only compressed views lie in, becomes a one-byte buffer that no
// view reads. decodeCompressedMeshes decodes the views. Returns whether anything changed. Throws
// Error naming the buffer view and the problem, also for a view that is not compressed but lies in
// a fallback buffer (it has no data to read).
bool setAsideMeshoptViews(nlohmann::json& document, bool binary);

// Decodes every meshopt-compressed buffer view, then every Draco primitive, of `model` in place.
// Throws Error naming the buffer view, or the mesh and the primitive, and the problem (a corrupt
// stream, an attribute the stream lacks, a count that is not the accessor's).
void decodeCompressedMeshes(tinygltf::Model& model);

}  // namespace glint::scene
