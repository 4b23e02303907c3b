#!/usr/bin/env python3
"""Lists every top-level name the shared kernel defines (functions, structs, constants, tables,
type aliases, macros) and fails if one lacks the kernel's prefix: functions glintXxx, types
GlintXxx, constants and macros GLINT_XXX (docs/conventions.md, "Kernel names"). A host renderer
includes the kernel into its own shaders, so an unprefixed name could collide with one of its own.

Usage: check_prefixes.py [--list] FILE_OR_DIR...   (a directory: its *.h files)
The HLSL branch of prelude.h gives GLSL's vector type names to HLSL (vec3 as float3 and the like);
those are GLSL's vocabulary, which the kernel is written in, not names of the kernel's, and are the
one listed exception."""
import os
import re
import sys

FUNCTION = re.compile(r"^glint[A-Z0-9]\w*$")
TYPE = re.compile(r"^Glint[A-Z0-9]\w*$")
CONSTANT = re.compile(r"^GLINT_[A-Z0-9_]+$")
# GLSL's own vector type names, which prelude.h maps to HLSL's.
GLSL_TYPE_NAMES = {prefix + "vec" + n for prefix in ("", "i", "u", "b") for n in "234"}


def strip_comments(text):
    text = re.sub(r"/\*.*?\*/", lambda m: "\n" * m.group(0).count("\n"), text, flags=re.S)
    return re.sub(r"//[^\n]*", "", text)


def definitions(path):
    """(line, kind, name) of each top-level definition of a kernel file."""
    text = strip_comments(open(path, encoding="utf-8").read())
    found = []
    # Preprocessor lines (with their continuations): macros; the rest is blanked out.
    lines = text.split("\n")
    code_lines = []
    i = 0
    while i < len(lines):
        line = lines[i]
        if line.lstrip().startswith("#"):
            directive = line
            start = i
            while directive.endswith("\\") and i + 1 < len(lines):
                i += 1
                directive = directive[:-1] + " " + lines[i]
                code_lines.append("")
            code_lines.append("")
            match = re.match(r"\s*#\s*define\s+(\w+)", directive)
            if match:
                found.append((start + 1, "macro", match.group(1)))
        else:
            code_lines.append(line)
        i += 1
    code = "\n".join(code_lines)
    # Tables: GLINT_TABLE_BEGIN(NAME, SIZE) values GLINT_TABLE_END.
    def table(match):
        found.append((code.count("\n", 0, match.start()) + 1, "constant", match.group(1)))
        return "\n" * match.group(0).count("\n")
    code = re.sub(r"GLINT_TABLE_BEGIN\s*\(\s*(\w+)\s*,[^)]*\)(.*?)GLINT_TABLE_END", table, code, flags=re.S)
    code = re.sub(r"\bGLINT_KERNEL_(BEGIN|END)\b", "", code)
    # Top-level statements: text at brace depth 0 up to the ';' or '{' that ends it.
    depth = 0
    statement = ""
    statement_line = 1
    line = 1
    for ch in code:
        if ch == "\n":
            line += 1
        if depth == 0:
            if not statement.strip():
                statement_line = line
            if ch == "{":
                found.extend(declared(statement, statement_line, opens_body=True))
                statement = ""
                depth = 1
            elif ch == ";":
                found.extend(declared(statement, statement_line, opens_body=False))
                statement = ""
            elif ch == "}":
                raise SystemExit(f"{path}:{line}: unbalanced '}}'")
            else:
                statement += ch
        else:
            if ch == "{":
                depth += 1
            elif ch == "}":
                depth -= 1
                if depth == 0:
                    statement = ""  # a struct's trailing ';' or a function's end
    return found


def declared(statement, line, opens_body):
    """The names a top-level statement declares."""
    s = " ".join(statement.split())
    if not s or s.startswith("static_assert"):  # a C++ check (in a C++-only block), no name
        return []
    match = re.match(r"^struct\s+(\w+)$", s)
    if match:
        return [(line, "type", match.group(1))]
    match = re.match(r"^typedef\s+.*?(\w+)$", s) or re.match(r"^using\s+(\w+)\s*=", s)
    if match:
        return [(line, "type", match.group(1))]
    if "(" in s and ("=" not in s or s.index("(") < s.index("=")):
        match = re.search(r"(\w+)\s*\($", s[: s.index("(") + 1])
        if match:
            return [(line, "function", match.group(1))]
    match = re.match(r"^(.*?)(\w+)\s*(\[[^\]]*\])?\s*(=.*)?$", s)
    if match and not opens_body:
        return [(line, "constant", match.group(2))]
    return [(line, "unrecognised", s[:60])]


def well_named(kind, name):
    if kind == "function":
        return bool(FUNCTION.match(name))
    if kind == "type":
        return bool(TYPE.match(name))
    if kind == "macro":
        return bool(CONSTANT.match(name)) or name in GLSL_TYPE_NAMES
    if kind == "constant":
        return bool(CONSTANT.match(name))
    return False


def main(argv):
    listing = "--list" in argv
    paths = []
    for arg in (a for a in argv if a != "--list"):
        if os.path.isdir(arg):
            paths += sorted(os.path.join(arg, f) for f in os.listdir(arg) if f.endswith(".h"))
        else:
            paths.append(arg)
    if not paths:
        print("check_prefixes.py: no kernel file given", file=sys.stderr)
        return 2
    bad = 0
    count = 0
    for path in paths:
        for line, kind, name in definitions(path):
            count += 1
            ok = well_named(kind, name)
            if listing or not ok:
                print(f"{path}:{line}: {kind} {name}" + ("" if ok else ": lacks the kernel prefix"))
            bad += not ok
    print(f"{count} top-level names in {len(paths)} files, {bad} without the prefix")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
