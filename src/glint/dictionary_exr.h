// The authors' published dictionary, a folder of EXR files, read into a Dictionary. Part of
// glint::image (the EXR decoder of image_io.h), so that glint::model links no image decoder.
#pragma once

#include <filesystem>

#include "glint/dictionary.h"

namespace glint {

// A folder dict_<L>_<N>_<R>_<alpha>_<s> of EXR files (docs/dictionary.md, "The authors' EXR
// dictionary"). Throws Error naming the folder or file and the problem.
Dictionary loadAuthorsExrDictionary(const std::filesystem::path& folder);
// A folder is read as the authors' EXR dictionary, a file as glint's own (Dictionary::load).
Dictionary loadAnyDictionary(const std::filesystem::path& path);

}  // namespace glint
