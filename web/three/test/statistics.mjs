// The glint statistics of a rendered view against the same view with the smooth lobe, as glint's
// own tests measure glints (tests/test_shadertoy.cpp): luminance (Rec. 709) of linear radiance;
// a pixel glints when it is brighter than twice the smooth render's plus a small absolute margin.
//   object pixels: those the smooth render lights (luminance > 0): the background and what no
//     light reaches are left out, in both renderers alike;
//   glintFraction: the share of object pixels that glint;
//   meanExcess: the mean of (glints - smooth) over the glinting pixels, in the renderers' linear
//     radiance (W/(m^2 sr) for glint's files: glint reads their lights at 683 lm/W);
//   meanRatio: mean luminance of the object pixels, glints over smooth (the model averages to the
//     smooth lobe).
export const GLINT_MARGIN = 0.02;

export function luminance(rgba, i) {
  return 0.2126 * rgba[4 * i] + 0.7152 * rgba[4 * i + 1] + 0.0722 * rgba[4 * i + 2];
}

// The pixels that glint, as glintStatistics counts them.
export function glintMask(glints, smooth) {
  const count = glints.length / 4;
  const mask = new Uint8Array(count);
  for (let i = 0; i < count; ++i) {
    const s = luminance(smooth, i);
    mask[i] = s > 0 && luminance(glints, i) > 2 * s + GLINT_MARGIN ? 1 : 0;
  }
  return mask;
}

// The share of the glint pixels of `a` that glint in `b` too.
export function sharedGlintPixels(a, b) {
  let glinting = 0;
  let shared = 0;
  for (let i = 0; i < a.length; ++i) {
    glinting += a[i];
    shared += a[i] & b[i];
  }
  return glinting ? shared / glinting : 0;
}

export function glintStatistics(glints, smooth) {
  const count = glints.length / 4;
  if (smooth.length !== glints.length) throw new Error('the two renders differ in size');
  let objectPixels = 0;
  let glinting = 0;
  let excess = 0;
  let glintSum = 0;
  let smoothSum = 0;
  for (let i = 0; i < count; ++i) {
    const s = luminance(smooth, i);
    if (!(s > 0)) continue;
    const g = luminance(glints, i);
    ++objectPixels;
    glintSum += g;
    smoothSum += s;
    if (g > 2 * s + GLINT_MARGIN) {
      ++glinting;
      excess += g - s;
    }
  }
  return {
    objectPixels,
    glintPixels: glinting,
    glintFraction: glinting / Math.max(objectPixels, 1),
    meanExcess: glinting ? excess / glinting : 0,
    meanRatio: smoothSum > 0 ? glintSum / smoothSum : 0,
  };
}
