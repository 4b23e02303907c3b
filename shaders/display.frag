// The viewer's display transform: the same exposure, tone curve and sRGB encoding as the images
// `glint render` writes (src/glint/kernel/tonemap.h).
#include "tonemap.h"

in vec2 vUv;
layout(location = 0) out vec4 outColour;
layout(binding = 0) uniform sampler2D uRadiance;
uniform float uExposure;

void main() {
  outColour = vec4(displayEncode(texture(uRadiance, vUv).rgb, uExposure), 1.0f);
}
