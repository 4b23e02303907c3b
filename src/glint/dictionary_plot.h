// A picture of a dictionary: chosen marginals at several levels, with the mean marginal of each
// level and the normal distribution the levels tend to (docs/dictionary.md shows one).
#pragma once

#include <vector>

#include "glint/dictionary.h"
#include "glint/image.h"

namespace glint {

struct DictionaryPlotOptions {
  std::vector<int> distributions{0, 1, 2};
  std::vector<int> levels{0, 2, 4, 7, 10, 15};  // levels past the dictionary's last are an error
};

// Throws Error when a requested level or distribution does not exist.
ImageRgb8 plotDictionary(const Dictionary& dictionary, const DictionaryPlotOptions& options);

}  // namespace glint
