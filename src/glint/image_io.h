// Linear float RGB images: reading PNG and EXR, writing EXR and sRGB PNG, GL readback conversion,
// error metrics and a false-colour difference picture (`glint diff`, docs/cli.md).
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "glint/decoder_checks.h"
#include "glint/image.h"

namespace glint {

// Linear RGB, row-major, top row first (as PNG and EXR store them).
struct ImageRgbF {
  int width = 0;
  int height = 0;
  std::vector<glm::vec3> pixels;

  static ImageRgbF filled(int width, int height, glm::vec3 value = glm::vec3(0.0f));
  glm::vec3& at(int x, int y) { return pixels[static_cast<std::size_t>(y) * width + x]; }
  const glm::vec3& at(int x, int y) const { return pixels[static_cast<std::size_t>(y) * width + x]; }
};

// The sRGB transfer functions (IEC 61966-2-1), exact piecewise forms; the only place they live.
// Decoding: encoded value in [0, 1] to linear. Encoding: linear to encoded, clamped to [0, 1]
// (NaN encodes as 0).
float srgbToLinear(float encoded);
float linearToSrgb(float linear);
// Linear to an 8-bit sRGB code value, rounded to nearest.
std::uint8_t linearToSrgb8(float linear);

// Reads a PNG (8 or 16 bit, grey, grey-alpha, RGB or RGBA; alpha ignored; values decoded from sRGB
// to linear) or an EXR (RGB(A) or one channel, half or float, stored linear values), chosen by the
// file's magic bytes, not its name. Throws Error with one line naming the file and the problem
// (missing, truncated or corrupt, unsupported format, zero size, more than kMaxImagePixels
// pixels, non-finite EXR pixels).
ImageRgbF readImage(const std::filesystem::path& path);
// readImage on bytes already read, `name` naming them in errors (the file's path for readImage).
// maxPixels lowers the pixel budget (the fuzz harness's, so that one input decodes in a second).
ImageRgbF decodeImage(std::span<const std::byte> bytes, const std::string& name,
                      std::uint64_t maxPixels = kMaxImagePixels);
// The EXR half of decodeImage alone, for readers that take only EXR (the authors' dictionary):
// bytes that are not an EXR are refused as such.
ImageRgbF decodeExrImage(std::span<const std::byte> bytes, const std::string& name,
                         std::uint64_t maxPixels = kMaxImagePixels);

// Float32 RGB EXR, lossless (ZIP). Throws Error naming the file for a non-finite pixel (readImage
// would refuse the file) or when it cannot be written; never leaves a partial file.
void writeExr(const std::filesystem::path& path, const ImageRgbF& image);
// The bytes writeExr writes (`path` only names the image in errors).
std::vector<std::byte> encodeExr(const std::filesystem::path& path, const ImageRgbF& image);
// 8-bit sRGB PNG: linear values encoded with linearToSrgb8 (clamped to [0, 1]).
void writePngSrgb(const std::filesystem::path& path, const ImageRgbF& image);
// By extension, case-insensitive: .png (writePngSrgb) or .exr (writeExr); otherwise Error.
void writeImage(const std::filesystem::path& path, const ImageRgbF& image);
// Throws the Error writeImage would throw for `path`'s extension, so that a program can refuse an
// output name before the work that makes the image.
void requireImageExtension(const std::filesystem::path& path);
// The extension with its dot, lower-cased ("" when there is none): how files are told apart by name.
std::string lowercaseExtension(const std::filesystem::path& path);

// The display transform of kernel/tonemap.h (exposure, ACES fit, sRGB, dithered rounding, so that
// smooth gradients do not band) to 8 bits per channel, on the CPU. The rasteriser's images and window use the same transform on the GPU
// (gl/display.h), whose pow may differ in the last bits: a value on a rounding boundary can land
// one level apart.
ImageRgb8 displayEncode(const ImageRgbF& radiance, float exposure);

// GL readback: `rgba` holds width * height RGBA pixels; `bottomUp` when rows come bottom row first,
// as glReadPixels returns them. Alpha is ignored. The 8-bit form decodes sRGB to linear (an
// GL_SRGB8_ALPHA8 framebuffer); the float form takes values as linear.

ImageRgbF fromRgba8Srgb(int width, int height, const std::uint8_t* rgba, bool bottomUp);
ImageRgbF fromRgbaFloat(int width, int height, const float* rgba, bool bottomUp);

struct ImageError {
  double rmse;           // sqrt(mean over pixels and channels of (t - r)^2)
  double relmse;         // mean over pixels and channels of (t - r)^2 / (r^2 + 0.01)
  double meanReference;  // mean over pixels and channels of r, for "RMSE relative to the mean"
};

// `test` against `reference`, both linear. relmse is the relative MSE of Rousselle, Knaus and
// Zwicker (2011, "Adaptive sampling and reconstruction using greedy error minimization") with
// epsilon 1e-2, which keeps near-black reference pixels from dominating. Throws Error naming both
// sizes when they differ, and for empty images. Sums are in double, in a fixed order.
ImageError compareImages(const ImageRgbF& test, const ImageRgbF& reference);

// How two renderers' glints agree pixel for pixel (docs/method.md, "Extended lights", "Measuring"):
// each renderer's glint image over its smooth image (the same scene with the smooth target), the
// per-pixel ratio of luminances, which cancels what the renderers do differently for the smooth
// part. Pixels where either smooth image is below 1e-6 are left out, and so are those where both
// ratios are 1 to within 1e-6 (the background, which neither shades with glints).
struct GlintRatioAgreement {
  int pixels = 0;                  // compared
  double logCorrelation = 0.0;     // Pearson correlation of the two log ratios: 1 is flake for flake
  double aboveTwiceA = 0.0;        // fraction of pixels whose ratio exceeds 2, in A and in B
  double aboveTwiceB = 0.0;
  double variationA = 0.0;         // coefficient of variation (std / mean) of the ratio, in A and in B
  double variationB = 0.0;
};
// The pixels compared are those whose smooth images are both at least `minimumSmooth` times the
// 99th percentile of B's smooth luminance (a ratio over a smooth image near zero is a path
// tracer's noise, not its flakes), less those where both ratios are 1 (no glint layer). Throws
// Error when the four sizes differ, minimumSmooth is negative or no pixel is left to compare.
inline constexpr double kGlintRatioMinimumSmooth = 0.01;
GlintRatioAgreement glintRatioAgreement(const ImageRgbF& glintA, const ImageRgbF& smoothA, const ImageRgbF& glintB,
                                        const ImageRgbF& smoothB, double minimumSmooth = kGlintRatioMinimumSmooth);

// A picture of the per-pixel mean over channels of |a - b|, divided by `scale` and mapped through
// an approximation of matplotlib's 'inferno' colour map (values beyond `scale` saturate), with a
// colour bar from 0 to `scale` below it. `scale` 0 picks the 99th percentile of the differences
// (the maximum when that is 0; 1 when the images are equal), so one outlier does not wash the
// picture out. The canvas is at least kMinDiffWidth wide so that the legend fits. Throws Error for
// sizes that differ or a negative or non-finite scale.
inline constexpr int kMinDiffWidth = 160;
ImageRgb8 falseColourDifference(const ImageRgbF& a, const ImageRgbF& b, float scale);
// The difference scale falseColourDifference uses for `scale` 0 (exposed for tests).
float automaticDifferenceScale(const ImageRgbF& a, const ImageRgbF& b);
// The colour map: t in [0, 1] (clamped) to sRGB.
Rgb8 infernoColour(float t);

}  // namespace glint
