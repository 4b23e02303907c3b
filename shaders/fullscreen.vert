// One triangle covering the screen; uv in [0, 1] over the viewport. At depth 0 (mid range) unless
// the program defines FULLSCREEN_AT_FAR_PLANE: then at the far plane, where it passes a
// less-or-equal depth test only on pixels still at the cleared depth.
out vec2 vUv;

void main() {
  vec2 corner = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
  vUv = corner;
#ifdef FULLSCREEN_AT_FAR_PLANE
  gl_Position = vec4(corner * 2.0f - 1.0f, 1.0f, 1.0f);
#else
  gl_Position = vec4(corner * 2.0f - 1.0f, 0.0f, 1.0f);
#endif
}
