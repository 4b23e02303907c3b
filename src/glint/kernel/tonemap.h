// Display transform shared by the CPU (images written by `glint trace`) and the GPU (the display
// pass of `glint render`'s images and the viewer's window, gl/display.h): exposure, a filmic
// curve, the sRGB encoding, then the rounding to 8 bits.
#ifndef GLINT_KERNEL_TONEMAP_H
#define GLINT_KERNEL_TONEMAP_H

#include "prelude.h"

GLINT_KERNEL_BEGIN

// Narkowicz 2015, "ACES Filmic Tone Mapping Curve": a fit of the ACES reference rendering
// transform, applied per channel to linear radiance times exposure; output in [0, 1].
GLINT_FN vec3 tonemapAcesFit(vec3 x) {
  return clamp((x * (2.51f * x + 0.03f)) / (x * (2.43f * x + 0.59f) + 0.14f), 0.0f, 1.0f);
}

// The sRGB opto-electronic transfer function (IEC 61966-2-1), linear [0, 1] to encoded [0, 1].
GLINT_FN float srgbEncode(float linear) {
  return linear <= 0.0031308f ? 12.92f * linear : 1.055f * pow(linear, 1.0f / 2.4f) - 0.055f;
}

GLINT_FN vec3 displayEncode(vec3 radiance, float exposure) {
  vec3 mapped = tonemapAcesFit(max(radiance * exposure, vec3(0.0f)));
  return vec3(srgbEncode(mapped.x), srgbEncode(mapped.y), srgbEncode(mapped.z));
}

// The display values as 8-bit code values (whole numbers 0..255 in floats), rounded to nearest:
// the one rounding of the CPU's images and of the GPU's display pass, where OpenGL leaves the
// rounding of a fraction to an 8-bit framebuffer to the implementation.
GLINT_FN vec3 displayCodeValues(vec3 radiance, float exposure) {
  return floor(displayEncode(radiance, exposure) * 255.0f + 0.5f);
}

GLINT_KERNEL_END

#endif
