// glint's extension of the 2020 glint model (Chermain et al. 2020) to extended lights: the mass of
// the footprint's P-NDF over the half vectors that send the view into a light's solid angle, the
// same cells, weights and draws as the P-SDF (glint_brdf.h), so that an area light or a region of
// an environment lights the very flakes a path tracer of the same microstructure shows
// (docs/method.md, "Extended lights").
//
// With slopes s = -h.xy / h.z, D(h) dw_h = P22(s) / cos(theta_h) ds, so a light's reflected radiance
// is about L F G2 |wo.h| / (|n.wo| cos(theta_h)) times M = the integral of P22 over the light's
// region of slope space (docs/method.md, Eq. EL-2). A dictionary cell's P22 is J p_i(x') p_j(y'),
// (x', y') its rotated, unscaled slope and J the Jacobian of that map, so over a region its mass is
// the integral of p_i(x') p_j(y') over the region's image in the cell's frame, the Jacobian gone:
// over a box, a product of two differences of the marginals' cumulative tables. The region, a
// polygon in slope space (the half vectors of a light's corners, clipped to the horizon, and of its
// edges' midpoints), is cut into GLINT_REGION_STRIPS strips across the cell's x' axis, each a box
// whose y' extent is the polygon's at the strip's centroid. The smooth cells (Beckmann) are Gaussian in the unscaled
// frame: the same strips with the normal CDF. GGX's remainder and target, whose slope density is
// not separable, take each strip's area times the density at its centre.
// The anti-aliasing filter of 2021 is not applied here: a region's integral is itself a box filter
// of the P-NDF, wider than the filter wherever a light covers more than a few texels of a lobe.
// Shared by the CPU library and the shading languages: see prelude.h for the rules.
#ifndef GLINT_KERNEL_GLINT_EXTENDED_LIGHTS_H
#define GLINT_KERNEL_GLINT_EXTENDED_LIGHTS_H

#include "prelude.h"
#include "glint_brdf.h"

GLINT_KERNEL_BEGIN

// The regions evaluated by one walk over the footprint's cells, a compile-time constant as
// GLINT_SLOPE_COUNT is; and the strips a region is cut into across its x extent in a cell's frame
// (glintRegionStrip).
#ifndef GLINT_REGION_COUNT
#define GLINT_REGION_COUNT 1
#endif
#ifndef GLINT_REGION_STRIPS
#define GLINT_REGION_STRIPS 8
#endif
// A light's quadrilateral clipped to the horizon has at most 5 corners; with each edge's midpoint,
// a region has 10 vertices.
#define GLINT_LIGHT_CORNERS 5
// The smooth lobe's mass below which a region's flakes are not walked (glintRegionMassSet).
#define GLINT_REGION_NEGLIGIBLE_MASS 1e-4f
#define GLINT_REGION_VERTICES 10
// The share of the smooth target's mass over a region that a cell may leave uncounted: its strips
// whose x mass falls below their part of it skip the y marginal (glintCellRegionMoments). The cells
// average, so the P-SDF's mass over the region loses at most this fraction.
#ifndef GLINT_CELL_NEGLIGIBLE_FRACTION
#define GLINT_CELL_NEGLIGIBLE_FRACTION 1e-3f
#endif

// A region of slope space: a polygon, its vertices in order around it (either way round); a
// polygon of fewer vertices repeats its last one.
struct GlintSlopeRegion {
  vec2 vertex[GLINT_REGION_VERTICES];
};

struct GlintRegionSet {
  GlintSlopeRegion region[GLINT_REGION_COUNT];
};

struct GlintRegionMassSet {
  vec4 mass[GLINT_REGION_COUNT];        // the P-SDF's mass over each region; .rgb weighted by the cells' colours
  vec2 meanSlope[GLINT_REGION_COUNT];   // where the P-SDF's mass over it lies on average (glintRegionReflectanceAt)
  vec2 moment[GLINT_REGION_COUNT];      // the P-SDF's first moment over it, in the unscaled frame (glintUnscaledSlope)
  float targetMass[GLINT_REGION_COUNT];  // the smooth target's mass over the same region, by the same strips
  vec2 targetMeanSlope[GLINT_REGION_COUNT];  // where that mass lies on average
  vec4 totalMass;  // the P-SDF's mass over every slope, as .mass (1 for the smooth target)
};

// A light's corners seen from the shading point: unit directions in the shading frame, clipped to
// the part above the horizon (count 0 to 5, the unused slots repeating the last corner).
struct GlintClippedLight {
  vec3 corner[GLINT_LIGHT_CORNERS];
  int count;
};

// The slope of the half vector between wo and wi (both in the shading frame, wo above the
// horizon). A wi below the horizon still has a half vector above it; one that would lie on the
// horizon is lifted just above it, so that the slope stays finite.
GLINT_FN vec2 glintHalfVectorSlope(vec3 wo, vec3 wi) {
  vec3 h = wo + wi;
  h.z = max(h.z, 1e-3f * length(h) + 1e-6f);
  return glintSlopeFromNormal(normalize(h));
}

// The part above the horizon of a light of corners wi0..wi3 (unit directions towards them, in the
// shading frame, in order around the light). A planar polygon's edges are arcs of great circles
// seen from any point, and so is the horizon: clipping the corners' polygon by the plane z = 0 and
// normalising is exact (Heitz et al. 2016 clip the same way). Directions just above the horizon
// (z >= 1e-4) keep the half vectors' slopes finite.
GLINT_FN GlintClippedLight glintClipLightToHorizon(vec3 wi0, vec3 wi1, vec3 wi2, vec3 wi3) {
  vec3 corners[4];
  corners[0] = wi0;
  corners[1] = wi1;
  corners[2] = wi2;
  corners[3] = wi3;
  GlintClippedLight light;
  light.count = 0;
  for (int k = 0; k < GLINT_LIGHT_CORNERS; ++k) {
    light.corner[k] = vec3(0.0f, 0.0f, 1.0f);
  }
  const float lowest = 1e-4f;
  for (int k = 0; k < 4; ++k) {
    vec3 a = corners[k];
    vec3 b = corners[(k + 1) % 4];
    if (a.z >= lowest) {
      light.corner[light.count] = a;
      light.count += 1;
    }
    if ((a.z >= lowest) != (b.z >= lowest)) {
      light.corner[light.count] = normalize(glintMix(a, b, (lowest - a.z) / (b.z - a.z)));
      light.count += 1;
    }
  }
  for (int k = 1; k < GLINT_LIGHT_CORNERS; ++k) {
    if (k >= light.count && light.count > 0) {
      light.corner[k] = light.corner[k - 1];
    }
  }
  return light;
}

// The direction the light's reflectance is taken in (glintRegionReflectance): the mean of its
// clipped corners, the light's centre when none is clipped; straight up when none is above the
// horizon, where its mass is zero.
GLINT_FN vec3 glintClippedLightCentre(GlintClippedLight light) {
  vec3 sum = glintSplat3(0.0f);
  for (int k = 0; k < GLINT_LIGHT_CORNERS; ++k) {
    sum += k < light.count ? light.corner[k] : glintSplat3(0.0f);
  }
  return light.count > 0 ? normalize(sum) : vec3(0.0f, 0.0f, 1.0f);
}

// The clipped light's cosine-weighted solid angle, the integral of wi.z over it: by Lambert's
// formula for a spherical polygon, half the sum over its edges of each arc's angle times the z of
// its plane's unit normal (the form factor of a polygon; Arvo 1995). Times the light's
// radiance, its irradiance; times a Lambertian albedo / pi, its diffuse reflection.
GLINT_FN float glintClippedLightProjectedSolidAngle(GlintClippedLight light) {
  float sum = 0.0f;
  for (int k = 0; k < GLINT_LIGHT_CORNERS; ++k) {
    if (k < light.count) {
      vec3 a = light.corner[k];
      vec3 b = light.corner[k + 1 < light.count ? k + 1 : 0];
      vec3 normal = cross(a, b);
      float sine = length(normal);
      if (sine > 0.0f) {
        sum += acos(clamp(dot(a, b), -1.0f, 1.0f)) * normal.z / sine;
      }
    }
  }
  return 0.5f * abs(sum);
}

// The region of slope space that the clipped light sends wo into: the polygon of its corners' and
// its edges' midpoints' half-vector slopes (docs/method.md, "Extended lights": exact at those ten
// points, straight between them). The half-vector map bends a light's edges in slope space; their
// midpoints keep a light up to 60 degrees across within a few percent of its mass.
GLINT_FN GlintSlopeRegion glintLightSlopeRegion(vec3 wo, GlintClippedLight light) {
  GlintSlopeRegion region;
  for (int k = 0; k < GLINT_LIGHT_CORNERS; ++k) {
    vec3 a = light.corner[k];
    vec3 b = light.corner[(k + 1) % GLINT_LIGHT_CORNERS];
    region.vertex[2 * k] = glintHalfVectorSlope(wo, a);
    // A great circle's arc's midpoint; the same point for a repeated corner.
    region.vertex[2 * k + 1] = glintHalfVectorSlope(wo, normalize(a + b));
  }
  return region;
}

// A region mapped by the linear map of the footprint's unscaling (glintUnscaledSlope).
GLINT_FN GlintSlopeRegion glintUnscaledRegion(GlintDictionaryView dict, GlintParameters params, GlintSlopeRegion region) {
  GlintSlopeRegion unscaled;
  for (int k = 0; k < GLINT_REGION_VERTICES; ++k) {
    unscaled.vertex[k] = glintUnscaledSlope(dict, params, region.vertex[k]);
  }
  return unscaled;
}

// A region in a cell's frame: scaled by the cell's GGX unscale, then turned by its rotation
// (glintDictionarySlope).
GLINT_FN GlintSlopeRegion glintCellRegion(vec2 rotation, float unscale, GlintSlopeRegion unscaled) {
  GlintSlopeRegion local;
  for (int k = 0; k < GLINT_REGION_VERTICES; ++k) {
    local.vertex[k] = glintDictionarySlope(rotation, unscaled.vertex[k] * unscale);
  }
  return local;
}

// The region's extent along x and along y: (xmin, xmax, ymin, ymax).
GLINT_FN vec4 glintRegionBounds(GlintSlopeRegion region) {
  vec4 bounds = vec4(region.vertex[0].x, region.vertex[0].x, region.vertex[0].y, region.vertex[0].y);
  for (int k = 1; k < GLINT_REGION_VERTICES; ++k) {
    vec2 v = region.vertex[k];
    bounds = vec4(min(bounds.x, v.x), max(bounds.y, v.x), min(bounds.z, v.y), max(bounds.w, v.y));
  }
  return bounds;
}

GLINT_FN vec2 glintRegionXRange(GlintSlopeRegion region) {
  vec4 bounds = glintRegionBounds(region);
  return vec2(bounds.x, bounds.y);
}

// Where the vertical line at x crosses the edge from a to b: widens (low, high) by its y.
GLINT_FN vec2 glintEdgeCrossing(vec2 a, vec2 b, float x, vec2 range) {
  float dx = b.x - a.x;
  if ((x - a.x) * (x - b.x) <= 0.0f && dx != 0.0f) {
    float y = a.y + (x - a.x) * (b.y - a.y) / dx;
    return vec2(min(range.x, y), max(range.y, y));
  }
  return range;
}

// The region's extent along y on the vertical line at x: (low, high), low > high where the line
// misses it.
GLINT_FN vec2 glintRegionYAt(GlintSlopeRegion region, float x) {
  vec2 range = vec2(3.0e38f, -3.0e38f);
  for (int k = 0; k < GLINT_REGION_VERTICES; ++k) {
    range = glintEdgeCrossing(region.vertex[k], region.vertex[(k + 1) % GLINT_REGION_VERTICES], x, range);
  }
  return range;
}

// Strip k of GLINT_REGION_STRIPS equal strips across the x interval (start, end).
GLINT_FN vec2 glintRegionStrip(vec2 xRange, int k) {
  float width = (xRange.y - xRange.x) / float(GLINT_REGION_STRIPS);
  return vec2(xRange.x + float(k) * width, k + 1 == GLINT_REGION_STRIPS ? xRange.y : xRange.x + float(k + 1) * width);
}

// The signed cumulative marginal and its first moment: the integrals of table `level`'s marginal
// of `distribution`, and of the slope times it, from 0 to x: (C(x), M(x)), C odd and M even in x,
// C +-1/2 beyond the support for a normalised marginal. The interpolation is glintMarginal's,
// linear between texels, so that these are exactly its integrals: the cumulative texel
// (glintDictionaryCumulativeTexel, which carries texel k's pair too: one read) plus texel k's part.
GLINT_FN vec2 glintCumulativeMarginal(GlintDictionaryView dict, int level, int distribution, float x) {
  float fourSigma = glintDictionaryDomain(dict);
  float spacing = fourSigma / float(dict.texelsPerDistribution);
  float t = min(abs(x), fourSigma) / spacing;
  int k = min(int(t), dict.texelsPerDistribution - 1);
  float f = t - float(k);
  vec4 texel = glintDictionaryCumulativeTexel(dict, level, distribution, k);
  vec2 base = vec2(texel.x, texel.y);
  vec2 ab = vec2(texel.z, texel.w);
  float rise = ab.y - ab.x;
  float c = base.x + spacing * f * (ab.x + 0.5f * f * rise);
  // The integral of (k + s) spacing (a + rise s) spacing ds over [0, f].
  float m = base.y + spacing * spacing * f * (float(k) * ab.x + 0.5f * f * (float(k) * rise + ab.x) + f * f * rise / 3.0f);
  return vec2(x < 0.0f ? -c : c, m);
}

// The same for a cell's marginal on one axis, the level or with `complement` the lobes the next
// level adds (glintBlockMarginal).
GLINT_FN vec2 glintCumulativeBlockMarginal(GlintDictionaryView dict, int level, int distribution, int complement, float x) {
  vec2 prefix = glintCumulativeMarginal(dict, level, distribution, x);
#if GLINT_CONSISTENT_LOD_COMPILED
  if (complement != 0) {
    return 2.0f * glintCumulativeMarginal(dict, level + 1, distribution, x) - prefix;
  }
#endif
  return prefix;
}

// Where in a strip its x marginal's mass lies: its mean over the strip, from the differences of
// the cumulative marginal and first moment; the strip's middle where it holds no mass.
GLINT_FN float glintStripCentroid(vec2 strip, vec2 startIntegrals, vec2 endIntegrals) {
  float mass = endIntegrals.x - startIntegrals.x;
  float mean = abs(mass) > 1e-12f ? (endIntegrals.y - startIntegrals.y) / mass : 0.5f * (strip.x + strip.y);
  return clamp(mean, strip.x, strip.y);
}

// A dictionary cell's mass over a region in its own frame (glintCellRegion), and its first moments
// there: (mass, integral of x, integral of y). Per strip, the x marginal's mass (and first moment)
// over the strip times the y marginal's mass (and first moment) over the region's y extent at the
// strip's centroid (the centroid rule: exact where the y marginal's mass varies linearly across the
// strip). A strip whose x marginal holds at most its share of `negligible` is counted as 0 without
// reading the y marginal (the y marginal's mass is at most 1), so that a cell loses at most
// `negligible`.
GLINT_FN vec3 glintCellRegionMoments(GlintDictionaryView dict, GlintCell cell, GlintSlopeRegion local, float negligible) {
  float fourSigma = glintDictionaryDomain(dict);
  vec4 bounds = glintRegionBounds(local);
  vec2 xRange = clamp(vec2(bounds.x, bounds.y), glintSplat2(-fourSigma), glintSplat2(fourSigma));
  if (!(xRange.x < xRange.y && bounds.z < fourSigma && bounds.w > -fourSigma)) {
    return glintSplat3(0.0f);  // the region misses the cell's support (a NaN vertex misses it too)
  }
  vec2 start = glintCumulativeBlockMarginal(dict, cell.dictionaryLevel, cell.distributions.x, cell.complement.x, xRange.x);
  float stripNegligible = negligible / float(GLINT_REGION_STRIPS);
  vec3 moments = glintSplat3(0.0f);
  for (int k = 0; k < GLINT_REGION_STRIPS; ++k) {
    vec2 strip = glintRegionStrip(xRange, k);
    vec2 end = glintCumulativeBlockMarginal(dict, cell.dictionaryLevel, cell.distributions.x, cell.complement.x, strip.y);
    if (end.x - start.x > stripNegligible) {
      vec2 across = glintRegionYAt(local, glintStripCentroid(strip, start, end));
      if (across.y > across.x) {
        vec2 y = glintCumulativeBlockMarginal(dict, cell.dictionaryLevel, cell.distributions.y, cell.complement.y, across.y) -
                 glintCumulativeBlockMarginal(dict, cell.dictionaryLevel, cell.distributions.y, cell.complement.y, across.x);
        vec2 x = end - start;
        moments += vec3(x.x * y.x, x.y * y.x, x.x * y.y);
      }
    }
    start = end;
  }
  return moments;
}

// The standard normal's cumulative integrals at x / sigma, scaled to a normal of std sigma: (CDF
// minus 1/2, the first moment from 0), as glintCumulativeMarginal's.
GLINT_FN vec2 glintCumulativeNormal(float x, float sigma) {
  float z = x / sigma;
  return vec2(glintNormalCdf(z) - 0.5f, sigma * 0.39894228f * (1.0f - exp(-0.5f * z * z)));
}

// The mass over an unscaled region of the isotropic Gaussian of standard deviation sigma per axis
// (the Beckmann target, and the smooth cells, in the unscaled frame, where their sigma is
// sigma_d), by glintCellRegionMoments' strips and centroid rule, and its first moments:
// (mass, integral of x, integral of y).
GLINT_FN vec3 glintGaussianRegionMoments(GlintSlopeRegion unscaled, float sigma) {
  vec2 xRange = clamp(glintRegionXRange(unscaled), glintSplat2(-4.0f * sigma), glintSplat2(4.0f * sigma));
  vec3 moments = glintSplat3(0.0f);
  if (!(xRange.x < xRange.y)) {
    return moments;
  }
  vec2 start = glintCumulativeNormal(xRange.x, sigma);
  for (int k = 0; k < GLINT_REGION_STRIPS; ++k) {
    vec2 strip = glintRegionStrip(xRange, k);
    vec2 end = glintCumulativeNormal(strip.y, sigma);
    vec2 across = glintRegionYAt(unscaled, glintStripCentroid(strip, start, end));
    if (across.y > across.x) {
      vec2 low = glintCumulativeNormal(across.x, sigma);
      vec2 high = glintCumulativeNormal(across.y, sigma);
      moments += vec3((end.x - start.x) * (high.x - low.x), (end.y - start.y) * (high.x - low.x), (end.x - start.x) * (high.y - low.y));
    }
    start = end;
  }
  return moments;
}

// GGX's slope density in its unscaled frame, 1 / (pi (1 + x^2 + y^2)^2), integrated as
// glintGaussianRegionMoments integrates the Gaussian: its marginal along x, 1 / (2 a^3) with
// a^2 = 1 + x^2, has the antiderivatives x / (2 a) (its CDF minus 1/2) and -1 / (2 a) (of its first
// moment), and across a strip, at the strip's centroid, the density along y given x,
// (2 a^3 / pi) / (a^2 + y^2)^2, has (atan(y / a) + a y / (a^2 + y^2)) / pi and -a^3 / (pi (a^2 + y^2));
// only their differences are used.
// Closed forms, so that a lobe far narrower than the light's region (a smooth clear coat under a
// softbox) keeps its mass, where the midpoint rule's few samples miss or overcount its peak.
GLINT_FN vec2 glintGgxCumulativeMarginal(float x) {
  float a = sqrt(1.0f + x * x);
  return vec2(0.5f * x / a, -0.5f / a);
}

GLINT_FN vec2 glintGgxCumulativeConditional(float y, float a) {
  float q = a * a + y * y;
  return vec2((atan(y / a) + a * y / q) * 0.31830989f, -a * a * a / q * 0.31830989f);
}

GLINT_FN vec3 glintGgxRegionMoments(GlintSlopeRegion unscaled) {
  vec2 xRange = glintRegionXRange(unscaled);
  vec3 moments = glintSplat3(0.0f);
  if (!(xRange.x < xRange.y)) {
    return moments;
  }
  vec2 start = glintGgxCumulativeMarginal(xRange.x);
  for (int k = 0; k < GLINT_REGION_STRIPS; ++k) {
    vec2 strip = glintRegionStrip(xRange, k);
    vec2 end = glintGgxCumulativeMarginal(strip.y);
    float xAt = glintStripCentroid(strip, start, end);
    vec2 across = glintRegionYAt(unscaled, xAt);
    if (across.y > across.x) {
      float a = sqrt(1.0f + xAt * xAt);
      vec2 low = glintGgxCumulativeConditional(across.x, a);
      vec2 high = glintGgxCumulativeConditional(across.y, a);
      moments += vec3((end.x - start.x) * (high.x - low.x), (end.y - start.y) * (high.x - low.x), (end.x - start.x) * (high.y - low.y));
    }
    start = end;
  }
  return moments;
}

// The midpoint rule over the strips of a region in the unscaled frame of roughness alpha,
// correlation rho and dictionary roughness alphaD (glintCorrelatedUnscale) for a slope density that
// is not separable: each strip's area times the density at its centre, mapped back to slope space
// and divided by the unscaling's Jacobian; with its first moments in the unscaled frame, as
// glintGaussianRegionMoments'. `tail` chooses GGX's smooth remainder (glintStudentTailSlopeP22)
// over the target's P22.
GLINT_FN vec3 glintMidpointRegionMoments(int ndf, vec2 alpha, float rho, float alphaD, GlintSlopeRegion unscaled, bool tail) {
  vec2 xRange = glintRegionXRange(unscaled);
  vec3 covariance = glintBeckmannSlopeCovariance(alpha, rho);
  vec3 moments = glintSplat3(0.0f);
  for (int k = 0; k < GLINT_REGION_STRIPS; ++k) {
    vec2 strip = glintRegionStrip(xRange, k);
    float middle = 0.5f * (strip.x + strip.y);
    vec2 across = glintRegionYAt(unscaled, middle);
    if (across.y > across.x && strip.y > strip.x) {
      vec2 centre = vec2(middle, 0.5f * (across.x + across.y));
      vec2 slope = glintCorrelatedScale(centre, alpha, rho, alphaD);
      float p22 = tail ? glintStudentTailSlopeP22(slope, covariance) : glintTargetP22(ndf, slope, alpha, rho);
      float mass = (strip.y - strip.x) * (across.y - across.x) * p22;
      moments += vec3(mass, mass * centre.x, mass * centre.y);
    }
  }
  return moments / glintCorrelatedJacobian(alpha, rho, alphaD);
}

// A smooth lobe's mass over a region of slope space (GLINT_NDF_BECKMANN or GLINT_NDF_GGX of
// roughness alpha and correlation rho) and the mean slope of that mass: (mass, mean slope). In its
// unscaled frame (alpha_d = 1) Beckmann is the isotropic Gaussian of sigma 1 / sqrt 2, GGX
// 1 / (pi (1 + |u|^2)^2), each by the strips and its closed-form integrals. The smooth target of a glint layer, and the specular lobe of
// every material under extended lights; the mean slope is where the light's reflectance is taken
// (glintRegionReflectanceAt).
GLINT_FN vec3 glintSmoothRegionMoments(int ndf, vec2 alpha, float rho, GlintSlopeRegion region) {
  GlintSlopeRegion unscaled;
  for (int k = 0; k < GLINT_REGION_VERTICES; ++k) {
    unscaled.vertex[k] = glintCorrelatedUnscale(region.vertex[k], alpha, rho, 1.0f);
  }
  vec3 moments = ndf != GLINT_NDF_GGX ? glintGaussianRegionMoments(unscaled, 0.70710678f) : glintGgxRegionMoments(unscaled);
  if (!(moments.x > 0.0f)) {
    return glintSplat3(0.0f);
  }
  vec2 meanUnscaled = vec2(moments.y, moments.z) / moments.x;
  vec2 mean = glintCorrelatedScale(meanUnscaled, alpha, rho, 1.0f);
  return vec3(moments.x, mean.x, mean.y);
}

// The masses over one footprint level's cells (glintLevelP22's walk, weights and cells, the masses
// of its regions in place of the P22 at its slopes).
GLINT_FN GlintRegionMassSet glintLevelRegionMass(GlintDictionaryView dict, GlintParameters params, GlintFootprint footprint,
                                                 vec2 uv, int level, GlintLevelDraw draw, GlintRegionSet unscaled,
                                                 GlintRegionMassSet targets) {
  GlintCellGrid grid = glintCellGrid(footprint, uv, dict.numLevels, level);
  float dictionarySum[GLINT_REGION_COUNT];
  vec2 chromaSum[GLINT_REGION_COUNT];
  vec2 momentSum[GLINT_REGION_COUNT];  // the dictionary cells' first moments, in the unscaled frame
  // A region that misses the disc holding every rotated support reads no dictionary cell.
  float reach = glintDictionaryDomain(dict) * 1.41421356f * glintTargetWidestCell(params.ndf);
  bool inReach[GLINT_REGION_COUNT];
  bool anyInReach = false;
  for (int r = 0; r < GLINT_REGION_COUNT; ++r) {
    dictionarySum[r] = 0.0f;
    chromaSum[r] = glintSplat2(0.0f);
    momentSum[r] = glintSplat2(0.0f);
    vec4 bounds = glintRegionBounds(unscaled.region[r]);
    inReach[r] = bounds.x < reach && bounds.y > -reach && bounds.z < reach && bounds.w > -reach;
    anyInReach = anyInReach || inReach[r];
  }
  GlintLodDraws draws = glintLodDraws(dict, params, footprint.logDensity, level, draw);
  float weightSum = 0.0f;
  float smoothWeightSum = 0.0f;
  float tailWeightSum = 0.0f;
  // The dictionary cells' own weights: each cell's distribution holds a mass of 1 over all slopes.
  float dictionaryWeightSum = 0.0f;
  vec2 dictionaryChromaSum = glintSplat2(0.0f);
  GlintCellWalk walk = glintWalkStart(grid);
  while (glintWalkGoing(grid, walk)) {
    float weight = glintWalkWeight(grid, walk);
    ivec2 index = glintCellAt(grid, walk.s, walk.t);
    walk = glintWalkStep(grid, walk);
    if (weight > 0.0f) {
      weightSum += weight;
      GlintCell cell = glintLodCell(dict, params, draws, index.x, index.y, level);
      float covered = weight * cell.coverage;
      smoothWeightSum += cell.smoothLimit ? covered : 0.0f;
      tailWeightSum += cell.ggxTail ? covered : 0.0f;
      vec2 chroma = params.colouredCells && cell.readsDictionary ? glintCellChroma(cell.hash) : glintSplat2(0.0f);
      if (cell.readsDictionary) {
        dictionaryWeightSum += covered;
        dictionaryChromaSum += covered * chroma;
      }
      if (cell.readsDictionary && anyInReach) {
        vec2 rotation = glintCellRotation(cell.hash);
        for (int r = 0; r < GLINT_REGION_COUNT; ++r) {
          if (inReach[r]) {
            float negligible = GLINT_CELL_NEGLIGIBLE_FRACTION * targets.targetMass[r];
            vec3 moments = glintCellRegionMoments(dict, cell, glintCellRegion(rotation, cell.unscale, unscaled.region[r]), negligible);
            float weighted = covered * moments.x;
            dictionarySum[r] += weighted;
            // The cell's moment turned back by its rotation and unscaled by its GGX unscale.
            momentSum[r] += (covered / cell.unscale) * glintDictionarySlope(vec2(rotation.x, -rotation.y), vec2(moments.y, moments.z));
            if (params.colouredCells) {
              chromaSum[r] += weighted * chroma;
            }
          }
        }
      }
    }
  }
  GlintRegionMassSet masses;
  masses.totalMass = weightSum > 0.0f ? glintLevelAverage(params, dictionaryWeightSum, dictionaryChromaSum, 1.0f, smoothWeightSum,
                                                          tailWeightSum, weightSum)
                                      : glintSplat4(0.0f);
  for (int r = 0; r < GLINT_REGION_COUNT; ++r) {
    masses.mass[r] = glintSplat4(0.0f);
    masses.moment[r] = glintSplat2(0.0f);
    masses.meanSlope[r] = glintSplat2(0.0f);
    masses.targetMass[r] = 0.0f;
    masses.targetMeanSlope[r] = glintSplat2(0.0f);
    if (weightSum > 0.0f) {
      vec3 smoothPart = smoothWeightSum > 0.0f
                            ? smoothWeightSum * glintGaussianRegionMoments(unscaled.region[r], 0.70710678f * dict.alpha)
                            : glintSplat3(0.0f);
      vec3 tailPart = tailWeightSum > 0.0f ? tailWeightSum * glintMidpointRegionMoments(params.ndf, params.alpha, params.rho,
                                                                                         dict.alpha, unscaled.region[r], true)
                                           : glintSplat3(0.0f);
      // The dictionary cells' masses need no Jacobian (EL-3).
      masses.mass[r] = glintLevelAverage(params, dictionarySum[r], chromaSum[r], 1.0f, smoothPart.x, tailPart.x, weightSum);
      masses.moment[r] = (momentSum[r] + vec2(smoothPart.y + tailPart.y, smoothPart.z + tailPart.z)) / weightSum;
    }
  }
  return masses;
}

// The P-SDF's mass over each region of slope space, blended between the footprint's two levels as
// the P-SDF is (glintP22Set), and the smooth target's mass over each. A degenerate footprint is the
// smooth limit: its mass is the target's.
GLINT_FN GlintRegionMassSet glintRegionMassSet(GlintDictionaryView dict, GlintParameters params, vec2 uv, vec2 duvdx, vec2 duvdy,
                                               GlintRegionSet regions) {
  GlintRegionSet unscaled;
  GlintRegionMassSet targets;
  bool walked[GLINT_REGION_COUNT];
  targets.totalMass = glintSplat4(1.0f);
  for (int r = 0; r < GLINT_REGION_COUNT; ++r) {
    vec3 target = glintSmoothRegionMoments(params.ndf, params.alpha, params.rho, regions.region[r]);
    targets.targetMass[r] = target.x;
    targets.targetMeanSlope[r] = vec2(target.y, target.z);
    targets.mass[r] = glintSplat4(target.x);
    targets.meanSlope[r] = targets.targetMeanSlope[r];
    targets.moment[r] = glintSplat2(0.0f);
    // A region holding less than GLINT_REGION_NEGLIGIBLE_MASS of the smooth lobe is not walked: the
    // lobe's far tail, whose flakes reflect a ten-thousandth of the light; its mass is the target's.
    walked[r] = target.x >= GLINT_REGION_NEGLIGIBLE_MASS;
    unscaled.region[r] = glintUnscaledRegion(dict, params, regions.region[r]);
    if (!walked[r]) {
      for (int k = 0; k < GLINT_REGION_VERTICES; ++k) {
        unscaled.region[r].vertex[k] = glintSplat2(1.0e6f);  // beyond every cell's reach
      }
    }
  }
  GlintFootprint footprint = glintPixelFootprint(duvdx, duvdy, params, dict.numLevels);
  if (footprint.degenerate) {
    return targets;
  }
  GlintRegionMassSet masses;
  vec2 wrapped = glintWrapUv(uv, dict.numLevels);
  int level = glintLodLevel(footprint);
  float blend = glintLodBlend(footprint);
  GlintLevelDraw draw = glintLevelDraw(dict, params, footprint.logDensity, level);
  masses = glintLevelRegionMass(dict, params, footprint, wrapped, level, draw, unscaled, targets);
  masses.totalMass = (1.0f - blend) * masses.totalMass;
  for (int r = 0; r < GLINT_REGION_COUNT; ++r) {
    masses.mass[r] = (1.0f - blend) * masses.mass[r];
    masses.moment[r] = (1.0f - blend) * masses.moment[r];
  }
  if (blend > 0.0f) {
    GlintLevelDraw next = glintNextLevelDraw(dict, params, footprint.logDensity, level, draw);
    GlintRegionMassSet coarser = glintLevelRegionMass(dict, params, footprint, wrapped, level + 1, next, unscaled, targets);
    masses.totalMass += blend * coarser.totalMass;
    for (int r = 0; r < GLINT_REGION_COUNT; ++r) {
      masses.mass[r] += blend * coarser.mass[r];
      masses.moment[r] += blend * coarser.moment[r];
    }
  }
  for (int r = 0; r < GLINT_REGION_COUNT; ++r) {
    masses.targetMass[r] = targets.targetMass[r];
    masses.targetMeanSlope[r] = targets.targetMeanSlope[r];
    // The mean slope of the P-SDF's mass, back in the target's slopes; the target's where the
    // region holds next to none of it (its moment is then mostly rounding).
    bool holdsMass = walked[r] && masses.mass[r].w > 1e-3f * targets.targetMass[r];
    masses.meanSlope[r] = holdsMass ? glintScaledSlope(dict, params, masses.moment[r] / masses.mass[r].w) : targets.targetMeanSlope[r];
    if (!walked[r]) {
      masses.mass[r] = targets.mass[r];
    }
  }
  return masses;
}

// What scales the prefiltered environment's specular in a glint program whose first `regions`
// regions are the environment's (docs/method.md, "Extended lights", Eq. EL-5): the P-SDF's mass
// outside them (.rgb, tinted by the cells' colours) over the smooth target's. The regions take out
// of the map their mean radiance; the map left over (the residual, prefiltered as the smooth lobe)
// lights the half vectors outside them. A flake that moves mass out of a region moves it there,
// where the residual lights it: without this factor that mass would be lost and a region's surplus
// never paid for, which under light from everywhere alike (an overcast sky) is most of what the
// flakes change. Where the regions hold nearly all of the lobe, the residual is only their texels'
// spread about their means: the P-SDF's whole mass scales it. Both ends meet continuously: the
// masses outside are taken with GLINT_RESIDUAL_BLEND of the whole lobe added, at the P-SDF's
// average, so that a sliver of lobe outside the regions (where the quotient of two small, noisy
// masses would swing) tends to the whole mass's scale.
#define GLINT_RESIDUAL_BLEND 0.02f
GLINT_FN vec3 glintResidualEnvironmentScale(GlintRegionMassSet masses, int regions) {
  vec4 outside = masses.totalMass;
  float targetOutside = 1.0f;
  for (int r = 0; r < GLINT_REGION_COUNT; ++r) {
    if (r < regions) {
      outside -= masses.mass[r];
      targetOutside -= masses.targetMass[r];
    }
  }
  vec3 total = vec3(masses.totalMass.x, masses.totalMass.y, masses.totalMass.z);
  vec3 scale = (vec3(outside.x, outside.y, outside.z) + GLINT_RESIDUAL_BLEND * total) / (max(targetOutside, 0.0f) + GLINT_RESIDUAL_BLEND);
  return max(scale, glintSplat3(0.0f));
}

// The reflected radiance per unit radiance and per unit of slope-space mass for a light whose
// representative direction is wi (docs/method.md, Eq. EL-2): F G2 |wo.h| / (|n.wo| cos(theta_h)),
// with the lobe's masking, Fresnel left to the caller. Times a region's mass and its radiance,
// the light's reflected radiance; 0 where wi is below the horizon.
GLINT_FN float glintRegionReflectance(int masking, int ndf, vec2 alpha, float rho, vec3 wo, vec3 wi) {
  if (wo.z <= 0.0f || wi.z <= 0.0f) {
    return 0.0f;
  }
  vec3 wh = normalize(wo + wi);
  // glintMaskedReflectance with D = 1 is G2 / (4 wo.z wi.z); dw_i = 4 |wo.h| dw_h and
  // D dw_h = P22 ds / cos(theta_h) turn f |n.wi| dw_i into it times 4 wi.z |wo.h| / h.z P22 ds.
  return glintMaskedMicrofacetReflectance(masking, ndf, alpha, rho, wo, wi, wh, 1.0f) * 4.0f * wi.z * dot(wo, wh) / wh.z;
}

// The unit normal of slope `slope` (s = -h.xy / h.z): the half vector about which a region's mass
// lies, where a host takes its Fresnel.
GLINT_FN vec3 glintSlopeHalfVector(vec2 slope) {
  return normalize(vec3(-slope.x, -slope.y, 1.0f));
}

// The same per unit of mass for a region whose mass lies about the mean slope `slope`
// (glintSmoothRegionMoments): wi is wo reflected about that slope's normal; a reflection below the
// horizon takes `fallback` (the light's clipped centre, glintClippedLightCentre) instead.
GLINT_FN float glintRegionReflectanceAt(int masking, int ndf, vec2 alpha, float rho, vec3 wo, vec2 slope, vec3 fallback) {
  vec3 h = glintSlopeHalfVector(slope);
  vec3 wi = 2.0f * dot(wo, h) * h - wo;
  return glintRegionReflectance(masking, ndf, alpha, rho, wo, wi.z > 0.0f ? wi : fallback);
}

GLINT_KERNEL_END

#endif
