// What the install test's image checkers (check_example_image.cpp, compare_with_render.cpp) share:
// luminance, a check that prints its verdict, and numbers as they print them.
#pragma once

#include <cstdio>
#include <string>

#include <glm/glm.hpp>

#include "glint/error.h"

namespace glint::install_test {

// Rec. 709 luminance of a linear colour.
inline float luminance(glm::vec3 c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; }

// Prints "ok: what" or "FAILED: what"; throws on failure, so the checker exits non-zero.
inline void require(bool condition, const std::string& what) {
  std::printf("%s: %s\n", condition ? "ok" : "FAILED", what.c_str());
  if (!condition) throw glint::Error("check failed: " + what);
}

inline std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", value);
  return text;
}

}  // namespace glint::install_test
