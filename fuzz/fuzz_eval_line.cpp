// `glint eval`'s JSON-line parser and the BRDF evaluation it leads to (app/eval_line.cpp), with the
// default dictionary, as `glint eval` runs it.
#include <string>

#include "app/eval_line.h"
#include "glint/dictionary.h"
#include "glint/error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const glint::Dictionary dictionary = glint::generateDictionary(glint::DictionaryParameters{});
  try {
    glint::app::evaluateLine(std::string(reinterpret_cast<const char*>(data), size), dictionary);
  } catch (const glint::Error&) {
  }
  return 0;
}
