// The depth pre-pass (src/gl/renderer.cpp): meshes are first drawn with this shader and colour
// writes off, so that the shading pass, under an equal-depth test, runs the forward shader once per
// covered pixel instead of once per fragment drawn there. With ALPHA_MASK (glTF alphaMode MASK),
// the fragments whose base colour alpha (factor, texture and vertex colour) is below the cutoff
// leave no depth, so what lies behind them is shaded instead; the other meshes keep a shader
// without discard. The shadow maps of point and spot lights (src/gl/shadow_maps.cpp) are drawn
// with it too, LINEAR_DEPTH = 1: their depth is the distance from the light, scaled to [0, 1].
#if ALPHA_MASK
in vec2 vUv;
in vec4 vColour;

layout(binding = 1) uniform sampler2D uBaseColourTexture;
uniform vec4 uBaseColour;
uniform mat3x2 uBaseColourUv;  // KHR_texture_transform, as in forward.frag
uniform float uAlphaCutoff;
#endif
#if LINEAR_DEPTH
in vec3 vPosition;
uniform vec3 uDepthOrigin;    // the light
uniform float uDepthScale;    // 1 / the map's far distance
#endif

void main() {
#if ALPHA_MASK
  if (uBaseColour.a * texture(uBaseColourTexture, uBaseColourUv * vec3(vUv, 1.0f)).a * vColour.a < uAlphaCutoff) {
    discard;
  }
#endif
#if LINEAR_DEPTH
  gl_FragDepth = distance(vPosition, uDepthOrigin) * uDepthScale;
#endif
}
