// Shadertoy's Image pass, iChannel0 = Buffer A: a glittering sphere under a turning sun, shaded with
// the glint BRDF of Chermain et al. 2020 (glintReflectance) on a dark metallic base. Define
// GLINT_SHADERTOY_SMOOTH to see the smooth Beckmann lobe the glints converge to instead.
void mainImage(out vec4 fragColor, in vec2 fragCoord) {
  vec2 p = (2.0 * fragCoord - iResolution.xy) / iResolution.y;
  vec3 origin = vec3(0.0, 0.0, 3.0);
  vec3 ray = normalize(vec3(p * 0.36397, -1.0));  // a 40 degree vertical field of view
  float b = dot(origin, ray);
  float h = b * b - dot(origin, origin) + 1.0;      // the unit sphere at the origin
  vec3 n = normalize(origin + (-b - sqrt(max(h, 0.0))) * ray);

  // The glint uv (longitude, latitude) and its screen derivatives, taken in uniform control flow,
  // before the branch on the hit. Longitude's derivative is taken on two cuts and the smaller kept,
  // so that the seam behind the sphere does not make a huge footprint.
  float turn = 0.05 * iTime;
  float longitude = atan(n.x, n.z) * 0.15915494 + turn;
  vec2 uv = vec2(longitude, acos(clamp(n.y, -1.0, 1.0)) * 0.31830989) * 4.0;
  vec2 uvCut = vec2(fract(longitude + 0.5) * 4.0, uv.y);
  vec2 duvdx = dFdx(uv);
  vec2 duvdy = dFdy(uv);
  duvdx.x = abs(duvdx.x) < abs(dFdx(uvCut.x)) ? duvdx.x : dFdx(uvCut.x);
  duvdy.x = abs(duvdy.x) < abs(dFdy(uvCut.x)) ? duvdy.x : dFdy(uvCut.x);
  if (h <= 0.0) {
    fragColor = vec4(vec3(0.02, 0.025, 0.03) * (1.0 - 0.3 * length(p)), 1.0);
    return;
  }

  GlintParameters params;
  params.alpha = vec2(0.35);
  params.rho = 0.0;
  params.logDensity = 18.0;
  params.relativeArea = 0.8;
  params.densityRandomisation = 2.0;
  params.maxAnisotropy = 8.0;
  params.patternSeed = 0u;
  params.colouredCells = false;
  params.ndf = GLINT_NDF_BECKMANN;
  params.masking = GLINT_MASKING_VCAVITY;
  params.lod = GLINT_LOD_PAPER;
  params.multipleScattering = false;
  params.footprintPolicy.maxAnisotropy = 0.0;
  params.footprintPolicy.maxCells = 0.0;
  params.footprintPolicy.minBlend = 0.0;

  // The shading frame: the tangent along the longitude (+u), the bitangent completing it.
  vec3 t = normalize(cross(vec3(0.0, 1.0, 0.0), n) + vec3(1e-6, 0.0, 0.0));
  vec3 bt = cross(n, t);
  vec3 view = -ray;
  vec3 sun = normalize(vec3(cos(0.4 * iTime), 0.7, 0.6 + 0.5 * sin(0.4 * iTime)));
  vec3 wo = vec3(dot(view, t), dot(view, bt), max(dot(view, n), 1e-4));
  vec3 wi = vec3(dot(sun, t), dot(sun, bt), dot(sun, n));
#ifdef GLINT_SHADERTOY_SMOOTH
  float specular = glintTargetCookTorranceReflectance(params.ndf, params.masking, params.alpha, 0.0, wo, wi);
#else
  float specular = glintReflectance(glintShadertoyDictionary(), params, uv, duvdx, duvdy, wo, wi);
#endif
  vec3 f0 = vec3(0.95, 0.75, 0.45);
  vec3 fresnel = glintFresnelSchlick(f0, dot(wo, normalize(wo + wi)));
  vec3 base = vec3(0.05, 0.012, 0.01);
  vec3 radiance = (base / GLINT_PI + fresnel * specular) * max(wi.z, 0.0) * 3.0 + base * 0.3;
  fragColor = vec4(glintDisplayEncode(radiance, 1.0), 1.0);
}
