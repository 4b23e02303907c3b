#include "glint/dictionary_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "glint/error.h"

namespace glint {

namespace {

constexpr int kPanelWidth = 420;
constexpr int kPanelHeight = 260;
constexpr int kColumns = 3;
constexpr int kMargin = 36;
constexpr Rgb8 kBackground{255, 255, 255};
constexpr Rgb8 kAxis{90, 90, 90};
constexpr Rgb8 kTarget{170, 170, 170};
constexpr Rgb8 kMean{0, 0, 0};
constexpr Rgb8 kPalette[] = {{31, 119, 180}, {214, 39, 40}, {44, 160, 44}, {255, 127, 14}, {148, 103, 189}, {23, 190, 207}};

}  // namespace

ImageRgb8 plotDictionary(const Dictionary& dictionary, const DictionaryPlotOptions& options) {
  const DictionaryParameters& p = dictionary.parameters();
  for (int level : options.levels) {
    if (level < 0 || level >= p.numLevels) {
      throw Error("plot level " + std::to_string(level) + " does not exist (levels 0 to " +
                  std::to_string(p.numLevels - 1) + ")");
    }
  }
  for (int n : options.distributions) {
    if (n < 0 || n >= p.numDistributions) {
      throw Error("plot distribution " + std::to_string(n) + " does not exist (0 to " +
                  std::to_string(p.numDistributions - 1) + ")");
    }
  }
  if (options.levels.empty()) throw Error("plot: no level to draw");

  const int panels = static_cast<int>(options.levels.size());
  const int rows = (panels + kColumns - 1) / kColumns;
  const int legendHeight = 40;
  ImageRgb8 image(kColumns * kPanelWidth, rows * kPanelHeight + legendHeight, kBackground);
  const float domain = p.slopeDomain();
  const double target = targetStd(p);
  constexpr int kSamples = 400;

  for (int panel = 0; panel < panels; ++panel) {
    const int level = options.levels[static_cast<std::size_t>(panel)];
    const int left = (panel % kColumns) * kPanelWidth + kMargin;
    const int top = (panel / kColumns) * kPanelHeight + 28;
    const int width = kPanelWidth - kMargin - 12;
    const int height = kPanelHeight - 28 - 30;

    // Curves as functions of slope over the whole (even) domain.
    auto slopeAt = [&](int i) { return -domain + 2.0f * domain * static_cast<float>(i) / kSamples; };
    std::vector<std::vector<float>> curves;
    for (int n : options.distributions) {
      std::vector<float> curve(kSamples + 1);
      for (int i = 0; i <= kSamples; ++i) curve[i] = dictionary.marginal(level, n, slopeAt(i));
      curves.push_back(std::move(curve));
    }
    std::vector<float> mean(kSamples + 1, 0.0f);
    std::vector<float> normal(kSamples + 1);
    for (int i = 0; i <= kSamples; ++i) {
      for (int n = 0; n < p.numDistributions; ++n) mean[i] += dictionary.marginal(level, n, slopeAt(i));
      mean[i] /= static_cast<float>(p.numDistributions);
      const double x = slopeAt(i);
      normal[i] = static_cast<float>(std::exp(-0.5 * x * x / (target * target)) / (target * std::sqrt(2.0 * M_PI)));
    }
    float yMax = *std::max_element(normal.begin(), normal.end());
    for (const auto& curve : curves) yMax = std::max(yMax, *std::max_element(curve.begin(), curve.end()));
    yMax *= 1.05f;

    auto px = [&](int i) { return static_cast<float>(left) + width * static_cast<float>(i) / kSamples; };
    auto py = [&](float v) { return static_cast<float>(top + height) - height * v / yMax; };
    image.drawLine(left, top + height, left + width, top + height, kAxis, 1.0f);
    image.drawLine(left, top, left, top + height, kAxis, 1.0f);
    image.drawLine(left + width / 2.0f, top + height, left + width / 2.0f, top + height + 4, kAxis, 1.0f);

    for (std::size_t c = 0; c < curves.size(); ++c) {
      const Rgb8 colour = kPalette[c % std::size(kPalette)];
      for (int i = 0; i < kSamples; ++i) image.drawLine(px(i), py(curves[c][i]), px(i + 1), py(curves[c][i + 1]), colour);
    }
    for (int i = 0; i < kSamples; i += 2) {  // dashed: the limit distribution
      image.drawLine(px(i), py(normal[i]), px(i + 1), py(normal[i + 1]), kTarget, 2.5f);
    }
    for (int i = 0; i < kSamples; ++i) image.drawLine(px(i), py(mean[i]), px(i + 1), py(mean[i + 1]), kMean, 1.2f);

    char text[96];
    std::snprintf(text, sizeof text, "level %d: %d lobes each", level, 1 << level);
    image.drawText(left, top - 22, text, kAxis);
    std::snprintf(text, sizeof text, "%.2f", -domain);
    image.drawText(left - 10, top + height + 8, text, kAxis);
    std::snprintf(text, sizeof text, "%.2f", domain);
    image.drawText(left + width - 24, top + height + 8, text, kAxis);
    image.drawText(left + width / 2 - 30, top + height + 8, "slope 0", kAxis);
    std::snprintf(text, sizeof text, "max %.3g", yMax);
    image.drawText(left + 6, top + 2, text, kAxis);
  }

  // Legend.
  int x = kMargin;
  const int y = rows * kPanelHeight + 12;
  for (std::size_t c = 0; c < options.distributions.size(); ++c) {
    const Rgb8 colour = kPalette[c % std::size(kPalette)];
    image.fillRect(x, y + 4, x + 24, y + 8, colour);
    const std::string label = "distribution " + std::to_string(options.distributions[c]);
    x += 30 + image.drawText(x + 30, y, label.c_str(), kAxis) + 20;
  }
  image.fillRect(x, y + 4, x + 24, y + 7, kMean);
  x += 30 + image.drawText(x + 30, y, "mean of all", kAxis) + 20;
  image.fillRect(x, y + 4, x + 10, y + 8, kTarget);
  image.fillRect(x + 14, y + 4, x + 24, y + 8, kTarget);
  char text[96];
  std::snprintf(text, sizeof text, "limit N(0, %.3f^2)", target);
  image.drawText(x + 30, y, text, kAxis);
  return image;
}

}  // namespace glint
