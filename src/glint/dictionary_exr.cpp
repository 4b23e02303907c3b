#include "glint/dictionary_exr.h"

#include <cstdio>
#include <regex>
#include <string>
#include <vector>

#include "glint/error.h"
#include "glint/file_io.h"
#include "glint/image_io.h"

namespace glint {

Dictionary loadAuthorsExrDictionary(const std::filesystem::path& folder) {
  // The folder's name carries the parameters: dict_<L>_<N>_<R>_<alpha>_<s>, 'p' for the point.
  const std::string name = std::filesystem::path(folder).lexically_normal().filename().string().empty()
                               ? folder.lexically_normal().parent_path().filename().string()
                               : folder.lexically_normal().filename().string();
  const std::regex pattern(R"(dict_(\d+)_(\d+)_(\d+)_(\d{1,9}p\d{1,9})_(\d{1,9}p\d{1,9}))");
  std::smatch match;
  if (!std::regex_match(name, match, pattern)) {
    throw Error(folder.string() + ": not an EXR dictionary folder (expected a name like dict_16_192_64_0p5_0p02)");
  }
  auto decimal = [](std::string text) {
    text[text.find('p')] = '.';
    return std::stof(text);  // at most 9 digits a side (the pattern): within float's range
  };
  // More digits than an int holds is out of every range the parameters accept: validate() says so.
  auto whole = [](const std::string& digits) { return digits.size() > 9 ? 1000000000 : std::stoi(digits); };
  DictionaryParameters parameters;
  parameters.numLevels = whole(match[1]);
  parameters.numDistributions = whole(match[2]);
  parameters.texelsPerDistribution = whole(match[3]);
  parameters.alpha = decimal(match[4]);
  parameters.lobeStd = decimal(match[5]);
  parameters.seed = 0;
  parameters.placement = LobePlacement::Imported;
  try {
    parameters.validate();
  } catch (const Error& e) {
    throw Error(folder.string() + ": " + e.what());
  }
  if (parameters.numDistributions % 3 != 0) {
    throw Error(folder.string() + ": the distribution count must be a multiple of 3 (RGB triplets)");
  }
  const int R = parameters.texelsPerDistribution;
  const int N = parameters.numDistributions;
  std::vector<float> values(static_cast<std::size_t>(parameters.numLevels) * N * R);
  for (int triplet = 0; triplet < N / 3; ++triplet) {
    for (int level = 0; level < parameters.numLevels; ++level) {
      char suffix[32];
      std::snprintf(suffix, sizeof suffix, "_%04d_%04d.exr", triplet, level);
      const std::filesystem::path file = folder / (name + suffix);
      // The checked EXR reader of images (image_io.h): the same header checks for both.
      const ImageRgbF image = decodeExrImage(readFile(file), file.string());
      if (image.width != R || image.height != 1) {
        throw Error(file.string() + ": image is " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                    ", expected " + std::to_string(R) + "x1");
      }
      for (int channel = 0; channel < 3; ++channel) {
        float* row = &values[(static_cast<std::size_t>(level) * N + 3 * triplet + channel) * R];
        for (int x = 0; x < R; ++x) row[x] = image.at(x, 0)[channel];
      }
    }
  }
  try {
    return Dictionary(parameters, values);
  } catch (const Error& e) {
    throw Error(folder.string() + ": " + e.what());
  }
}

Dictionary loadAnyDictionary(const std::filesystem::path& path) {
  std::error_code ec;
  return std::filesystem::is_directory(path, ec) ? loadAuthorsExrDictionary(path) : Dictionary::load(path);
}

}  // namespace glint
