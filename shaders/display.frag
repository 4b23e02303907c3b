// The display pass (gl/display.h): the radiance of a frame, texel for pixel, through
// kernel/tonemap.h's exposure, tone curve, sRGB encoding and dithered rounding to 8 bits, for the
// viewer's window and the PNG images of `glint render` alike.
#include "tonemap.h"

layout(location = 0) out vec4 outColour;
layout(binding = 0) uniform sampler2D uRadiance;
uniform float uExposure;

void main() {
  // A whole code value over 255 converts to exactly that value in an 8-bit framebuffer.
  ivec2 texel = ivec2(gl_FragCoord.xy);
  vec3 radiance = texelFetch(uRadiance, texel, 0).rgb;
  // The dither is laid out from the image's top row, as the CPU's images are (rows here go up).
  ivec2 pixel = ivec2(texel.x, textureSize(uRadiance, 0).y - 1 - texel.y);
  outColour = vec4(glintDisplayCodeValues(radiance, uExposure, pixel) / 255.0f, 1.0f);
}
