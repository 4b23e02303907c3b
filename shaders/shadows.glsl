// Shadow-map lookups of forward.frag (SHADOWS = 1): the fraction of a light that reaches a point,
// as the path tracer's shadow ray finds it, from the maps src/gl/shadow_maps.cpp draws before
// the frame (docs/renderer.md, "Shadows"). A spot light has one layer of a 2D array, a directional
// light uShadowCascades layers (its cascades, nearest first), point lights (and spots too wide for
// one map) one cube of a cube-map array; bit i of SHADOW_CUBES says which caster i has. The casters
// are the LIGHT_COUNT lights, then the AREA_LIGHT_COUNT area lights, each a cube map from its centre.
// Caster i's maps are entries i * SHADOW_CASCADES + c of the arrays below. Every map holds depth as
// a linear function of distance, so that the bias below is in world units for all of them.
#if SHADOWS
#define SHADOW_MAP_COUNT ((GLINT_SLOPE_COUNT + AREA_LIGHT_COUNT) * SHADOW_CASCADES)
layout(binding = 13) uniform sampler2DArrayShadow uShadowMaps;
layout(binding = 14) uniform samplerCubeArrayShadow uShadowCubes;
uniform int uShadowCascades;                        // a directional light's maps
uniform mat4 uShadowMatrix[SHADOW_MAP_COUNT];       // world to the map's clip space (2D maps)
uniform float uShadowLayer[SHADOW_MAP_COUNT];       // the layer (2D) or the cube (cube maps)
uniform float uShadowDepthScale[SHADOW_MAP_COUNT];  // world length to map depth
uniform float uShadowTexel[SHADOW_MAP_COUNT];       // a texel's world size: at distance 1 (point, spot) or anywhere (directional)

// A directional light's map for a point: the first (finest) cascade that holds it at least
// SHADOW_CASCADE_MARGIN texels inside its border, where the normal offset and the filter's taps
// below stay inside the map; the last one otherwise. Every point the camera sees is inside some
// cascade's margin (src/gl/shadow_maps.cpp fits them so).
int shadowCascade(int first, vec3 position) {
  float inside = 1.0f - 2.0f * float(SHADOW_CASCADE_MARGIN) / float(textureSize(uShadowMaps, 0).x);
  for (int c = 0; c < uShadowCascades - 1; ++c) {
    vec4 clip = uShadowMatrix[first + c] * vec4(position, 1.0f);
    if (all(lessThanEqual(abs(clip.xy), vec2(inside)))) return first + c;
  }
  return first + uShadowCascades - 1;
}

// The receiver's bias, in texels of its map at its distance: the lookup point moves off the
// surface along its normal by kShadowNormalOffset texels, and its depth towards the light by
// kShadowConstantBias plus kShadowSlopeBias times the tangent of the light's angle to the normal
// (at most kShadowMaxSlope): across one texel a surface at that angle changes depth by the
// tangent, and the filter below reads the surface's own depth up to about 1.5 texels away.
const float kShadowNormalOffset = 1.0f;
const float kShadowConstantBias = 1.0f;
const float kShadowSlopeBias = 2.0f;
const float kShadowMaxSlope = 8.0f;

// Percentage-closer filtering: four bilinear depth comparisons (each a 2 x 2 texel test weighed
// by the lookup's position) half a texel apart across the light's direction, a smooth step about
// two texels wide where the tracer's shadow has a hard edge.
// Caster i at `light` (w = 1: a position, w = 0: a direction).
float shadowVisibility(int i, vec4 light, vec3 position, vec3 normal, vec3 towardsLight, float lightDistance) {
  bool cube = ((SHADOW_CUBES >> i) & 1) != 0;
  bool positional = light.w > 0.0f;
  int map = positional ? i * SHADOW_CASCADES : shadowCascade(i * SHADOW_CASCADES, position);
  float texel = uShadowTexel[map] * lightDistance;
  float cosine = dot(normal, towardsLight);
  vec3 facing = cosine < 0.0f ? -normal : normal;  // double-sided sheets: the side the light sees
  cosine = max(abs(cosine), 1e-3f);
  float slope = min(sqrt(max(1.0f - cosine * cosine, 0.0f)) / cosine, kShadowMaxSlope);
  vec3 receiver = position + facing * (kShadowNormalOffset * texel);
  float bias = texel * (kShadowConstantBias + kShadowSlopeBias * slope);
  vec3 across = normalize(cross(towardsLight, abs(towardsLight.y) < 0.9f ? vec3(0.0f, 1.0f, 0.0f) : vec3(1.0f, 0.0f, 0.0f)));
  vec3 up = cross(towardsLight, across);
  float visible = 0.0f;
  for (int k = 0; k < 4; ++k) {
    vec2 tap = 0.5f * texel * vec2((k & 1) != 0 ? 1.0f : -1.0f, (k & 2) != 0 ? 1.0f : -1.0f);
    vec3 q = receiver + tap.x * across + tap.y * up;
    if (cube) {
      vec3 fromLight = q - light.xyz;
      visible += texture(uShadowCubes, vec4(fromLight, uShadowLayer[map]), (length(fromLight) - bias) * uShadowDepthScale[map]);
    } else {
      vec4 clip = uShadowMatrix[map] * vec4(q, 1.0f);
      vec3 ndc = clip.xyz / clip.w;
      float depth = positional ? length(q - light.xyz) * uShadowDepthScale[map] : 0.5f * ndc.z + 0.5f;
      visible += texture(uShadowMaps, vec4(0.5f * ndc.xy + 0.5f, uShadowLayer[map], depth - bias * uShadowDepthScale[map]));
    }
  }
  return 0.25f * visible;
}
#endif
