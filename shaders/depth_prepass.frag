// The depth pre-pass (src/gl/renderer.cpp): meshes are first drawn with this shader and colour
// writes off, so that the shading pass, under an equal-depth test, runs the forward shader once per
// covered pixel instead of once per fragment drawn there.
void main() {}
