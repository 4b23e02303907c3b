// The display pass (gl/display.h): the radiance of a frame, texel for pixel, through
// kernel/tonemap.h's exposure, tone curve, sRGB encoding and rounding to 8 bits, for the viewer's
// window and the PNG images of `glint render` alike.
#include "tonemap.h"

layout(location = 0) out vec4 outColour;
layout(binding = 0) uniform sampler2D uRadiance;
uniform float uExposure;

void main() {
  // A whole code value over 255 converts to exactly that value in an 8-bit framebuffer.
  vec3 radiance = texelFetch(uRadiance, ivec2(gl_FragCoord.xy), 0).rgb;
  outColour = vec4(displayCodeValues(radiance, uExposure) / 255.0f, 1.0f);
}
