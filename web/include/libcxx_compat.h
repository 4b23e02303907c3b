// C++17 and C++20 library features that the libc++ of Debian's Emscripten (3.1.6, LLVM 14) does not have yet
// and glint's sources use; force-included into every file of the web build (web/CMakeLists.txt).
#pragma once

#ifdef __cplusplus
#include <bit>
#include <charconv>
#include <cstdio>
#include <cstdlib>
#include <system_error>
#if !defined(__cpp_lib_bit_cast)
namespace std {
template <class To, class From>
constexpr To bit_cast(const From& from) noexcept {
  return __builtin_bit_cast(To, from);
}
}  // namespace std
#endif

#if !defined(__cpp_lib_to_chars)
namespace std {
// to_chars of a float or double, shortest form: the fewest significant digits that read back as
// the same value (what the standard's overload gives, up to the choice of notation).
inline to_chars_result glintShortestToChars(char* first, char* last, double value, bool isFloat) {
  char text[32];
  int length = 0;
  for (int digits = 1; digits <= 17; ++digits) {
    length = std::snprintf(text, sizeof text, "%.*g", digits, value);
    const double back = std::strtod(text, nullptr);
    if (isFloat ? static_cast<float>(back) == static_cast<float>(value) : back == value) break;
  }
  if (length < 0 || length > last - first) return {last, errc::value_too_large};
  for (int i = 0; i < length; ++i) first[i] = text[i];
  return {first + length, errc{}};
}
inline to_chars_result to_chars(char* first, char* last, double value) {
  return glintShortestToChars(first, last, value, false);
}
inline to_chars_result to_chars(char* first, char* last, float value) {
  return glintShortestToChars(first, last, value, true);
}
// from_chars of a float, through strtof on a terminated copy of the characters.
inline from_chars_result from_chars(const char* first, const char* last, float& value) {
  char text[64];
  const long length = last - first < 63 ? last - first : 63;
  for (long i = 0; i < length; ++i) text[i] = first[i];
  text[length] = '\0';
  char* end = nullptr;
  const float parsed = std::strtof(text, &end);
  if (end == text) return {first, errc::invalid_argument};
  value = parsed;
  return {first + (end - text), errc{}};
}
}  // namespace std
#endif
#endif
