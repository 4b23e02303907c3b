#version 450 core
// glint_opengl's vertex shader: world-space vertices (the sphere sits at the origin) to clip space.
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in vec4 aTangent;  // xyz along increasing u, w the bitangent's sign (glTF)
layout(location = 3) in vec2 aUv;

uniform mat4 uViewProjection;

out vec3 vPosition;
out vec3 vNormal;
out vec4 vTangent;
out vec2 vUv;

void main() {
  vPosition = aPosition;
  vNormal = aNormal;
  vTangent = aTangent;
  vUv = aUv;
  gl_Position = uViewProjection * vec4(aPosition, 1.0f);
}
