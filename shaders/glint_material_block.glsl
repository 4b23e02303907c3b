// The forward shader's glint material (kernel/glint_material.h): one std140 uniform block, bound
// per mesh to its material's range of the renderer's buffer of all materials (src/gl/renderer.cpp;
// binding gl::kGlintMaterialBinding). Its own file so that the test of its layout
// (tests/test_gl_kernel.cpp) compiles the very declaration the renderer uses. GLSL ES 3.00 has no
// layout(binding): src/gl/shader.cpp takes it out and binds the block after linking.
#ifndef GLINT_MATERIAL_BLOCK_GLSL
#define GLINT_MATERIAL_BLOCK_GLSL

#include "glint_material.h"

layout(std140, binding = 0) uniform GlintMaterialBlock { GlintMaterial uGlintMaterial; };

#endif
