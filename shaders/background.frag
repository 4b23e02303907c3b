// The environment behind the meshes: drawn as a triangle at the far plane after them, so it covers
// only the pixels no mesh did, with the radiance a camera ray in that direction meets (what the
// path tracer shows there too).
// microfacet.h for GLINT_PI.
#include "microfacet.h"
#include "environment.glsl"

in vec2 vUv;
layout(location = 0) out vec4 outRadiance;

uniform mat4 uInverseViewProjection;

void main() {
  vec2 ndc = vUv * 2.0f - 1.0f;
  vec4 near = uInverseViewProjection * vec4(ndc, -1.0f, 1.0f);
  vec4 far = uInverseViewProjection * vec4(ndc, 1.0f, 1.0f);
  vec3 direction = normalize(far.xyz / far.w - near.xyz / near.w);
  outRadiance = vec4(environmentRadiance(direction, 0.0f), 1.0f);
}
