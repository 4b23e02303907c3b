// Display transform shared by the CPU (images written by `glint trace`) and the GPU (the display
// pass of `glint render`'s images and the viewer's window, gl/display.h): exposure, a filmic
// curve, the sRGB encoding, then the dithered rounding to 8 bits.
#ifndef GLINT_KERNEL_TONEMAP_H
#define GLINT_KERNEL_TONEMAP_H

#include "prelude.h"

GLINT_KERNEL_BEGIN

// Narkowicz 2015, "ACES Filmic Tone Mapping Curve": a fit of the ACES reference rendering
// transform, applied per channel to linear radiance times exposure; output in [0, 1].
GLINT_FN vec3 glintTonemapAcesFit(vec3 x) {
  return clamp((x * (2.51f * x + 0.03f)) / (x * (2.43f * x + 0.59f) + 0.14f), 0.0f, 1.0f);
}

// The sRGB opto-electronic transfer function (IEC 61966-2-1), linear [0, 1] to encoded [0, 1].
GLINT_FN float glintSrgbEncode(float value) {
  return value <= 0.0031308f ? 12.92f * value : 1.055f * pow(value, 1.0f / 2.4f) - 0.055f;
}

GLINT_FN vec3 glintDisplayEncode(vec3 radiance, float exposure) {
  vec3 mapped = glintTonemapAcesFit(max(radiance * exposure, glintSplat3(0.0f)));
  return vec3(glintSrgbEncode(mapped.x), glintSrgbEncode(mapped.y), glintSrgbEncode(mapped.z));
}

// The threshold of `pixel` in the 8 x 8 Bayer matrix of ordered dithering, in (0, 1): each 8 x 8
// tile holds all 64 thresholds (k + 0.5) / 64, spread so that neighbours differ. Bayer's
// recursion: each bit pair of the coordinates, lowest first, picks the quadrant of the next finer
// level.
GLINT_FN float glintOrderedDitherThreshold(ivec2 pixel) {
  int rank = 0;
  for (int bit = 0; bit < 3; ++bit) {
    rank = rank * 4 + 2 * (((pixel.x ^ pixel.y) >> bit) & 1) + ((pixel.y >> bit) & 1);
  }
  return (float(rank) + 0.5f) / 64.0f;
}

// The display values as 8-bit code values (whole numbers 0..255 in floats) of the image's pixel
// `pixel` (x from the left, y from the top row): the one rounding of the CPU's images and of the
// GPU's display pass, where OpenGL leaves the rounding of a fraction to an 8-bit framebuffer to
// the implementation. Dithered: each value moves by up to half a code, by the pixel's Bayer
// threshold, before it is rounded, so that a smooth gradient (a sky) shows no bands (an 8 x 8 tile
// of one value averages to it within 1/64 of a code). It depends on the position alone, so every
// run gives the same bytes; a value exactly on a code keeps it (black stays black, white white).
GLINT_FN vec3 glintDisplayCodeValues(vec3 radiance, float exposure, ivec2 pixel) {
  vec3 code = floor(glintDisplayEncode(radiance, exposure) * 255.0f + glintOrderedDitherThreshold(pixel));
  return clamp(code, 0.0f, 255.0f);
}

GLINT_KERNEL_END

#endif
