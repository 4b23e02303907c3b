// One triangle covering the screen; uv in [0, 1] over the viewport.
out vec2 vUv;

void main() {
  vec2 corner = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
  vUv = corner;
  gl_Position = vec4(corner * 2.0f - 1.0f, 0.0f, 1.0f);
}
