// Forward pass: world-space vertices (transforms are baked at load) to clip space.
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in vec4 aTangent;
layout(location = 3) in vec2 aUv;
layout(location = 4) in vec4 aColour;  // glTF COLOR_0, white when the mesh has none

uniform mat4 uViewProjection;

out vec3 vPosition;
out vec3 vNormal;
out vec4 vTangent;
out vec2 vUv;
out vec4 vColour;
// The depth pre-pass and the shading pass both transform with this shader; invariant makes their
// depths bit-identical, which the shading pass's equal-depth test relies on.
invariant gl_Position;

void main() {
  vPosition = aPosition;
  vNormal = aNormal;
  vTangent = aTangent;
  vUv = aUv;
  vColour = aColour;
  gl_Position = uViewProjection * vec4(aPosition, 1.0f);
}
