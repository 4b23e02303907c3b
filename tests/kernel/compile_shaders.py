#!/usr/bin/env python3
"""Compiles a shader that includes the shared kernel with glslangValidator, in one of the four
shading languages the kernel supports (src/glint/kernel/prelude.h), for the tests of
tests/CMakeLists.txt (KernelLanguages.*, KernelHost.*, KernelEval.*):

  gl      GLSL 4.50 for OpenGL, as SPIR-V for OpenGL (-G, plain uniforms' locations auto-mapped);
  vulkan  GLSL 4.50 for Vulkan (-V: no plain uniforms, descriptor sets and bindings);
  es      GLSL ES 3.00 (a fragment shader: ES 3.00 has no compute stage), validated as a WebGL2
          implementation sees it: `#include "..."` lines expanded by the host, as glint's
          renderer does (glslangValidator resolves includes only when it writes SPIR-V, and
          SPIR-V needs ES 3.10);
  hlsl    HLSL compute entry `main` (-D -V -e main -S comp).

Usage: compile_shaders.py --kernel DIR --shaders DIR LANGUAGE FILE [-DNAME=VALUE...]
Exits 77 (ctest's skip) with one line when glslangValidator is not installed."""
import os
import re
import shutil
import subprocess
import sys
import tempfile

SKIP = 77


def expand(path, include_dirs, out, stack=()):
    """The file with its quoted #include lines replaced by the included files, as
    src/gl/shader.cpp's expandIncludes does (include guards stop repeats)."""
    if path in stack:
        raise SystemExit(f"{path}: includes itself")
    with open(path, encoding="utf-8") as f:
        for line in f:
            match = re.match(r'\s*#\s*include\s+"([^"]+)"', line)
            if not match:
                out.append(line if line.endswith("\n") else line + "\n")
                continue
            for directory in [os.path.dirname(path)] + include_dirs:
                candidate = os.path.join(directory, match.group(1))
                if os.path.isfile(candidate):
                    expand(candidate, include_dirs, out, stack + (path,))
                    break
            else:
                raise SystemExit(f"{path}: included file {match.group(1)} not found in {include_dirs}")


def main(argv):
    args = list(argv)
    options = {}
    for name in ("--kernel", "--shaders"):
        if name not in args or args.index(name) + 1 >= len(args):
            print(f"compile_shaders.py: {name} DIR is required", file=sys.stderr)
            return 2
        i = args.index(name)
        options[name] = os.path.abspath(args[i + 1])
        del args[i : i + 2]
    defines = [a for a in args if a.startswith("-D")]
    positional = [a for a in args if not a.startswith("-D")]
    if len(positional) != 2 or positional[0] not in ("gl", "vulkan", "es", "hlsl"):
        print("usage: compile_shaders.py --kernel DIR --shaders DIR gl|vulkan|es|hlsl FILE [-DNAME=VALUE...]",
              file=sys.stderr)
        return 2
    language, source = positional[0], os.path.abspath(positional[1])
    glslang = shutil.which("glslangValidator")
    if glslang is None:
        print("glslangValidator not found (Debian's glslang-tools): skipped")
        return SKIP
    include_dirs = [options["--kernel"], options["--shaders"], os.path.dirname(source)]
    includes = ["-I" + d for d in include_dirs]
    with tempfile.TemporaryDirectory() as temporary:
        output = os.path.join(temporary, "out.spv")
        if language == "gl":
            command = [glslang, "-G", "--auto-map-locations", *includes, *defines, source, "-o", output]
        elif language == "vulkan":
            command = [glslang, "-V", *includes, *defines, source, "-o", output]
        elif language == "hlsl":
            command = [glslang, "-D", "-V", "-e", "main", "-S", "comp", *includes, *defines, source, "-o", output]
        else:
            lines = []
            expand(source, include_dirs, lines)
            expanded = os.path.join(temporary, os.path.basename(source))
            with open(expanded, "w", encoding="utf-8") as f:
                f.writelines(lines)
            command = [glslang, *defines, expanded]
        result = subprocess.run(command, capture_output=True, text=True)
    print(" ".join(command))
    print(result.stdout + result.stderr)
    print(f"{os.path.basename(source)} as {language}: " + ("compiles" if result.returncode == 0 else "does not compile"))
    return 0 if result.returncode == 0 else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
