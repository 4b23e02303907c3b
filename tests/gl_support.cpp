#include "gl_support.h"

#include <memory>

#include "gl/context.h"

namespace glint::test {

void useGlContext() {
  static const std::unique_ptr<gl::HeadlessContext> context = std::make_unique<gl::HeadlessContext>();
}

}  // namespace glint::test
