// Shadertoy's Buffer A: the dictionary, texel pair (p[k], p[k + 1]) of every distribution of every
// level, at index (level N + n) R + k, row after row of GLINT_SHADERTOY_ROW pixels (the Common tab's
// hook reads it so). Every frame: about 8 million Gaussian lobes, a millisecond on a GPU.
void mainImage(out vec4 fragColor, in vec2 fragCoord) {
  int index = int(fragCoord.y) * GLINT_SHADERTOY_ROW + int(fragCoord.x);
  int texels = GLINT_SHADERTOY_TEXELS;
  if (int(fragCoord.x) >= GLINT_SHADERTOY_ROW || index >= GLINT_SHADERTOY_LEVELS * GLINT_SHADERTOY_DISTRIBUTIONS * texels) {
    fragColor = vec4(0.0);
    return;
  }
  int k = index % texels;
  int distribution = (index / texels) % GLINT_SHADERTOY_DISTRIBUTIONS;
  int level = index / (texels * GLINT_SHADERTOY_DISTRIBUTIONS);
  float p0 = glintProceduralDictionaryTexel(level, distribution, k, texels, GLINT_SHADERTOY_ALPHA_D,
                                            GLINT_SHADERTOY_LOBE_STD, GLINT_SHADERTOY_SEED);
  float p1 = k + 1 < texels ? glintProceduralDictionaryTexel(level, distribution, k + 1, texels, GLINT_SHADERTOY_ALPHA_D,
                                                             GLINT_SHADERTOY_LOBE_STD, GLINT_SHADERTOY_SEED)
                            : 0.0;
  fragColor = vec4(p0, p1, 0.0, 1.0);
}
