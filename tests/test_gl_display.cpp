// The display pass (gl/display.h) against the CPU's displayEncode: the same transform, pixel for
// pixel in place (not flipped or shifted, the dither laid out alike), apart from values the two
// languages' pow put on different sides of a rounding boundary.
#include <cmath>
#include <cstdlib>

#include <gtest/gtest.h>

#include "gl/display.h"
#include "gl_support.h"
#include "glint/kernel/tonemap.h"

namespace glint {
namespace {

TEST(DisplayGl, EncodesAsTheCpuDoes) {
  test::useGlContext();
  // A ramp over 0..8 in x, different per channel and per row (up to 0.5 more towards the bottom),
  // with black, negative and very bright pixels: an image no flip or shift maps onto itself.
  const int width = 193;
  const int height = 61;
  ImageRgbF radiance = ImageRgbF::filled(width, height);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const float t = 8.0f * x / (width - 1) + 0.5f * y / (height - 1);
      radiance.at(x, y) = {t, 0.5f * t * t, x % 7 == 0 ? -1.0f : (y % 5 == 0 ? 1e6f : 0.1f * t)};
    }
  }
  for (const float exposure : {1.0f, 0.3f}) {
    const ImageRgb8 gpu = gl::DisplayPass().encode(radiance, exposure);
    const ImageRgb8 cpu = displayEncode(radiance, exposure);
    ASSERT_EQ(gpu.width(), width);
    ASSERT_EQ(gpu.height(), height);
    int differing = 0;
    for (int y = 0; y < height; ++y) {
      for (int x = 0; x < width; ++x) {
        const Rgb8 g = gpu.at(x, y);
        const Rgb8 c = cpu.at(x, y);
        const glm::vec3 exact = kernel::glintDisplayEncode(radiance.at(x, y), exposure) * 255.0f;
        const int gc[3] = {g.r, g.g, g.b};
        const int cc[3] = {c.r, c.g, c.b};
        for (int k = 0; k < 3; ++k) {
          if (gc[k] == cc[k]) continue;
          ++differing;
          // Only by a level, and only where the CPU's value lies within 1e-3 of its pixel's rounding
          // boundary (a whole code less the dither's threshold).
          EXPECT_EQ(std::abs(gc[k] - cc[k]), 1) << x << ", " << y << " channel " << k;
          const float dithered = exact[k] + kernel::glintOrderedDitherThreshold(glm::ivec2(x, y));
          EXPECT_LT(std::abs(dithered - std::round(dithered)), 1e-3f) << x << ", " << y << " channel " << k;
        }
      }
    }
    EXPECT_LT(differing, width * height * 3 / 1000) << "exposure " << exposure;
  }
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}

}  // namespace
}  // namespace glint
