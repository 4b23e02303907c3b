// The whole kernel in a GLSL 4.50 compute shader for OpenGL, with glint's own renderer's side of the
// dictionary hook (shaders/glint_dictionary_gl.glsl): KernelLanguages.DesktopGl.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "kernel_entry_points.glsl"
#include "glint_dictionary_gl.glsl"

layout(local_size_x = 64) in;
layout(std430, binding = 1) buffer Values { vec4 values[]; };
layout(location = 0) uniform uint uCount;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i + 2u < uCount) {
    values[i] = kernelEntryPoints(glintDictionary(), values[i], values[i + 1u], values[i + 2u]);
  }
}
