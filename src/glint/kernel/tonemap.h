// Display transform of the CPU (`glint trace`'s images) and the GPU (`glint render`'s display pass and
// the viewer, gl/display.h): exposure, a filmic curve, sRGB encoding, dithered rounding to 8 bits.
#ifndef GLINT_KERNEL_TONEMAP_H
#define GLINT_KERNEL_TONEMAP_H

#include "prelude.h"

GLINT_KERNEL_BEGIN

// Narkowicz 2015, "ACES Filmic Tone Mapping Curve": a fit of the ACES reference rendering transform,
// per channel on linear radiance times exposure; output in [0, 1].
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

// `pixel`'s threshold in the 8 x 8 Bayer matrix, in (0, 1): each tile holds all 64 thresholds
// (k + 0.5) / 64, neighbours differing. Bayer's recursion: each bit pair of the coordinates, lowest
// first, picks the quadrant of the next finer level.
GLINT_FN float glintOrderedDitherThreshold(ivec2 pixel) {
  int rank = 0;
  for (int bit = 0; bit < 3; ++bit) {
    rank = rank * 4 + 2 * (((pixel.x ^ pixel.y) >> bit) & 1) + ((pixel.y >> bit) & 1);
  }
  return (float(rank) + 0.5f) / 64.0f;
}

// The display values as 8-bit codes (whole numbers 0..255 in floats) of pixel `pixel` (x from the
// left, y from the top): the one rounding of the CPU's images and the GPU's display pass, as OpenGL
// leaves rounding to an 8-bit framebuffer to the implementation. Dithered by up to half a code by the
// pixel's Bayer threshold, so smooth gradients show no bands (an 8 x 8 tile of one value averages to
// it within 1/64 of a code). Position alone decides, so every run gives the same bytes; a value
// exactly on a code keeps it (black stays black, white white).
GLINT_FN vec3 glintDisplayCodeValues(vec3 radiance, float exposure, ivec2 pixel) {
  vec3 code = floor(glintDisplayEncode(radiance, exposure) * 255.0f + glintOrderedDitherThreshold(pixel));
  return clamp(code, 0.0f, 255.0f);
}

GLINT_KERNEL_END

#endif
