// The GPU half of the glint material tests (tests/test_gl_kernel.cpp): the renderer's material
// block (glint_material_block.glsl), bound by the host to one material of a buffer of them, and
// kernel::glintMaterialParameters and glintMaterialUv at each case's texture samples and uv. Every
// output is the bits of the value, so that the host compares them exactly.
#include "glint_material_block.glsl"
// The dictionary hook: never called here, but glint_material.h includes glint_brdf.h, whose
// functions call it, and Mesa's linker resolves the calls of every function, called or not.
#include "glint_dictionary_gl.glsl"

layout(local_size_x = 64) in;

struct MaterialCase {
  vec4 samples;          // the R channels of the roughness, log-density and relative-area textures; unused
  vec4 footprintPolicy;  // GlintFootprintPolicy: aniso, cells, drop; unused
  vec4 uv;               // a mesh uv; unused
};
// GlintParameters, field after field: (alpha.x, alpha.y, rho, logDensity), (relativeArea,
// densityRandomisation, maxAnisotropy, patternSeed), (colouredCells, ndf, masking,
// multipleScattering), (footprintPolicy.maxAnisotropy, .maxCells, .minBlend, lod), then the glint uv
// of the case's uv (x, y, 0, 0).
struct MaterialOutput {
  uvec4 words[5];
};
layout(std430, binding = 0) readonly buffer Inputs { MaterialCase inputs[]; };
layout(std430, binding = 1) writeonly buffer Outputs { MaterialOutput outputs[]; };

uniform uint uCount;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= uCount) {
    return;
  }
  MaterialCase c = inputs[i];
  GlintFootprintPolicy policy;
  policy.maxAnisotropy = c.footprintPolicy.x;
  policy.maxCells = c.footprintPolicy.y;
  policy.minBlend = c.footprintPolicy.z;
  GlintParameters p = glintMaterialParameters(uGlintMaterial, c.samples.x, c.samples.y, c.samples.z, policy);
  vec2 glintUv = glintMaterialUv(uGlintMaterial, c.uv.xy);
  outputs[i].words[0] = floatBitsToUint(vec4(p.alpha.x, p.alpha.y, p.rho, p.logDensity));
  outputs[i].words[1] = uvec4(floatBitsToUint(p.relativeArea), floatBitsToUint(p.densityRandomisation),
                              floatBitsToUint(p.maxAnisotropy), p.patternSeed);
  outputs[i].words[2] = uvec4(p.colouredCells ? 1u : 0u, uint(p.ndf), uint(p.masking), p.multipleScattering ? 1u : 0u);
  outputs[i].words[3] = uvec4(floatBitsToUint(p.footprintPolicy.maxAnisotropy),
                              floatBitsToUint(p.footprintPolicy.maxCells),
                              floatBitsToUint(p.footprintPolicy.minBlend), uint(p.lod));
  outputs[i].words[4] = uvec4(floatBitsToUint(glintUv), 0u, 0u);
}
