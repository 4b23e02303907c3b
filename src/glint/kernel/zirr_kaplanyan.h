// The real-time glint BRDF of Zirr & Kaplanyan 2016, "Real-time Rendering of Procedural Multiscale
// Materials" (I3D 2016, DOI 10.1145/2856400.2856409): a baseline next to Chermain et al. 2020.
// Written from the team's specification ../shared/docs/zirr-kaplanyan-2016.md (cited as "spec" and a section),
// no reference code copied. Shared by the CPU library and the GLSL renderer: see prelude.h for the
// kernel rules, docs/zirr-kaplanyan.md for the deviations and what the tests measured.
//
// The model (spec 1.3): the smooth Beckmann BRDF times a stochastic "found / expected microdetails"
// ratio, counted per cell of a multilevel uv grid and per bin of the half-vector domain with a
// binomial law, filtered over the pixel footprint and blended between two grid levels.
//
// Deviations from the reference code, all documented in docs/zirr-kaplanyan.md:
//   - integer hashing (glintPcg4d) of (cell id, pattern seed) and (bin, cell) instead of the sin-based
//     float hash: identical on CPU and GPU, no float-precision aliasing (spec 4.4); hence no
//     +100 uv offset and no 533 u2 bin offset, which served that hash;
//   - the binomial's P(0) = (1 - q)^N uses an accurate log(1 - q), the count tail is applied only
//     where the scan found no count, and q = 1 is the certain count (the reference divides by
//     1 - q = 0 there);
//   - float-range guards: levels in [GLINT_ZIRR_KAPLANYAN_MIN_LEVEL, GLINT_ZIRR_KAPLANYAN_MAX_LEVEL], expected
//     counts at most e^GLINT_ZIRR_KAPLANYAN_MAX_LOG_COUNT, cells with fewer than
//     GLINT_ZIRR_KAPLANYAN_MIN_EXPECTED_COUNT expected microdetails are empty;
//   - the cone term uses (wo.h + wi.h) / 2 for wi.h (equal in exact arithmetic) so that the
//     evaluation is reciprocal bit for bit; cells of zero coverage weight are not evaluated.
#ifndef GLINT_KERNEL_ZIRR_KAPLANYAN_H
#define GLINT_KERNEL_ZIRR_KAPLANYAN_H

#include "prelude.h"
#include "random.h"
#include "microfacet.h"
#include "glint_brdf.h"

GLINT_KERNEL_BEGIN

// Global cap on cell visits, both levels together: the isolated (normative) code's IT_MAX
// (spec 2.3; the Shadertoy uses 60). With at most 2 x 18 x 4 = 144 visits it never binds.
GLINT_CONST int GLINT_ZIRR_KAPLANYAN_MAX_CELL_VISITS = 150;
GLINT_CONST int GLINT_ZIRR_KAPLANYAN_MAX_ROWS = 18;         // rows per level, long axis (spec 2.3)
GLINT_CONST int GLINT_ZIRR_KAPLANYAN_MAX_CELLS_PER_ROW = 4;   // cells per row, short axis (spec 2.3)
GLINT_CONST float GLINT_ZIRR_KAPLANYAN_REFERENCE_MAX_ANISOTROPY = 16.0f;  // K_a of the reference (spec 1.6)
GLINT_CONST float GLINT_ZIRR_KAPLANYAN_STEREOGRAPHIC_SCALE = 0.75f;      // q = 0.75 H.xy / (1 + H.z) (spec 3 step 3)
GLINT_CONST float GLINT_ZIRR_KAPLANYAN_MIN_MESO_VARIANCE = 1e-12f;        // inside the meso roughness sqrt (spec 3 step 2)
GLINT_CONST float GLINT_ZIRR_KAPLANYAN_VARIATION_CLAMP = 0.999f;         // erfinv argument of the count multiplier (spec 3 step 7)
GLINT_CONST float GLINT_ZIRR_KAPLANYAN_MIN_MULTIPLIER = 1e-12f;          // floor of the count multiplier (spec 3 step 7)
GLINT_CONST float GLINT_ZIRR_KAPLANYAN_GAUSSIAN_THRESHOLD = 5.0f;        // N p above it: normal approximation (spec 3.9)
GLINT_CONST float GLINT_ZIRR_KAPLANYAN_GAUSSIAN_CLAMP = 0.999999f;       // erfinv argument of that branch (spec 3.9)
GLINT_CONST float GLINT_ZIRR_KAPLANYAN_MIN_PROBABILITY = 1e-30f;         // P_MIN of the isolated code (spec 3.9)
GLINT_CONST float GLINT_ZIRR_KAPLANYAN_LOG2_QUANTISATION_BASE = -0.152003093f;  // log2(0.9): p quantised to 0.9^k (spec 3.9)
GLINT_CONST int GLINT_ZIRR_KAPLANYAN_BINOMIAL_SCAN = 18;                  // inverse-CDF scan i = 0..17, then the tail (spec 3.9)
// Guards of the float range (not in the reference): cell sizes 2^-24..2^24 uv keep cell indices
// inside int; expected counts up to 1e30 per cell keep every product finite (beyond, the relative
// noise sqrt(1 / (E p)) is far below float precision: the smooth limit); a cell expecting fewer
// than 1e-30 microdetails is empty (the reference divides by that count).
GLINT_CONST float GLINT_ZIRR_KAPLANYAN_MIN_LEVEL = -24.0f;
GLINT_CONST float GLINT_ZIRR_KAPLANYAN_MAX_LEVEL = 24.0f;
GLINT_CONST float GLINT_ZIRR_KAPLANYAN_MAX_LOG_COUNT = 69.0f;  // ln(1e30)
GLINT_CONST float GLINT_ZIRR_KAPLANYAN_MIN_EXPECTED_COUNT = 1e-30f;
// The reference's glints() averages to a quarter of Cook-Torrance's f (its "solid angle" /4 on
// top of the Smith term's own 1/4, spec 1.7). Scaled by 4 (spec 4.2, "output scale": x 4 n.l
// onto f cos, i.e. x 4 onto f) the mean is Cook-Torrance with a Beckmann D and a GGX-form Smith G,
// comparable to glintReflectance.
GLINT_CONST float GLINT_ZIRR_KAPLANYAN_OUTPUT_SCALE = 4.0f;
// Mapping from our parameters (spec 4.2): a microdetail's lobe exp(-d^2 / mu^2) has std mu / sqrt(2);
// Chermain's per-microfacet lobe has std lobeStd * alpha / alpha_d = 0.02 alpha / 0.5 per axis, so
// mu = sqrt(2) 0.04 alpha.
GLINT_CONST float GLINT_ZIRR_KAPLANYAN_MICRO_ROUGHNESS_PER_ALPHA = 0.0565685425f;
// Chermain has no clamp on found / expected: a dynamic range that only cells expecting fewer than
// 1e-6 glinting microdetails reach (their rare spikes are clamped to 1e6 times the mean).
GLINT_CONST float GLINT_ZIRR_KAPLANYAN_MAPPED_DYNAMIC_RANGE = 1e6f;

// The model's own parameters (spec 2.2), validated by the host.
struct GlintZirrKaplanyanParameters {
  vec2 roughness;         // r: macro Beckmann roughness per axis (x = tangent = +u, y = +v)
  vec2 microRoughness;    // mu: width of one microdetail's lobe, 0 < mu <= r
  float searchConeAngle;  // c: angular size of the searched cone of half vectors
  float variation;        // v: amplitude of the per-(cell, bin) count multiplier
  float dynamicRange;     // R: a cell's found / expected ratio is clamped to R p
  float logDensity;       // ln(rho_d), rho_d = microdetails per unit (compressed) uv area; a log so
                          // that our density range (up to e^100) stays a float
  float maxAnisotropy;    // K_a: cell size >= the footprint's long extent / K_a (16 in the reference)
  uint patternSeed;       // selects another pattern (not in the reference, which has one)
};

GLINT_FN vec2 glintZirrKaplanyanMesoRoughness(vec2 roughness, vec2 microRoughness) {
  // Gaussian widths add in quadrature: microdetail orientations spread by rho (spec 1.2, 3 step 2).
  return sqrt(max(roughness * roughness - microRoughness * microRoughness, glintSplat2(GLINT_ZIRR_KAPLANYAN_MIN_MESO_VARIANCE)));
}

// Our parameters to the model's (spec 4.2). What does not correspond:
//   - relativeArea (MRA) has no counterpart: ZK cells are never empty by a mask; match with
//     MRA = 1, or multiply ZK's output by MRA to match the mean energy only;
//   - densityRandomisation (zeta) has no counterpart: the variation v is set to 0, which makes the
//     mean exactly the smooth BRDF (ZK's 1 + v erfinv(.) multiplier is another, heavy-tailed law);
//   - colouredCells is not modelled;
//   - the search cone is 0: Chermain evaluates the exact half vector of a point light;
//   - the masking term stays ZK's GGX-form Smith G (Chermain: V-cavity).
// The spec's output scale (x 4) is applied by glintZirrKaplanyanReflectance, not here.
GLINT_FN GlintZirrKaplanyanParameters glintZirrKaplanyanFromGlint(GlintParameters glint) {
  GlintZirrKaplanyanParameters zk;
  zk.roughness = glint.alpha;  // the same Beckmann convention (spec 4.2: exact)
  zk.microRoughness = GLINT_ZIRR_KAPLANYAN_MICRO_ROUGHNESS_PER_ALPHA * glint.alpha;
  // ZK counts per unit compressed uv area: a cell of side h covers h^2 / (gamma_x gamma_y) of uv.
  vec2 meso = glintZirrKaplanyanMesoRoughness(zk.roughness, zk.microRoughness);
  zk.logDensity = glint.logDensity + log(max(meso.x / meso.y, meso.y / meso.x));
  zk.searchConeAngle = 0.0f;
  zk.variation = 0.0f;
  zk.dynamicRange = GLINT_ZIRR_KAPLANYAN_MAPPED_DYNAMIC_RANGE;
  zk.maxAnisotropy = glint.maxAnisotropy;  // the same cap in both methods (spec 4.2)
  zk.patternSeed = glint.patternSeed;
  return zk;
}

// The coherent multilevel index (spec 1.5, 3 step 7): trailing zero bits removed, so cell i at
// level l + 1 has the id of its first child 2i at level l. Arithmetic shift, so negative indices
// keep the property (-1 at level l + 1 and -2 at level l); 0 stays 0.
GLINT_FN int glintZirrKaplanyanCoherentIndex(int i) {
  if (i == 0) {
    return 0;
  }
  return i >> glintFindLSB(uint(i));
}

// A grid coordinate (an integral float) as an int, clamped into int's range first (float to int
// is undefined outside it).
GLINT_FN int glintZirrKaplanyanCellIndex(float i) {
  return int(clamp(i, -2147483520.0f, 2147483520.0f));
}

// ln(1 - q) without the cancellation of 1 - q in float (the series to q^4 below 0.01, relative
// error under 2e-9): the binomial's P(0) = (1 - q)^N for N in the millions and q near 1e-7 would
// otherwise be 1 and lose the count.
GLINT_FN float glintZirrKaplanyanLogOneMinus(float q) {
  if (q < 0.01f) {
    return -q * (1.0f + q * (0.5f + q * (0.33333333f + q * 0.25f)));
  }
  return log(1.0f - q);
}

// The binomial count (spec 3.9, APPROX_BINOMIAL), split into its set-up, which depends on n and p
// only, and the draw at u: with v = 0 every cell of a grid level has the same n and p, so the
// tuned schedule sets the law up once per level (glintZirrKaplanyanLevel) and draws per cell.
GLINT_CONST int GLINT_ZIRR_KAPLANYAN_COUNT_IS_CONSTANT = 0;  // the count is `trials`: 0 (no trial, p <= P_MIN) or n (p >= 1)
GLINT_CONST int GLINT_ZIRR_KAPLANYAN_COUNT_IS_NORMAL = 1;    // n p above GLINT_ZIRR_KAPLANYAN_GAUSSIAN_THRESHOLD
GLINT_CONST int GLINT_ZIRR_KAPLANYAN_COUNT_IS_SCANNED = 2;   // the inverse CDF scanned, then the geometric tail

struct GlintZirrKaplanyanBinomialLaw {
  int kind;           // kZirrKaplanyanCountIs...
  float trials;       // constant: the count; normal: n, the clamp; scanned: n' = ceil(n)
  float mean;         // normal: n p
  float spread;       // normal: sqrt(n p (1 - p))
  float pmfLo;        // scanned: P(0) at the lower quantised probability p_lo, and its odds p_lo / (1 - p_lo)
  float oddsLo;
  float pmfHi;        // scanned: the same at p_hi (0 when p_hi = 1)
  float oddsHi;
  bool hiIsOne;       // scanned: p_hi = 1, every trial succeeds
  float interpolation;  // scanned: where p' lies between p_hi and p_lo, in powers of 0.9
  float log2P;        // scanned: log2 p', the geometric tail's ratio
  float tailMass;     // scanned: 1 - p'^(n' - 18), 1 / C of the spec
};

// The law of Binomial(n, p) as the draw below uses it; n need not be an integer.
GLINT_FN GlintZirrKaplanyanBinomialLaw glintZirrKaplanyanBinomialLaw(float n, float p) {
  GlintZirrKaplanyanBinomialLaw law;
  law.kind = GLINT_ZIRR_KAPLANYAN_COUNT_IS_CONSTANT;
  law.trials = 0.0f;
  law.mean = 0.0f;
  law.spread = 0.0f;
  law.pmfLo = 0.0f;
  law.oddsLo = 0.0f;
  law.pmfHi = 0.0f;
  law.oddsHi = 0.0f;
  law.hiIsOne = false;
  law.interpolation = 0.0f;
  law.log2P = 0.0f;
  law.tailMass = 0.0f;
  if (!(n > 0.0f)) {
    return law;
  }
  float mean = n * p;
  if (mean > GLINT_ZIRR_KAPLANYAN_GAUSSIAN_THRESHOLD) {
    law.kind = GLINT_ZIRR_KAPLANYAN_COUNT_IS_NORMAL;
    law.trials = n;
    law.mean = mean;
    law.spread = sqrt(mean * max(1.0f - p, 0.0f));
    return law;
  }
  if (p >= 1.0f) {
    law.trials = n;
    return law;
  }
  if (p <= GLINT_ZIRR_KAPLANYAN_MIN_PROBABILITY) {
    return law;
  }
  // An integer number of trials with the same mean, and p quantised to the powers of 0.9 on either
  // side (p_lo < p' <= p_hi): the two counts are interpolated like mip levels, so the result is
  // continuous in p (temporal stability).
  float trials = ceil(n);
  float pTrial = p * n / trials;
  if (pTrial <= GLINT_ZIRR_KAPLANYAN_MIN_PROBABILITY) {  // guard: p n / n' can underflow where p did not
    return law;
  }
  float t = log2(pTrial) / GLINT_ZIRR_KAPLANYAN_LOG2_QUANTISATION_BASE;
  float tFloor = floor(t);
  float pHi = exp2(tFloor * GLINT_ZIRR_KAPLANYAN_LOG2_QUANTISATION_BASE);
  float pLo = 0.9f * pHi;
  law.kind = GLINT_ZIRR_KAPLANYAN_COUNT_IS_SCANNED;
  law.trials = trials;
  law.hiIsOne = tFloor <= 0.0f;  // q = 1: every trial succeeds, the count is n'
  law.pmfLo = exp(trials * glintZirrKaplanyanLogOneMinus(pLo));
  law.pmfHi = law.hiIsOne ? 0.0f : exp(trials * glintZirrKaplanyanLogOneMinus(pHi));
  law.oddsLo = pLo / (1.0f - pLo);
  law.oddsHi = law.hiIsOne ? 0.0f : pHi / (1.0f - pHi);
  law.interpolation = t - tFloor;
  law.log2P = log2(pTrial);
  law.tailMass = 1.0f - exp2((trials - float(GLINT_ZIRR_KAPLANYAN_BINOMIAL_SCAN)) * law.log2P);
  return law;
}

// The number of microdetails of a cell that reflect into the eye: an inverse-CDF draw at u of the
// law, continuous in p (spec 3.9). scanLength: the counts scanned before the tail. The reference
// scans GLINT_ZIRR_KAPLANYAN_BINOMIAL_SCAN whatever n' (a constant trip count, which llvmpipe unrolls and
// runs on every lane); glintZirrKaplanyanScanLength gives the same counts with a trip count of its own.
GLINT_FN float glintZirrKaplanyanBinomialDraw(GlintZirrKaplanyanBinomialLaw law, float u, int scanLength) {
  if (law.kind == GLINT_ZIRR_KAPLANYAN_COUNT_IS_NORMAL) {
    // Normal approximation; erfinv(2u - 1) has std 1/sqrt(2), so this normal is sqrt(2) narrower
    // than the binomial (spec 3.9, kept for fidelity).
    float k = law.mean + glintErfinvApprox(-GLINT_ZIRR_KAPLANYAN_GAUSSIAN_CLAMP + 2.0f * GLINT_ZIRR_KAPLANYAN_GAUSSIAN_CLAMP * u) *
                             law.spread;
    return clamp(k, 0.0f, law.trials);
  }
  if (law.kind == GLINT_ZIRR_KAPLANYAN_COUNT_IS_CONSTANT) {
    return law.trials;
  }
  float trials = law.trials;
  float pmfLo = law.pmfLo;
  float pmfHi = law.pmfHi;
  float cdfLo = pmfLo;
  float cdfHi = pmfHi;
  float countLo = trials;
  float countHi = trials;
  bool foundLo = false;
  bool foundHi = false;
  for (int i = 0; i < scanLength; ++i) {
    if (!foundLo && u < cdfLo) {
      countLo = float(i);
      foundLo = true;
    }
    if (u < cdfHi) {  // the larger p has the smaller CDF: the other count is found already
      countHi = float(i);
      foundHi = true;
      break;
    }
    if (i == GLINT_ZIRR_KAPLANYAN_BINOMIAL_SCAN - 1) {
      break;  // the tail below starts from CDF(17)
    }
    float step = (trials - float(i)) / float(i + 1);
    pmfLo = pmfLo * step * law.oddsLo;
    pmfHi = pmfHi * step * law.oddsHi;
    cdfLo += pmfLo;
    cdfHi += pmfHi;
  }
  // Beyond 17 successes: the inverse CDF of a geometric tail with ratio p' truncated at n'
  // (reaching n' at U = 1), where U is u renormalised to the remaining mass. For n' <= 18 the scan
  // covered every count and only rounding is left: n'.
  bool hasTail = trials > float(GLINT_ZIRR_KAPLANYAN_BINOMIAL_SCAN);
  if (!foundLo) {
    float tailU = (u - cdfLo) / (1.0f - cdfLo);
    float tail = float(GLINT_ZIRR_KAPLANYAN_BINOMIAL_SCAN) + log2(max(1.0f - tailU * law.tailMass, 1e-30f)) / law.log2P;
    countLo = hasTail ? min(trials, tail) : trials;
  }
  if (!foundHi) {
    float tailU = (u - cdfHi) / (1.0f - cdfHi);
    float tail = float(GLINT_ZIRR_KAPLANYAN_BINOMIAL_SCAN) + log2(max(1.0f - tailU * law.tailMass, 1e-30f)) / law.log2P;
    countHi = (hasTail && !law.hiIsOne) ? min(trials, tail) : trials;
  }
  return countHi + (countLo - countHi) * law.interpolation;
}

// How many counts the scan must visit for the law to draw what the reference's 18 draw: 0..n' - 1
// when n' < 18 (the reference goes on, but past n' the pmf is exactly 0, so the CDF and whether u
// is below it no longer change; a u found by none of 0..n' - 1 has the count n' either way), else
// the reference's 18. A trip count the compiler cannot fold into a constant, so that llvmpipe does
// not unroll the loop for every lane but runs it only as long as one of its lanes is still scanning.
GLINT_FN int glintZirrKaplanyanScanLength(GlintZirrKaplanyanBinomialLaw law) {
  return int(min(law.trials, float(GLINT_ZIRR_KAPLANYAN_BINOMIAL_SCAN)));
}

// The reference's binomial draw in one call (set-up and draw at u, the full scan): the unit the
// tests check.
GLINT_FN float glintZirrKaplanyanBinomial(float u, float n, float p) {
  return glintZirrKaplanyanBinomialDraw(glintZirrKaplanyanBinomialLaw(n, p), u, GLINT_ZIRR_KAPLANYAN_BINOMIAL_SCAN);
}

// Smith's masking in GGX form with a^2 = r_x r_y, as the reference writes it (spec 3 step 4):
// G_X = |n.X| + sqrt(|n.X|^2 (1 - a^2) + a^2) = 2 |n.X| / G1_GGX(X).
GLINT_FN float glintZirrKaplanyanSmithDenominator(float cosTheta, float a2) {
  float c = abs(cosTheta);
  return c + sqrt(c * c * (1.0f - a2) + a2);
}

// What every cell of a pixel shares (spec 3 steps 3-4).
struct GlintZirrKaplanyanPixel {
  vec2 binCoordinate;  // e = q / (mu + c): the half vector in bin units
  float probability;   // p: the chance that one microdetail reflects into the eye
  float brdfScale;     // K = Lambda / (4 pi mu_x mu_y): pmf to BRDF
};

// E0 = rho_d h^2 (spec 3 step 7.5): the microdetails a cell of size h = 2^level expects, in logs.
GLINT_FN float glintZirrKaplanyanExpectedBase(float level, GlintZirrKaplanyanParameters params) {
  return exp(min(params.logDensity + 1.38629436f * level, GLINT_ZIRR_KAPLANYAN_MAX_LOG_COUNT));
}

// The binomial's trials for a cell expecting E0 m microdetails: at least one where E0 >= 1 (step 7.5).
GLINT_FN float glintZirrKaplanyanTrials(float expected, float expectedBase) {
  return max(expected, min(1.0f, expectedBase));
}

// What every cell of a grid level shares. The reference computes all of it per cell; the tuned
// schedule once per level: E0, and with v = 0 the count's law too, since the count multiplier
// 1 + 0 erfinv(.) is then exactly 1 and every cell of the level expects E0 and draws from the same
// Binomial(E0, p) at its own u.
struct GlintZirrKaplanyanLevel {
  float level;          // log2 of the cell size
  float expectedBase;   // E0 (tuned schedule only)
  bool sharesLaw;       // tuned schedule and v = 0: every cell expects E0 and draws from `law`
  GlintZirrKaplanyanBinomialLaw law;
};

GLINT_FN GlintZirrKaplanyanLevel glintZirrKaplanyanLevel(float level, GlintZirrKaplanyanPixel pixel, GlintZirrKaplanyanParameters params,
                                               bool asReference) {
  GlintZirrKaplanyanLevel setup;
  setup.level = level;
  setup.expectedBase = asReference ? 0.0f : glintZirrKaplanyanExpectedBase(level, params);
  setup.sharesLaw = !asReference && params.variation == 0.0f;
  setup.law = glintZirrKaplanyanBinomialLaw(
      setup.sharesLaw ? glintZirrKaplanyanTrials(setup.expectedBase, setup.expectedBase) : 0.0f, pixel.probability);
  return setup;
}

// The value of one cell (spec 3 steps 7-8): the found / expected microdetail ratio, clamped to
// R p, times K. (iu, iv) are the cell's integer grid coordinates at the level's cell size.
GLINT_FN float glintZirrKaplanyanCell(int iu, int iv, GlintZirrKaplanyanLevel setup, GlintZirrKaplanyanPixel pixel,
                                 GlintZirrKaplanyanParameters params, bool asReference) {
  // Coherent ids and the pattern seed, hashed by a bijection: the cell's bin-grid jitter from two
  // lanes, a 64-bit cell key from the other two.
  uvec4 cellHash = glintPcg4d(uvec4(uint(glintZirrKaplanyanCoherentIndex(iu)), uint(glintZirrKaplanyanCoherentIndex(iv)),
                               params.patternSeed, 0u));
  vec2 jitter = vec2(glintHashToUnitOpen(cellHash.x), glintHashToUnitOpen(cellHash.y));
  // The half-vector bin, on a grid jittered per cell (spec 3 step 7.3).
  vec2 binFloor = floor(pixel.binCoordinate + jitter);
  uvec4 binHash = glintPcg4d(uvec4(uint(glintZirrKaplanyanCellIndex(binFloor.x)), uint(glintZirrKaplanyanCellIndex(binFloor.y)),
                              cellHash.z, cellHash.w));
  float expected = setup.expectedBase;
  GlintZirrKaplanyanBinomialLaw law = setup.law;
  if (!setup.sharesLaw) {
    // Count multiplier ("randomize glint sizes"), negative values folded into (0, 1) (step 7.4).
    float multiplier = 1.0f + params.variation * glintErfinvApprox(-GLINT_ZIRR_KAPLANYAN_VARIATION_CLAMP +
                                                              2.0f * GLINT_ZIRR_KAPLANYAN_VARIATION_CLAMP * glintHashToUnitOpen(binHash.x));
    if (multiplier <= 0.0f) {
      multiplier = glintFract(multiplier) / (1.0f - multiplier);
    }
    multiplier = max(multiplier, GLINT_ZIRR_KAPLANYAN_MIN_MULTIPLIER);
    float expectedBase = asReference ? glintZirrKaplanyanExpectedBase(setup.level, params) : setup.expectedBase;
    expected = expectedBase * multiplier;
    law = glintZirrKaplanyanBinomialLaw(glintZirrKaplanyanTrials(expected, expectedBase), pixel.probability);
  }
  if (expected < GLINT_ZIRR_KAPLANYAN_MIN_EXPECTED_COUNT) {
    return 0.0f;
  }
  float found = glintZirrKaplanyanBinomialDraw(law, glintHashToUnitOpen(binHash.y),
                                          asReference ? GLINT_ZIRR_KAPLANYAN_BINOMIAL_SCAN : glintZirrKaplanyanScanLength(law));
  return min(found / expected, params.dynamicRange * pixel.probability) * pixel.brdfScale;
}

// Whether every cell's count is certainly 0, so that the walk would only sum zeros: the tuned
// schedule's early exit, the counterpart of the glint renderer's negligible-slope exit but exact.
// Below p = P_MIN a scanned count is 0 (glintZirrKaplanyanBinomialLaw), and the only other branch, the
// normal one, needs n p > 5, while n is at most max(E0 m, 1) with E0 <= e^69 < 1e30 and the
// multiplier m <= 1 + v erfinv(0.999) = 1 + 2.33 v (3 v: a margin for rounding).
GLINT_FN bool glintZirrKaplanyanNoCellReflects(float probability, GlintZirrKaplanyanParameters params) {
  return probability <= GLINT_ZIRR_KAPLANYAN_MIN_PROBABILITY &&
         probability * (1e30f * (1.0f + 3.0f * params.variation)) <= GLINT_ZIRR_KAPLANYAN_GAUSSIAN_THRESHOLD;
}

// The reference's glints(): ZK16 for one pixel footprint and one directional light (spec 3),
// without the output scale (a quarter of Cook-Torrance's f on average). uv and its screen-space
// derivatives (the columns of J), wo and wi in the local frame (z = normal, x = +u). cellVisits:
// the cells visited, both levels together (at most GLINT_ZIRR_KAPLANYAN_MAX_CELL_VISITS).
//
// asReference: the schedule of the reference shader (every cell sets up its own E0 and binomial
// law, the binomial scan has the constant trip count 18, no early exit), kept to measure against.
// Otherwise the tuned schedule (docs/zirr-kaplanyan.md, "Cost"): the same arithmetic on the same
// values in the same order wherever a value is used, so the result is bit for bit the same
// (ZirrKaplanyan.TunedScheduleIsBitIdenticalToTheReference), with per-level set-up, scan bounds
// of their own and the early exit where no cell can reflect.
GLINT_FN float glintZirrKaplanyanGlintsScheduled(vec2 uv, vec2 duvdx, vec2 duvdy, vec3 wo, vec3 wi,
                                            GlintZirrKaplanyanParameters params, bool asReference,
                                            GLINT_OUT(int) cellVisits) {
  cellVisits = 0;
  // Step 0: gating.
  if (wo.z <= 0.0f || wi.z <= 0.0f) {
    return 0.0f;
  }
  vec2 r = params.roughness;
  vec2 mu = params.microRoughness;
  // Step 2: material anisotropy gamma compresses uv and the bin grid along the smoother meso axis.
  vec2 meso = glintZirrKaplanyanMesoRoughness(r, mu);
  vec2 gamma = vec2(min(meso.x / meso.y, 1.0f), min(meso.y / meso.x, 1.0f));

  // Step 3: half vector and its stereographic bin coordinates.
  vec3 h = normalize(wo + wi);
  GlintZirrKaplanyanPixel pixel;
  pixel.binCoordinate = GLINT_ZIRR_KAPLANYAN_STEREOGRAPHIC_SCALE * vec2(h.x, h.y) / (1.0f + h.z) * gamma /
                        (mu + glintSplat2(params.searchConeAngle));
  // Step 4: p0 = pi mu_x mu_y D_Beckmann(h; r); the masking Lambda = G1 G1 / (4 n.l n.v);
  // K = Lambda / (4 pi mu_x mu_y); the search cone flattens p (phenomenological, no pi).
  // (Below h.z = 1e-6 the slope exceeds 1e6 and D is exactly 0 in float; the guard avoids 0 / 0.)
  float p0 = h.z > 1e-6f ? GLINT_PI * mu.x * mu.y * glintNdfFromP22(glintBeckmannP22(glintSlopeFromNormal(h), r, 0.0f), h.z) : 0.0f;
  float a2 = r.x * r.y;
  float lambda = 1.0f / (glintZirrKaplanyanSmithDenominator(wi.z, a2) * glintZirrKaplanyanSmithDenominator(wo.z, a2));
  pixel.brdfScale = lambda / (4.0f * GLINT_PI * mu.x * mu.y);
  float cosLightHalf = 0.5f * (dot(wi, h) + dot(wo, h));
  float cone = params.searchConeAngle > 0.0f
                   ? params.searchConeAngle * params.searchConeAngle / (4.0f * cosLightHalf * h.z)
                   : 0.0f;
  pixel.probability = min(p0 + (1.0f - p0) * clamp(cone, 0.0f, 1.0f), 1.0f);
  if (!asReference && glintZirrKaplanyanNoCellReflects(pixel.probability, params)) {
    return 0.0f;
  }

  // Step 1: M = J^-1 through the adjugate of J / s, s its largest entry (det cancels in the skew
  // and stays out of uvPP's division; the scale keeps det finite for any finite footprint):
  // det M e_u ~ (duvdy.y, -duvdx.y), det M e_v ~ (-duvdy.x, duvdx.x).
  vec2 extent = max(abs(duvdx), abs(duvdy));
  float scale = max(max(extent.x, extent.y), 1e-30f);
  vec2 jx = duvdx / scale;
  vec2 jy = duvdy / scale;
  float det = jx.x * jy.y - jy.x * jx.y;
  vec2 adjU = vec2(jy.y, -jx.y);
  vec2 adjV = vec2(-jy.x, jx.x);
  // uv distance along u (v) that moves one pixel in the L-infinity pixel norm.
  float uvPerPixelU = scale * (abs(det) / max(max(abs(adjU.x), abs(adjU.y)), 1e-30f));
  float uvPerPixelV = scale * (abs(det) / max(max(abs(adjV.x), abs(adjV.y)), 1e-30f));

  // Step 5: compressed noise coordinates (no +100 offset: see the header), the footprint's
  // axis-aligned box, its long axis L and short axis S.
  vec2 y = uv * gamma;
  vec2 box = extent * gamma;
  bool longIsU = box.x > box.y;
  float yL = longIsU ? y.x : y.y;
  float yS = longIsU ? y.y : y.x;
  float boxL = longIsU ? box.x : box.y;
  float gammaL = longIsU ? gamma.x : gamma.y;
  float gammaS = longIsU ? gamma.y : gamma.x;
  // Skew: rows follow the uv line along which pixel coordinate k stays constant, k being the pixel
  // axis that moves most along S.
  vec2 adjL = longIsU ? adjU : adjV;
  vec2 adjS = longIsU ? adjV : adjU;
  bool kIsX = abs(adjS.x) > abs(adjS.y);
  float adjLk = kIsX ? adjL.x : adjL.y;
  float adjSk = kIsX ? adjS.x : adjS.y;
  float skew = adjSk != 0.0f ? -(adjLk / adjSk) * (gammaS / gammaL) : 0.0f;
  // Base cell size: the short axis' uv per pixel, at least the long extent / K_a.
  float cellSize = max(longIsU ? uvPerPixelV : uvPerPixelU, boxL / params.maxAnisotropy);
  float lod = clamp(log2(cellSize), GLINT_ZIRR_KAPLANYAN_MIN_LEVEL, GLINT_ZIRR_KAPLANYAN_MAX_LEVEL);
  float level0 = floor(lod);

  // Step 6: two grid levels, blended linearly in log2(cell size).
  float result = 0.0f;
  for (int j = 0; j < 2; ++j) {
    float level = level0 + float(j);
    float hCell = glintLdexp(1.0f, int(level));
    float levelWeight = 1.0f - abs(level - lod);
    GlintZirrKaplanyanLevel levelSetup = glintZirrKaplanyanLevel(level, pixel, params, asReference);
    // Range of cell corners: the box shrunk by half a cell, never past its centre.
    float loL = min(yL - 0.5f * boxL + 0.5f * hCell, yL);
    float hiL = max(yL + 0.5f * boxL - 0.5f * hCell, yL);
    float startL = floor(loL / hCell);
    float extentL = hiL + hCell - startL * hCell;
    float weightSum = 0.0f;
    float valueSum = 0.0f;
    for (int t = 0; t < GLINT_ZIRR_KAPLANYAN_MAX_ROWS; ++t) {
      if (!(float(t) * hCell < extentL) || cellVisits >= GLINT_ZIRR_KAPLANYAN_MAX_CELL_VISITS) {
        break;
      }
      float indexL = startL + float(t);
      float zL = indexL * hCell;
      // Linear ramps one cell beyond each end of the corner range.
      float weightL = max(1.0f - max((loL - zL) / hCell, 0.0f), 0.0f) *
                      max(1.0f - max((zL - hiL) / hCell, 0.0f), 0.0f);
      float rowCentre = yS + skew * (zL - yL);
      float indexS = floor(rowCentre / hCell);
      for (int k = 0; k < GLINT_ZIRR_KAPLANYAN_MAX_CELLS_PER_ROW; ++k) {
        if (!(indexS * hCell < rowCentre + hCell) || cellVisits >= GLINT_ZIRR_KAPLANYAN_MAX_CELL_VISITS) {
          break;
        }
        // A tent of half-width h on the row centre: linear interpolation between two cells.
        float weight = weightL * max(1.0f - abs(indexS * hCell - rowCentre) / hCell, 0.0f);
        if (weight > 0.0f) {
          int iL = glintZirrKaplanyanCellIndex(indexL);
          int iS = glintZirrKaplanyanCellIndex(indexS);
          weightSum += weight;
          valueSum += weight * glintZirrKaplanyanCell(longIsU ? iL : iS, longIsU ? iS : iL, levelSetup, pixel, params,
                                                 asReference);
        }
        indexS += 1.0f;
        cellVisits += 1;
      }
    }
    // The guard the reference keeps under DEBUG (spec 3 step 6.5).
    result += levelWeight * (weightSum > 0.0f ? valueSum / weightSum : 0.0f);
  }
  return result;
}

// The tuned schedule: the CPU BSDF's and the renderer's `zirr-kaplanyan`.
GLINT_FN float glintZirrKaplanyanGlintsCounted(vec2 uv, vec2 duvdx, vec2 duvdy, vec3 wo, vec3 wi,
                                          GlintZirrKaplanyanParameters params, GLINT_OUT(int) cellVisits) {
  return glintZirrKaplanyanGlintsScheduled(uv, duvdx, duvdy, wo, wi, params, false, cellVisits);
}

GLINT_FN float glintZirrKaplanyanGlints(vec2 uv, vec2 duvdx, vec2 duvdy, vec3 wo, vec3 wi, GlintZirrKaplanyanParameters params) {
  int cellVisits;
  return glintZirrKaplanyanGlintsCounted(uv, duvdx, duvdy, wo, wi, params, cellVisits);
}

// The ZK16 BRDF without Fresnel (F = 1) and without the cosine, comparable to glintReflectance:
// the renderer's entry point (uv and its dFdx/dFdy, wo and wi in the local frame).
GLINT_FN float glintZirrKaplanyanReflectance(vec2 uv, vec2 duvdx, vec2 duvdy, vec3 wo, vec3 wi,
                                        GlintZirrKaplanyanParameters params) {
  return GLINT_ZIRR_KAPLANYAN_OUTPUT_SCALE * glintZirrKaplanyanGlints(uv, duvdx, duvdy, wo, wi, params);
}

// The same value on the reference shader's schedule: the renderer's `zirr-kaplanyan-reference`,
// timed by `glint bench` next to the tuned one.
GLINT_FN float glintZirrKaplanyanReferenceReflectance(vec2 uv, vec2 duvdx, vec2 duvdy, vec3 wo, vec3 wi,
                                                 GlintZirrKaplanyanParameters params) {
  int cellVisits;
  return GLINT_ZIRR_KAPLANYAN_OUTPUT_SCALE * glintZirrKaplanyanGlintsScheduled(uv, duvdx, duvdy, wo, wi, params, true, cellVisits);
}

GLINT_KERNEL_END

#endif
