// The GPU half of the surface test (tests/test_surface.cpp): kernel::glintSurface (surface.h) at
// each case's samples, with the renderer's material block (glint_material_block.glsl) bound by the
// host to one material. The outputs are the surface's fields, in the C++ test's layout.
#define GLINT_ALBEDO_TABLES 1
#include "glint_material_block.glsl"
#include "surface.h"
#include "clearcoat.h"
// The dictionary hook: never called here, but surface.h includes glint_brdf.h, whose functions call
// it, and Mesa's linker resolves the calls of every function, called or not.
#include "glint_dictionary_gl.glsl"

layout(local_size_x = 64) in;

struct SurfaceCase {
  vec4 baseColour;
  vec4 metallicRoughnessOcclusion;  // metallic, roughness, occlusion, unused
  vec4 emission;
  vec4 normal;
  vec4 tangent;
  vec4 mappedNormal;
  vec4 view;
  vec4 glintSamples;
  vec4 normalMapCovariance;
  vec4 footprintPolicy;  // aniso, cells, drop, unused
  vec4 coat;             // clearcoat factor, roughness, unused
  vec4 coatNormal;
  vec4 light;
};
struct SurfaceOutput {
  vec4 t;
  vec4 b;
  vec4 n;
  vec4 wo;
  vec4 baseColour;
  vec4 metallicRoughnessOcclusionLayer;  // metallic, roughness, occlusion, hasGlintLayer
  vec4 diffuse;
  vec4 f0;
  vec4 emission;
  vec4 smoothLobe;  // smoothAlpha.x, .y, smoothRho, unused
  vec4 glint;       // glint.alpha.x, .y, .rho, .logDensity
  vec4 glintMore;   // glint.relativeArea, .densityRandomisation, .maxAnisotropy, unused
  vec4 coatN;       // coat.n, coat.weight
  vec4 coatT;       // coat.t, coat.alpha
  vec4 coatLight;   // glintCoatReflectedCosine at the light, glintCoatedEmissionWeight, unused
};
layout(std430, binding = 0) readonly buffer Inputs { SurfaceCase inputs[]; };
layout(std430, binding = 1) writeonly buffer Outputs { SurfaceOutput outputs[]; };

uniform uint uCount;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= uCount) {
    return;
  }
  SurfaceCase c = inputs[i];
  GlintSurfaceSamples s;
  s.baseColour = c.baseColour;
  s.metallicRoughness = c.metallicRoughnessOcclusion.xy;
  s.occlusion = c.metallicRoughnessOcclusion.z;
  s.emission = c.emission.xyz;
  s.normal = c.normal.xyz;
  s.tangent = c.tangent;
  s.mappedNormal = c.mappedNormal.xyz;
  s.view = c.view.xyz;
  s.glintSamples = c.glintSamples.xyz;
  s.normalMapCovariance = c.normalMapCovariance.xyz;
  GlintFootprintPolicy policy;
  policy.maxAnisotropy = c.footprintPolicy.x;
  policy.maxCells = c.footprintPolicy.y;
  policy.minBlend = c.footprintPolicy.z;
  GlintSurface surface = glintSurface(s, uGlintMaterial, policy);
  outputs[i].t = vec4(surface.t, 0.0f);
  outputs[i].b = vec4(surface.b, 0.0f);
  outputs[i].n = vec4(surface.n, 0.0f);
  outputs[i].wo = vec4(surface.wo, 0.0f);
  outputs[i].baseColour = surface.baseColour;
  outputs[i].metallicRoughnessOcclusionLayer =
      vec4(surface.metallic, surface.roughness, surface.occlusion, float(surface.hasGlintLayer));
  outputs[i].diffuse = vec4(surface.diffuse, 0.0f);
  outputs[i].f0 = vec4(surface.f0, 0.0f);
  outputs[i].emission = vec4(surface.emission, 0.0f);
  outputs[i].smoothLobe = vec4(surface.smoothAlpha, surface.smoothRho, 0.0f);
  outputs[i].glint = vec4(surface.glint.alpha, surface.glint.rho, surface.glint.logDensity);
  outputs[i].glintMore = vec4(surface.glint.relativeArea, surface.glint.densityRandomisation, surface.glint.maxAnisotropy, 0.0f);
  GlintCoatSamples coatSamples;
  coatSamples.factorRoughness = c.coat.xy;
  coatSamples.mappedNormal = c.coatNormal.xyz;
  GlintCoat coat = glintSurfaceCoat(surface, s, coatSamples);
  outputs[i].coatN = vec4(coat.n, coat.weight);
  outputs[i].coatT = vec4(coat.t, coat.alpha);
  outputs[i].coatLight = vec4(glintCoatReflectedCosine(coat, surface.wo, c.light.xyz),
                              glintCoatedEmissionWeight(c.coat.x, s.normal, s.view), 0.0f, 0.0f);
}
