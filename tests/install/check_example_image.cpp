// Checks the two images of examples/path_tracer that the install test renders
// (run_install_test.cmake): the glinty sphere (GLINT) and the same scene shaded with the smooth lobe
// the glint BRDF converges to (SMOOTH, --smooth). One line a check; exit status 1 at the first that
// fails.
//   glint_check_example_image GLINT.exr SMOOTH.exr
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "glint/error.h"
#include "glint/image_io.h"

namespace {

float luminance(glm::vec3 c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; }

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

void require(bool condition, const std::string& what) {
  std::printf("%s: %s\n", condition ? "ok" : "FAILED", what.c_str());
  if (!condition) throw glint::Error("check failed: " + what);
}

std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", value);
  return text;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: glint_check_example_image GLINT.exr SMOOTH.exr\n");
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
