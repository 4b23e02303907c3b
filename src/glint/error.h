// Error policy (docs/conventions.md): user and file errors throw glint::Error with a one-line
// message naming the file or field and the problem; `glint` catches it once in main. Programmer
// errors are assertions. The hot path (the kernel) never throws: its inputs are validated first.
#pragma once

#include <stdexcept>
#include <string>

namespace glint {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace glint
