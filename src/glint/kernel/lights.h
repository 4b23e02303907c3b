// The falloff of punctual lights (KHR_lights_punctual), for the rasteriser (forward.frag) and the path
// tracer: a spot light's intensity falls off between an inner and an outer cone, and a point or spot
// light may have a range beyond which it is dark.
#ifndef GLINT_KERNEL_LIGHTS_H
#define GLINT_KERNEL_LIGHTS_H

#include "prelude.h"

GLINT_KERNEL_BEGIN

// The cone as a scale and offset of the cosine (the extension's recommended implementation): full
// intensity within the inner angle, none beyond the outer. No cone: (0, 1).
GLINT_FN vec2 glintSpotConeScaleOffset(float innerConeAngle, float outerConeAngle) {
  float cosOuter = cos(outerConeAngle);
  float scale = 1.0f / max(0.001f, cos(innerConeAngle) - cosOuter);
  return vec2(scale, -cosOuter * scale);
}

// The fraction of the intensity sent towards a point (`axis` the spot's direction, `towardsLight` the
// unit direction to the light): the cosine's linear ramp between the cones, squared.
GLINT_FN float glintSpotAttenuation(vec3 axis, vec3 towardsLight, vec2 coneScaleOffset) {
  float ramp = clamp(dot(axis, -towardsLight) * coneScaleOffset.x + coneScaleOffset.y, 0.0f, 1.0f);
  return ramp * ramp;
}

// `range`: the extension's recommended window on the inverse-square law, max(min(1 - (d / range)^4,
// 1), 0), 0 at the range and nearly 1 close to the light. `inverseRange` is 1 / range, 0 without one;
// `distance2` is d^2.
GLINT_FN float glintRangeWindow(float distance2, float inverseRange) {
  float ratio2 = distance2 * inverseRange * inverseRange;
  return clamp(1.0f - ratio2 * ratio2, 0.0f, 1.0f);
}

GLINT_KERNEL_END

#endif
