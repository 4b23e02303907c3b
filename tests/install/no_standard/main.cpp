// Includes every installed glint header (the model's API and the kernel) and evaluates the BRDF
// once, so that a header that needs a newer standard than the compiler's default fails to build.
#include <cstdio>

#include <glint/bsdf.h>
#include <glint/dictionary.h>
#include <glint/kernel/glint_kernel.h>

int main() {
  const glint::GlintParameters parameters = glint::defaultGlintParameters();
  glint::validateGlintParameters(parameters);
  std::printf("log density %.1f\n", parameters.logDensity);
  return 0;
}
