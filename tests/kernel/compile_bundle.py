#!/usr/bin/env python3
"""A bundle of `glint shader-bundle --language LANGUAGE` compiles on its own: the bundle's text,
then a host's few lines (the dictionary hook over a buffer of its own, and an entry point that
calls the kernel's main functions), compiled by glslangValidator as tests/kernel/compile_shaders.py
does for each language (ShaderBundle.* in tests/CMakeLists.txt). With `extended-lights`, the
kernel's bundle, then `--extended-lights`'s after it, and a host that defines the hook's third
function too and calls the region masses of one area light.

Usage: compile_bundle.py GLINT_EXECUTABLE glsl|glsl-es|vulkan|hlsl [extended-lights]
Exits 77 (ctest's skip) with one line when glslangValidator is not installed."""
import os
import shutil
import subprocess
import sys
import tempfile

SKIP = 77

# The host's side, in the kernel's GLSL vocabulary (the HLSL branch of the prelude maps vec2 and
# the rest onto HLSL's types).
PARAMETERS = """
  GlintDictionaryView d;
  d.numLevels = 16;
  d.numDistributions = 192;
  d.texelsPerDistribution = 64;
  d.alpha = 0.5;
  d.numMips = 1;
  d.mipRowLength = 64;
  GlintParameters p;
  p.alpha = vec2(0.3, 0.3);
  p.rho = 0.0;
  p.logDensity = 20.0;
  p.relativeArea = 1.0;
  p.densityRandomisation = 2.0;
  p.maxAnisotropy = 8.0;
  p.patternSeed = 0u;
  p.colouredCells = false;
  p.ndf = GLINT_NDF_BECKMANN;
  p.masking = GLINT_MASKING_VCAVITY;
  p.lod = GLINT_LOD_PAPER;
  p.multipleScattering = false;
  p.footprintPolicy.maxAnisotropy = 0.0;
  p.footprintPolicy.maxCells = 0.0;
  p.footprintPolicy.minBlend = 0.0;
  float f = glintReflectance(d, p, vec2(0.3, 0.7), vec2(0.001, 0.0), vec2(0.0, 0.001), vec3(0.0, 0.0, 1.0),
                             normalize(vec3(0.1, 0.0, 1.0)));
"""

HOOK_BODY = """{
  return PAIR((level * d.numDistributions + distribution) * d.texelsPerDistribution + texel);
}
vec4 glintDictionaryFilteredTexels(GlintDictionaryView d, int level, int distribution, int index) {
  vec2 pair = glintDictionaryTexelPair(d, level, distribution, index);
  return vec4(pair.x, pair.y, 0.0, 0.0);
}
"""
HOOK = "vec2 glintDictionaryTexelPair(GlintDictionaryView d, int level, int distribution, int texel) " + HOOK_BODY

# The extended lights' part: the cumulative hook over the same buffer (CUMULATIVE(i)), and one
# rectangle light above the surface.
CUMULATIVE_HOOK = """
vec4 glintDictionaryCumulativeTexel(GlintDictionaryView d, int level, int distribution, int texel) {
  return CUMULATIVE((level * d.numDistributions + distribution) * d.texelsPerDistribution + texel);
}
"""
EXTENDED_CALL = """
  GlintClippedLight light = glintClipLightToHorizon(normalize(vec3(-0.2, -0.2, 1.0)), normalize(vec3(0.2, -0.2, 1.0)),
                                                    normalize(vec3(0.2, 0.2, 1.0)), normalize(vec3(-0.2, 0.2, 1.0)));
  GlintRegionSet regions;
  regions.region[0] = glintLightSlopeRegion(vec3(0.0, 0.0, 1.0), light);
  GlintRegionMassSet masses = glintRegionMassSet(d, p, vec2(0.3, 0.7), vec2(0.001, 0.0), vec2(0.0, 0.001), regions);
  f += masses.mass[0].w * glintClippedLightProjectedSolidAngle(light);
"""
CUMULATIVE_READS = {
    "glsl": "#define CUMULATIVE(i) vec4(pairs[i], pairs[i])\n",
    "vulkan": "#define CUMULATIVE(i) vec4(pairs[i], pairs[i])\n",
    "glsl-es": "#define CUMULATIVE(i) texelFetch(uPairs, ivec2((i) % 2048, (i) / 2048), 0)\n",
    "hlsl": "#define CUMULATIVE(i) float4(pairs[i], pairs[i])\n",
}

HOSTS = {
    "glsl": ("comp", "#version 450\n", """
layout(std430, binding = 3) readonly buffer Pairs { vec2 pairs[]; };
#define PAIR(i) pairs[i]
""" + HOOK + """
layout(local_size_x = 1) in;
layout(std430, binding = 4) buffer Result { float result[]; };
void main() {""" + PARAMETERS + """  result[0] = f;
}
"""),
    "vulkan": ("comp", "#version 450\n", """
layout(set = 0, binding = 3) readonly buffer Pairs { vec2 pairs[]; };
#define PAIR(i) pairs[i]
""" + HOOK + """
layout(local_size_x = 1) in;
layout(set = 0, binding = 4) buffer Result { float result[]; };
void main() {""" + PARAMETERS + """  result[0] = f;
}
"""),
    "glsl-es": ("frag", "#version 300 es\nprecision highp float;\nprecision highp int;\n", """
uniform highp sampler2D uPairs;
#define PAIR(i) texelFetch(uPairs, ivec2((i) % 2048, (i) / 2048), 0).xy
""" + HOOK + """
out vec4 colour;
void main() {""" + PARAMETERS + """  colour = vec4(f);
}
"""),
    "hlsl": ("hlsl", "", """
StructuredBuffer<float2> pairs : register(t3);
#define PAIR(i) pairs[i]
""" + HOOK + """
RWStructuredBuffer<float> result : register(u4);
[numthreads(1, 1, 1)]
void main() {""" + PARAMETERS + """  result[0] = f;
}
"""),
}


def main(argv):
    extended = len(argv) == 3 and argv[2] == "extended-lights"
    if len(argv) not in (2, 3) or argv[1] not in HOSTS or (len(argv) == 3 and not extended):
        print("usage: compile_bundle.py GLINT_EXECUTABLE glsl|glsl-es|vulkan|hlsl [extended-lights]", file=sys.stderr)
        return 2
    glint, language = argv[:2]
    glslang = shutil.which("glslangValidator")
    if glslang is None:
        print("glslangValidator not found (Debian's glslang-tools): skipped")
        return SKIP
    stage, version, host = HOSTS[language]
    if extended:
        host = host.replace("  result[0] = f;", EXTENDED_CALL + "  result[0] = f;").replace(
            "  colour = vec4(f);", EXTENDED_CALL + "  colour = vec4(f);")
        # After the hook's buffer, before the entry point and its attributes.
        entry = "[numthreads" if language == "hlsl" else "layout(local_size_x" if language in ("glsl", "vulkan") else "out vec4 colour;"
        host = host.replace(entry, CUMULATIVE_READS[language] + CUMULATIVE_HOOK + entry, 1)
    with tempfile.TemporaryDirectory() as temporary:
        text = ""
        for part in [[], ["--extended-lights"]] if extended else [[]]:
            bundle = os.path.join(temporary, "glint.bundle")
            written = subprocess.run([glint, "shader-bundle", "--language", language, *part, "-o", bundle],
                                     capture_output=True, text=True)
            if written.returncode != 0:
                print(written.stderr)
                return 1
            with open(bundle, encoding="utf-8") as f:
                part_text = f.read()
            if "#include" in part_text:
                print("the bundle still has #include lines")
                return 1
            # The language's own branches only: prelude.h's C++ branch (namespace glint::kernel)
            # and, outside HLSL, its HLSL spellings are left out of the text.
            others = ["namespace glint::kernel {"] + ([] if language == "hlsl" else ["#define vec2 float2"])
            if any(other in part_text for other in others):
                print(f"the {language} bundle keeps another language's branch: " +
                      ", ".join(o for o in others if o in part_text))
                return 1
            text += ("#define GLINT_REGION_COUNT 1\n" if part else "") + part_text
        source = os.path.join(temporary, "host." + stage)
        with open(source, "w", encoding="utf-8") as f:
            f.write(version + text + host)
        output = os.path.join(temporary, "out.spv")
        if language == "glsl":
            command = [glslang, "-G", source, "-o", output]
        elif language == "vulkan":
            command = [glslang, "-V", source, "-o", output]
        elif language == "hlsl":
            command = [glslang, "-D", "-V", "-e", "main", "-S", "comp", source, "-o", output]
        else:
            command = [glslang, source]
        result = subprocess.run(command, capture_output=True, text=True)
    print(" ".join(command[:-2] if "-o" in command else command))
    print(result.stdout + result.stderr)
    what = f"the {language} bundle" + (" with its extended lights" if extended else "")
    print(f"{what}: " + ("compiles on its own" if result.returncode == 0 else "does not compile"))
    return 0 if result.returncode == 0 else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
