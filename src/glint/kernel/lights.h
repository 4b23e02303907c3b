// The falloff of punctual lights, shared by the rasteriser (forward.frag) and the path tracer: a
// spot light (KHR_lights_punctual) is a point light whose intensity falls off between an inner and
// an outer cone around its axis, and a point or spot light may have a range beyond which it is
// dark. See prelude.h for the rules of kernel code.
#ifndef GLINT_KERNEL_LIGHTS_H
#define GLINT_KERNEL_LIGHTS_H

#include "prelude.h"

GLINT_KERNEL_BEGIN

// The cone as a scale and an offset of the cosine (KHR_lights_punctual's recommended
// implementation): full intensity within the inner angle, none beyond the outer one. A light
// without a cone is (0, 1).
GLINT_FN vec2 glintSpotConeScaleOffset(float innerConeAngle, float outerConeAngle) {
  float cosOuter = cos(outerConeAngle);
  float scale = 1.0f / max(0.001f, cos(innerConeAngle) - cosOuter);
  return vec2(scale, -cosOuter * scale);
}

// The fraction of the light's intensity sent towards a point: `axis` is the direction the spot
// shines along, `towardsLight` the unit direction from the point to the light. The glTF
// extension's smooth falloff: the linear ramp of the cosine between the cones, squared.
GLINT_FN float glintSpotAttenuation(vec3 axis, vec3 towardsLight, vec2 coneScaleOffset) {
  float ramp = clamp(dot(axis, -towardsLight) * coneScaleOffset.x + coneScaleOffset.y, 0.0f, 1.0f);
  return ramp * ramp;
}

// KHR_lights_punctual's `range` for point and spot lights: the extension's recommended window on
// top of the inverse-square law, max(min(1 - (d / range)^4, 1), 0), which reaches 0 at the range and
// leaves the light nearly unchanged close to it. `inverseRange` is 1 / range, 0 for a light without
// one (the window is then 1); `distance2` is d^2.
GLINT_FN float glintRangeWindow(float distance2, float inverseRange) {
  float ratio2 = distance2 * inverseRange * inverseRange;
  return clamp(1.0f - ratio2 * ratio2, 0.0f, 1.0f);
}

GLINT_KERNEL_END

#endif
