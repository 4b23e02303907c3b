// A kernel-style file with one name of each kind lacking the prefix, for the check of
// check_prefixes.py itself (KernelNames.CheckFindsUnprefixedNames expects each reported).
#ifndef GLINT_TEST_UNPREFIXED_FIXTURE_H
#define GLINT_TEST_UNPREFIXED_FIXTURE_H
#define PI 3.14159265f

GLINT_KERNEL_BEGIN

GLINT_CONST float kPi = 3.14159265f;

struct DictionaryView {
  int numLevels;
};

GLINT_FN vec3 fresnelSchlick(vec3 f0, float cosThetaI) {
  return f0;
}

GLINT_KERNEL_END

#endif
