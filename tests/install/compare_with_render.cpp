// Compares an example's image of glint's `sphere` scene with the rasteriser's (`glint render
// sphere ... -o RENDER.exr`), both linear EXR of the same size: the install test's check that a
// renderer built on the installed package (examples/vulkan) shades the glints as glint does
// (run_install_test.cmake). One line a check; exit status 1 at the first that fails.
//   glint_compare_with_render EXAMPLE.exr RENDER.exr
//
// The two differ by design in the geometry pass, not in the shading: the rasteriser draws the
// sphere as 128 x 64 quads, interpolates normals, tangents and uvs across each triangle and takes
// the uv derivatives as differences between neighbouring pixels (dFdx, dFdy); the example
// intersects the exact sphere and takes the derivatives from ray differentials. So a pixel's
// footprint differs slightly (the tessellation's facets show in the difference as a faint grid),
// and where a footprint straddles a cell boundary or a level of detail, a glint can change. The
// checks below are over the sphere's pixels (non-zero in either image) and are chosen to hold with
// those differences and to fail on a shading difference (a wrong dictionary, density, uv scale,
// footprint, frame, light or Fresnel), each measured with a margin (docs/integration.md, "Deferred
// shading").
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "glint/error.h"
#include "glint/image_io.h"
#include "image_checks.h"

namespace {

using namespace glint::install_test;

// Glint pixels: brighter than twice the median of their 5 x 5 neighbourhood (the smooth shading
// around them) by at least `floor`: single bright pixels that the diffuse term and the smooth
// highlight, which vary slowly across the sphere, do not make.
std::vector<bool> glintPixels(const std::vector<float>& l, int width, int height, float floor) {
  std::vector<bool> glint(l.size(), false);
  std::vector<float> window;
  for (int y = 2; y < height - 2; ++y) {
    for (int x = 2; x < width - 2; ++x) {
      window.clear();
      for (int dy = -2; dy <= 2; ++dy) {
        for (int dx = -2; dx <= 2; ++dx) window.push_back(l[(y + dy) * width + x + dx]);
      }
      std::nth_element(window.begin(), window.begin() + 12, window.end());
      const float centre = l[y * width + x];
      glint[y * width + x] = centre > 2.0f * window[12] && centre - window[12] > floor;
    }
  }
  return glint;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: glint_compare_with_render EXAMPLE.exr RENDER.exr\n");
    return 2;
  }
  try {
    const glint::ImageRgbF example = glint::readImage(argv[1]);
    const glint::ImageRgbF render = glint::readImage(argv[2]);
    require(example.width == render.width && example.height == render.height && example.width >= 64,
            "both images are the same size, at least 64 pixels wide");
    const int width = example.width, height = example.height;
    std::vector<float> a(example.pixels.size()), b(render.pixels.size());
    for (std::size_t i = 0; i < a.size(); ++i) a[i] = luminance(example.pixels[i]), b[i] = luminance(render.pixels[i]);

    int onBoth = 0, onExampleOnly = 0, onRenderOnly = 0;
    double sumA = 0.0, sumB = 0.0, squaredDifference = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i) {
      if (a[i] <= 0.0f && b[i] <= 0.0f) continue;
      onBoth += a[i] > 0.0f && b[i] > 0.0f;
      onExampleOnly += b[i] <= 0.0f;
      onRenderOnly += a[i] <= 0.0f;
      sumA += a[i];
      sumB += b[i];
      squaredDifference += double(a[i] - b[i]) * (a[i] - b[i]);
    }
    const int lit = onBoth + onExampleOnly + onRenderOnly;
    const double meanB = sumB / lit;
    const double relativeRmse = std::sqrt(squaredDifference / lit) / meanB;
    const float floor = static_cast<float>(0.25 * meanB);
    const std::vector<bool> glintsA = glintPixels(a, width, height, floor), glintsB = glintPixels(b, width, height, floor);
    int countA = 0, countB = 0, shared = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
      countA += glintsA[i];
      countB += glintsB[i];
      shared += glintsA[i] && glintsB[i];
    }
    // The camera: the same pixels see the sphere, but for a few on its silhouette, where the
    // tessellated outline lies inside the circle (measured: 10 of 22,651 at 256 x 256).
    require(onExampleOnly + onRenderOnly < lit / 100,
            "the same pixels see the sphere: " + std::to_string(onExampleOnly + onRenderOnly) + " of " +
                std::to_string(lit) + " differ, under 1%");
    // The light, the diffuse term and Fresnel: the sphere's mean radiance (measured 0.06% apart).
    // Glints move light around without adding any, so the mean alone cannot tell glints apart.
    require(std::abs(sumA / sumB - 1.0) < 0.02, "the sphere's mean luminance " + number(sumA / lit) +
                                                    " is within 2% of the render's " + number(meanB));
    // Per pixel: sqrt(mean (a - b)^2) / mean b over the sphere, measured 0.016. Another realisation
    // of the same statistics (pattern seed 1) measured 0.41; the smallest changes tried (log density
    // 13 -> 14, uv scale 4 -> 4.02, alpha 0.5 -> 0.45, density randomisation 2 -> 1) 0.18 to 0.35.
    require(relativeRmse < 0.05, "the relative RMSE over the sphere " + number(relativeRmse) + " is under 0.05");
    // The glints themselves, at the same pixels: measured 142 and 140 glint pixels, 138 of the
    // render's in the example too; the changes above share 0 to 65 of them.
    require(countA > 0.9 * countB && countA < 1.1 * countB,
            "the example has " + std::to_string(countA) + " glint pixels, within 10% of the render's " +
                std::to_string(countB));
    require(shared > 0.85 * countB, std::to_string(shared) + " of the render's " + std::to_string(countB) +
                                         " glint pixels are glint pixels of the example too, over 85%");
  } catch (const glint::Error& e) {
    std::fprintf(stderr, "glint_compare_with_render: %s\n", e.what());
    return 1;
  }
  return 0;
}
