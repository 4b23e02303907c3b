// One headless OpenGL 4.5 context for the whole test process (Mesa llvmpipe through EGL here and
// in CI): creating one per test would cost more than most tests.
#pragma once

namespace glint::test {

// Makes the shared context current (creating it on first use); throws glint::Error when no
// OpenGL 4.5 context can be made.
void useGlContext();

}  // namespace glint::test
