// `glint diff`: error metrics of a test image against a reference, and a false-colour picture of
// where they differ (docs/cli.md).
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "commands.h"
#include "glint/error.h"
#include "glint/image_io.h"

namespace glint::app {

namespace {

struct DiffOptions {
  std::string test;
  std::string reference;
  std::string output;
  float scale = 0.0f;
  std::vector<std::string> smooth;  // --glint-ratio: A's and B's smooth images
  double minimumSmooth = kGlintRatioMinimumSmooth;
};

void runDiff(const DiffOptions& options) {
  // Checked before any work, so that a wrong name costs nothing and leaves no file.
  if (!options.output.empty() && lowercaseExtension(options.output) != ".png") {
    throw Error(options.output + ": the difference picture is a PNG; give -o a .png name");
  }
  const ImageRgbF test = readImage(options.test);
  const ImageRgbF reference = readImage(options.reference);
  if (!options.smooth.empty()) {
    GlintRatioAgreement agreement;
    try {
      agreement = glintRatioAgreement(test, readImage(options.smooth[0]), reference, readImage(options.smooth[1]), options.minimumSmooth);
    } catch (const Error& e) {
      throw Error(options.test + " vs " + options.reference + ": " + e.what());
    }
    std::printf("pixels %d\nlog-ratio correlation %.4f\nabove twice the smooth %.5f %.5f\nratio variation %.4f %.4f\n",
                agreement.pixels, agreement.logCorrelation, agreement.aboveTwiceA, agreement.aboveTwiceB,
                agreement.variationA, agreement.variationB);
    std::fflush(stdout);
    return;
  }
  ImageError error;
  try {
    error = compareImages(test, reference);
  } catch (const Error& e) {
    throw Error(options.test + " vs " + options.reference + ": " + e.what());
  }
  // The picture first: a run that fails prints nothing but its error.
  if (!options.output.empty()) writePng(options.output, falseColourDifference(test, reference, options.scale));
  std::printf("rmse %.6g\nrelmse %.6g\n", error.rmse, error.relmse);
  std::fflush(stdout);
}

}  // namespace

void registerDiffCommand(CLI::App& app) {
  auto options = std::make_shared<DiffOptions>();
  CLI::App* command =
      app.add_subcommand("diff", "Compare image A against reference B (PNG or EXR): RMSE, relative MSE, a picture");
  command->add_option("A", options->test, "The image under test (PNG or EXR)")->required();
  command->add_option("B", options->reference, "The reference image (PNG or EXR)")->required();
  CLI::Option* output =
      command->add_option("-o,--output", options->output, "Write a false-colour picture of mean |A - B| to this PNG");
  command
      ->add_option("--scale", options->scale,
                   "The |A - B| at the top of the colour map (0: the 99th percentile of the differences)")
      ->capture_default_str()
      ->needs(output);
  CLI::Option* glintRatio =
      command
      ->add_option("--glint-ratio", options->smooth,
                   "A_SMOOTH B_SMOOTH: compare A's and B's glints, each image over its smooth one (the same scene "
                   "with --brdf cook-torrance), pixel for pixel: the log ratios' correlation, the fractions above "
                   "twice the smooth image and the ratios' coefficients of variation, each for A then B")
      ->expected(2)
      ->excludes(output);
  command
      ->add_option("--min-smooth", options->minimumSmooth,
                   "With --glint-ratio: compare only pixels whose smooth images are both at least this fraction of "
                   "the 99th percentile of B's smooth image (a ratio over a smooth value near zero is the path "
                   "tracer's noise)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1.0))
      ->needs(glintRatio);
  command->callback([options] { runDiff(*options); });
}

}  // namespace glint::app
