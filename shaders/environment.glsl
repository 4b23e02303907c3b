// The scene's environment as an equirectangular, mip-mapped texture (src/gl/environment.cpp), +y
// up: the forward pass's specular ambient and the background pass's sky read it the same way.
#ifndef ENVIRONMENT_GLSL
#define ENVIRONMENT_GLSL

layout(binding = 9) uniform sampler2D uEnvironment;
uniform float uEnvironmentIntensity;
uniform float uEnvironmentMaxLod;
uniform vec2 uEnvironmentRotation;  // cos and sin of the map's turn about +y (scene::Environment::rotation)

// Radiance arriving from direction d, pre-filtered for a lobe of roughness alpha (0: sharp).
vec3 environmentRadiance(vec3 d, float alpha) {
  // The world direction turned back by the map's rotation (scene::Environment::mapDirection).
  d = vec3(uEnvironmentRotation.x * d.x - uEnvironmentRotation.y * d.z, d.y,
           uEnvironmentRotation.x * d.z + uEnvironmentRotation.y * d.x);
  vec2 uv = vec2(atan(d.x, -d.z) / (2.0f * GLINT_PI) + 0.5f, acos(clamp(d.y, -1.0f, 1.0f)) / GLINT_PI);
  float lod = clamp(log2(max(alpha, 1e-3f) * float(textureSize(uEnvironment, 0).x)), 0.0f, uEnvironmentMaxLod);
  return textureLod(uEnvironment, uv, lod).rgb * uEnvironmentIntensity;
}

#endif
