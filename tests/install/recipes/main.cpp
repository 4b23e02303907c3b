// Runs the C++ recipe of docs/integration.md ("Recipes"), which CMakeLists.txt copies from the
// document word for word into the build folder as integration_recipe.cpp: the glint BSDF at 4,096
// footprints of a floor seen 38 degrees from its normal, the light in the mirror direction. Checks
// that f is finite and non-negative; that the recipe's density glints (f's deviation over the
// footprints above half its mean, the brightest footprint over 3 times the mean); that the mean is
// within 15% of the smooth lobe's, which the glint BRDF averages to; and that every sample's pdf
// and f are pdf() and f() at its direction, taken back to world space through the frame the test
// gave (which fails if the recipe's frame is another). Prints the figures; exits 1 on a failed check.
//   glint_integration_recipe [DICTIONARY.gdict]   (without one: the dictionary made at start)
#include "integration_recipe.cpp"

#include <algorithm>
#include <cstdio>
#include <exception>

#include <glint/pcg.h>

int main(int argc, char** argv) try {
  const glint::Dictionary dictionary = loadGlintDictionary(argc > 1 ? argv[1] : "");
  glint::SurfaceFootprint footprint;
  footprint.duvdx = glm::vec2(2e-3f, 0.0f);
  footprint.duvdy = glm::vec2(0.4e-3f, 2e-3f);
  const float uvAreaPerPixel = std::abs(footprint.duvdx.x * footprint.duvdy.y - footprint.duvdx.y * footprint.duvdy.x);
  const glint::GlintParameters material = glintMaterial(uvAreaPerPixel);

  // A floor (normal +y, u along +x, glTF handedness -1: the bitangent is -cross(n, t) = +z).
  const glm::vec3 n(0.0f, 1.0f, 0.0f);
  const glm::vec4 tangent(1.0f, 0.0f, 0.0f, -1.0f);
  const glm::vec3 bitangent(0.0f, 0.0f, 1.0f);
  const glm::vec3 toViewer = glm::normalize(glm::vec3(0.5f, 1.0f, -0.6f));
  const glm::vec3 toLight = 2.0f * glm::dot(n, toViewer) * n - toViewer;  // the mirror direction
  const glm::vec3 wo(glm::dot(toViewer, glm::vec3(tangent)), glm::dot(toViewer, bitangent), glm::dot(toViewer, n));
  const glm::vec3 wi(glm::dot(toLight, glm::vec3(tangent)), glm::dot(toLight, bitangent), glm::dot(toLight, n));
  const float smooth = glint::CookTorranceBsdf(material.alpha, material.rho, glint::Fresnel::schlick(glint::Spectrum(0.04f)),
                                               glint::Spectrum(1.0f), glint::microfacetTarget(material))
                           .f(wo, wi).x;

  bool ok = true;
  auto check = [&ok](bool condition, const char* what) {
    if (!condition) {
      std::fprintf(stderr, "glint_integration_recipe: failed: %s\n", what);
      ok = false;
    }
  };
  glint::Pcg32 rng(7, 1);
  auto uniform = [&rng] { return static_cast<float>(rng.nextOpenUnit()); };
  constexpr int kSide = 64;
  double sum = 0.0, sumSquares = 0.0, brightest = 0.0;
  int dark = 0, drawn = 0, pdfsAgree = 0;
  for (int j = 0; j < kSide; ++j) {
    for (int i = 0; i < kSide; ++i) {
      footprint.uv = glm::vec2(0.25f + 0.013f * i, 0.5f + 0.011f * j);  // footprints apart: independent glints
      const GlintShading shading =
          shadeGlints(dictionary, material, n, tangent, toViewer, toLight, footprint, glm::vec3(uniform(), uniform(), uniform()));
      const float f = shading.f.x;
      check(std::isfinite(f) && f >= 0.0f, "f is finite and non-negative");
      check(std::isfinite(shading.lightPdf) && shading.lightPdf >= 0.0f, "pdf() is finite and non-negative");
      sum += f;
      sumSquares += double(f) * f;
      brightest = std::max(brightest, double(f));
      dark += f < 0.05f * smooth ? 1 : 0;
      if (shading.bounce && shading.bounce->wi.z > 0.0f) {
        ++drawn;
        const glint::BsdfSample& s = *shading.bounce;
        const glm::vec3 direction = s.wi.x * glm::vec3(tangent) + s.wi.y * bitangent + s.wi.z * n;
        const GlintShading back = shadeGlints(dictionary, material, n, tangent, toViewer, direction, footprint, glm::vec3(0.5f));
        const bool agree = std::abs(back.lightPdf - s.pdf) <= 1e-3f * s.pdf && std::abs(back.f.x - s.f.x) <= 1e-3f * s.f.x + 1e-6f &&
                           std::abs(s.weight.x - s.f.x * s.wi.z / s.pdf) <= 1e-3f * s.weight.x + 1e-6f;
        pdfsAgree += agree ? 1 : 0;
      }
    }
  }
  const int count = kSide * kSide;
  const double mean = sum / count;
  const double deviation = std::sqrt(std::max(0.0, sumSquares / count - mean * mean));
  std::printf("log density %.2f (100 microfacets in a footprint of %.2g glint uv)\n", material.logDensity, uvAreaPerPixel);
  std::printf("f at the mirror direction over %d footprints: mean %.4g, the smooth lobe's %.4g (ratio %.3f); "
              "deviation %.2f x the mean, brightest %.1f x the mean, %.1f%% under 5%% of the smooth lobe\n",
              count, mean, smooth, mean / smooth, deviation / mean, brightest / mean, 100.0 * dark / count);
  std::printf("samples: %d of %d drawn above the horizon, %d with pdf() and f() at their direction equal to theirs\n",
              drawn, count, pdfsAgree);
  check(mean > 0.85 * smooth && mean < 1.15 * smooth, "the mean over footprints is within 15% of the smooth lobe's");
  check(deviation > 0.5 * mean, "f varies from footprint to footprint by over half its mean (glints)");
  check(brightest > 3.0 * mean, "the brightest footprint is over 3 times the mean (glints)");
  check(drawn > count / 2, "most samples are drawn");
  check(pdfsAgree == drawn, "every sample's pdf is pdf() at its direction");
  return ok ? 0 : 1;
} catch (const std::exception& e) {
  std::fprintf(stderr, "glint_integration_recipe: %s\n", e.what());
  return 1;
}
