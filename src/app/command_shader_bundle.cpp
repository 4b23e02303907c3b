// `glint shader-bundle`: the kernel as one file, for a host renderer that takes one include
// (--language), or as a Shadertoy shader (--shadertoy): docs/integration.md.
#include <cstddef>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "app/commands.h"
#include "gl/shader.h"
#include "glint/error.h"
#include "glint/file_io.h"
#include "glint/version.h"

namespace glint::app {

namespace {

struct BundleOptions {
  std::string language;
  bool extendedLights = false;
  bool shadertoy = false;
  std::string output;
};

// What a bundle's first lines say: what it is, which version made it, how a host uses it.
std::string bundleHeader(const std::string& what) {
  return "// glint " GLINT_VERSION_STRING " shader kernel: " + what +
         ".\n// Written by `glint shader-bundle`; the equations of Chermain et al. 2020 (Pacific Graphics),\n"
         "// with their 2021 anti-aliasing (I3D); see docs/integration.md for the dictionary hook a host defines.\n";
}

// The embedded file with its includes expanded, without the #line directives of glint's own
// program assembly: in a bundle they would name source strings the host never sees.
// With `after`, as it reads after that file (its files left out).
std::string expandedWithoutLines(const std::string& name, const std::string& after = "") {
  static const std::regex lineDirective(R"(^\s*#\s*line\b.*$)");
  std::istringstream lines(after.empty() ? gl::expandIncludes(name).text : gl::expandIncludesAfter(after, name).text);
  std::string out;
  for (std::string line; std::getline(lines, line);) {
    if (!std::regex_match(line, lineDirective)) out += line + '\n';
  }
  return out;
}

// The lines that select a language's branch of the kernel's prelude, ahead of the kernel.
std::string languagePreamble(const std::string& language) {
  if (language == "glsl") return "// Desktop GLSL 4.50 (OpenGL).\n";
  if (language == "glsl-es") return "// GLSL ES 3.00 (WebGL2): the compiler defines GL_ES.\n";
  if (language == "vulkan") return "// GLSL 4.50 for Vulkan (SPIR-V through glslang).\n";
  if (language == "hlsl") return "// HLSL, shader model 6 rules.\n#ifndef GLINT_HLSL\n#define GLINT_HLSL 1\n#endif\n";
  throw Error("--language must be glsl, glsl-es, vulkan or hlsl, got '" + language + "'");
}

void runShaderBundle(const BundleOptions& options) {
  if (options.shadertoy == !options.language.empty()) {
    throw Error("give one of --language LANGUAGE and --shadertoy");
  }
  if (options.extendedLights && options.shadertoy) throw Error("--extended-lights goes with --language, not --shadertoy");
  if (!options.shadertoy) {
    const std::string preamble = languagePreamble(options.language);
    const std::string text =
        options.extendedLights
            ? bundleHeader("glints under area lights and environment regions (glint_extended_lights.h) as " +
                           options.language) +
                  "// Include it after the kernel's bundle (--language without --extended-lights) and define\n"
                  "// GLINT_REGION_COUNT first; it needs the hook's third function, glintDictionaryCumulativeTexel.\n" +
                  expandedWithoutLines("glint_extended_lights.h", "glint_kernel.h")
            : bundleHeader("the whole kernel as " + options.language) + preamble + expandedWithoutLines("glint_kernel.h");
    if (options.output.empty()) {
      std::fputs(text.c_str(), stdout);
      return;
    }
    writeFileAtomically(options.output, textBytes(text));
    std::fprintf(stderr, "glint: wrote %s (%s)\n", options.output.c_str(), options.language.c_str());
    return;
  }
  if (options.output.empty()) throw Error("--shadertoy writes three files: give the folder with -o FOLDER");
  // The folder is made if it is missing (its parent must exist, as for every other output), and
  // the three files are one output: all are written, or none, and a folder made here for them goes
  // again when they cannot be.
  const std::filesystem::path folder = options.output;
  std::error_code error;
  const bool made = !std::filesystem::exists(folder, error) && std::filesystem::create_directory(folder, error);
  if (error || !std::filesystem::is_directory(folder)) {
    throw Error(options.output + ": cannot make the folder (" + (error ? error.message() : "a file is in its place") + ")");
  }
  const std::string header = bundleHeader("a Shadertoy shader");
  try {
    writeFilesAtomically(
        {{folder / "common.glsl", textBytes(header + "// Paste into the Common tab.\n" + expandedWithoutLines("shadertoy_common.glsl"))},
         {folder / "buffer_a.glsl", textBytes(header + "// Paste into Buffer A.\n" + expandedWithoutLines("shadertoy_buffer_a.glsl"))},
         {folder / "image.glsl", textBytes(header + "// Paste into the Image tab; set its iChannel0 to Buffer A.\n" +
                                         expandedWithoutLines("shadertoy_image.glsl"))}});
  } catch (const Error&) {
    if (made) std::filesystem::remove(folder, error);  // only if empty: nothing of the user's goes
    throw;
  }
  std::fprintf(stderr, "glint: wrote %s: common.glsl (Common), buffer_a.glsl (Buffer A), image.glsl (Image, iChannel0 = Buffer A)\n",
               options.output.c_str());
}

}  // namespace

void registerShaderBundleCommand(CLI::App& app) {
  auto options = std::make_shared<BundleOptions>();
  CLI::App* command = app.add_subcommand(
      "shader-bundle", "Write the kernel as one include for a host's shaders, or a Shadertoy shader");
  command->add_option("--language", options->language, "glsl, glsl-es, vulkan or hlsl");
  command->add_flag("--extended-lights", options->extendedLights,
                    "Write glints under area lights and environment regions (glint_extended_lights.h) alone, a second "
                    "include after the kernel's bundle of the same --language");
  command->add_flag("--shadertoy", options->shadertoy,
                    "Write a Shadertoy shader (Common, Buffer A, Image) into the folder -o names");
  command->add_option("-o,--output", options->output, "The file (--language; default: standard output) or folder (--shadertoy)");
  command->callback([options] { runShaderBundle(*options); });
}

}  // namespace glint::app
