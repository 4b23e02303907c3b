// One line of `glint eval`, apart from its command so that the fuzz target calls the very same
// parser (fuzz/fuzz_eval_line.cpp).
#pragma once

#include <string>

#include "glint/dictionary.h"

namespace glint::app {

// A JSON object of the fields docs/cli.md lists to its output line, {"f": ..., "D": ..., "P22": ...}
// without the newline. Throws Error with the problem (malformed JSON, an unknown field, a value of
// the wrong type or out of range); the caller adds the line number.
std::string evaluateLine(const std::string& line, const Dictionary& dictionary);

}  // namespace glint::app
