// Checks the two images of examples/path_tracer that the install test renders
// (run_install_test.cmake): the glinty sphere (GLINT) and the same scene shaded with the smooth lobe
// the glint BRDF converges to (SMOOTH, --smooth). One line a check; exit status 1 at the first that
// fails.
//   glint_check_example_image GLINT.exr SMOOTH.exr
// With --against-render, compares an example's image of glint's built-in sphere (EXAMPLE, e.g.
// examples/opengl's) with `glint render sphere`'s (RENDER) of the same setup, pixel by pixel.
//   glint_check_example_image --against-render EXAMPLE.exr RENDER.exr
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "glint/error.h"
#include "glint/image_io.h"
#include "image_checks.h"

namespace {

using namespace glint::install_test;

struct Statistics {
  double sphereMean = 0.0;   // over a disc at the centre, well inside the sphere
  double sphereMax = 0.0;
  double backgroundMean = 0.0;  // over the four corners, sky only
};

// The sphere spans 70% of the frame's height, centred: a disc of 46% of the width is inside it;
// the corner squares, 1/16 of the width a side, are outside it.
Statistics measure(const glint::ImageRgbF& image, const std::string& name) {
  Statistics s;
  int sphereCount = 0, backgroundCount = 0;
  const int corner = std::max(1, image.width / 16);
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const glm::vec3 c = image.at(x, y);
      for (int channel = 0; channel < 3; ++channel) {
        if (!std::isfinite(c[channel]) || c[channel] < 0.0f) {
          throw glint::Error(name + ": pixel (" + std::to_string(x) + ", " + std::to_string(y) +
                             ") is negative or not finite");
        }
      }
      const float dx = (x + 0.5f) / image.width - 0.5f, dy = (y + 0.5f) / image.height - 0.5f;
      if (std::sqrt(dx * dx + dy * dy) < 0.23f) {
        s.sphereMean += luminance(c);
        s.sphereMax = std::max<double>(s.sphereMax, luminance(c));
        ++sphereCount;
      }
      const bool left = x < corner, right = x >= image.width - corner;
      const bool top = y < corner, bottom = y >= image.height - corner;
      if ((left || right) && (top || bottom)) {
        s.backgroundMean += luminance(c);
        ++backgroundCount;
      }
    }
  }
  s.sphereMean /= sphereCount;
  s.backgroundMean /= backgroundCount;
  return s;
}


// An example's image of glint's built-in sphere against `glint render sphere`'s. Both rasterise the
// same mesh with the same camera and shade it with the same kernel, light, sky and material, so
// they agree to float rounding (the shaders' arithmetic is ordered differently) wherever the
// example is right. The sky is uniform, so the sphere's pixels are those of the render that differ
// from its corner; the glints are the sphere's pixels over 4 times its median luminance (the same
// sphere shaded with the smooth lobe the glints average to peaks at 2.3 times it).
void compareWithRender(const glint::ImageRgbF& example, const glint::ImageRgbF& render) {
  require(example.width == render.width && example.height == render.height && render.width >= 64 &&
              render.height >= 64,
          "both images are the same size, at least 64x64 (" + std::to_string(example.width) + "x" +
              std::to_string(example.height) + " and " + std::to_string(render.width) + "x" +
              std::to_string(render.height) + ")");
  const glm::vec3 sky = render.at(0, 0);
  auto onSphere = [&](const glint::ImageRgbF& image, std::size_t i) {
    return glm::any(glm::greaterThan(glm::abs(image.pixels[i] - sky), glm::vec3(1e-6f)));
  };
  std::vector<float> sphereLuminance;
  std::size_t coverageDiffers = 0;
  double squaredError = 0.0, squaredValue = 0.0;
  for (std::size_t i = 0; i < render.pixels.size(); ++i) {
    if (onSphere(render, i) != onSphere(example, i)) ++coverageDiffers;
    if (!onSphere(render, i)) continue;
    const glm::vec3 e = example.pixels[i], r = render.pixels[i];
    squaredError += glm::dot(e - r, e - r);
    squaredValue += glm::dot(r, r);
    sphereLuminance.push_back(luminance(r));
  }
  require(sphereLuminance.size() > render.pixels.size() / 4,
          "the render shows the sphere over a quarter of the frame (" + std::to_string(sphereLuminance.size()) +
              " pixels)");
  // Coverage: the same triangles through the same matrix cover the same pixels.
  require(coverageDiffers * 1000 <= sphereLuminance.size(),
          "the sphere covers the same pixels in both, but for 0.1% of them (" + std::to_string(coverageDiffers) +
              " differ)");
  // Over the sphere: rounding moves a pixel by parts in a million; 1% leaves room for another
  // driver's fused multiply-adds and a glint whose cell flips at a threshold.
  const double relativeRmse = std::sqrt(squaredError / squaredValue);
  require(relativeRmse < 0.01, "the relative RMSE over the sphere's pixels " + number(relativeRmse) + " is under 1%");
  std::vector<float> sorted = sphereLuminance;
  std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
  const float glintThreshold = 4.0f * sorted[sorted.size() / 2];
  std::size_t glints = 0, agreeing = 0;
  for (std::size_t i = 0; i < render.pixels.size(); ++i) {
    const float r = luminance(render.pixels[i]);
    if (!onSphere(render, i) || r <= glintThreshold) continue;
    ++glints;
    if (std::abs(luminance(example.pixels[i]) - r) <= 0.02f * r) ++agreeing;
  }
  require(glints >= 20,
          "the render shows glints (" + std::to_string(glints) + " pixels over 4 times the sphere's median)");
  // Glint for glint: each of the render's glint pixels is within 2% in the example, but for 1%.
  require(agreeing * 100 >= glints * 99, std::to_string(agreeing) + " of the render's " + std::to_string(glints) +
                                             " glint pixels are within 2% in the example (99% needed)");
}

}  // namespace

int main(int argc, char** argv) {
  if (argc == 4 && std::string(argv[1]) == "--against-render") {
    try {
      compareWithRender(glint::readImage(argv[2]), glint::readImage(argv[3]));
    } catch (const glint::Error& e) {
      std::fprintf(stderr, "glint_check_example_image: %s\n", e.what());
      return 1;
    }
    return 0;
  }
  if (argc != 3) {
    std::fprintf(stderr,
                 "usage: glint_check_example_image GLINT.exr SMOOTH.exr\n"
                 "       glint_check_example_image --against-render EXAMPLE.exr RENDER.exr\n");
    return 2;
  }
  try {
    const glint::ImageRgbF glinty = glint::readImage(argv[1]);
    const glint::ImageRgbF smooth = glint::readImage(argv[2]);
    require(glinty.width >= 64 && glinty.height >= 64 && smooth.width == glinty.width && smooth.height == glinty.height,
            "both images are the same size, at least 64x64 (" + std::to_string(glinty.width) + "x" +
                std::to_string(glinty.height) + ")");
    const Statistics g = measure(glinty, argv[1]);
    const Statistics s = measure(smooth, argv[2]);
    // Lit by the light, both spheres are far brighter than the sky; without the light (no light
    // sample, no BSDF sample reaching it) a sphere reflecting the dim sky is darker than the sky.
    require(g.sphereMean > 5.0 * g.backgroundMean, "the glinty sphere's mean " + number(g.sphereMean) +
                                                       " is over 5 times the background's " + number(g.backgroundMean));
    require(s.sphereMean > 5.0 * s.backgroundMean, "the smooth sphere's mean " + number(s.sphereMean) +
                                                       " is over 5 times the background's " + number(s.backgroundMean));
    // Glints: a few microfacets of a pixel's footprint that reflect the light make it several times
    // brighter than the smooth highlight's peak; a BSDF that averaged them away would not.
    require(g.sphereMax > 4.0 * s.sphereMax, "the brightest glint " + number(g.sphereMax) +
                                                 " is over 4 times the smooth highlight's peak " + number(s.sphereMax));
    // The glint BRDF averages to the smooth one over many footprints (method.md, section 2.6), so the
    // sphere's mean reflected light is about the same: glints are light moved around, not added.
    require(std::abs(g.sphereMean / s.sphereMean - 1.0) < 0.15,
            "the glinty sphere's mean is within 15% of the smooth one's (ratio " + number(g.sphereMean / s.sphereMean) +
                ")");
  } catch (const glint::Error& e) {
    std::fprintf(stderr, "glint_check_example_image: %s\n", e.what());
    return 1;
  }
  return 0;
}
