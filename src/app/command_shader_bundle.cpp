// `glint shader-bundle`: the kernel as one file, for a host renderer that takes one include
// (--language), or as a Shadertoy shader (--shadertoy): docs/integration.md.
#include <cstddef>
#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
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

// What a bundle's language says of the macros that select the kernel's language branches
// (prelude.h): defined (true), not defined (false), or not known here (nullopt: the host's).
std::optional<bool> languageDefines(const std::string& language, const std::string& macro) {
  if (macro == "__cplusplus") return false;
  if (macro == "GLINT_HLSL") return language == "hlsl";
  if (macro == "__HLSL_VERSION") return language == "hlsl" ? std::nullopt : std::optional<bool>(false);
  if (macro == "GL_ES") return language == "glsl-es";
  return std::nullopt;
}

// A preprocessor condition over those macros, in three values: true, false, or not known (a macro
// of the host's, or an operator this reader leaves to the compiler). Reads defined(X), defined X,
// !, &&, ||, parentheses, whole numbers and bare names.
class LanguageCondition {
 public:
  LanguageCondition(const std::string& text, const std::string& language) : language_(language) {
    static const std::regex token(R"(\s*(defined\b|[A-Za-z_]\w*|\d+|&&|\|\||!|\(|\)|\S))");
    for (std::sregex_iterator it(text.begin(), text.end(), token), end; it != end; ++it) tokens_.push_back((*it)[1]);
  }

  std::optional<bool> value() {
    const std::optional<bool> result = disjunction();
    return position_ == tokens_.size() && !malformed_ ? result : std::nullopt;
  }

 private:
  std::optional<bool> disjunction() {
    std::optional<bool> result = conjunction();
    while (accept("||")) {
      const std::optional<bool> next = conjunction();
      result = (result == true || next == true) ? std::optional<bool>(true)
               : (result && next)               ? std::optional<bool>(false)
                                                : std::nullopt;
    }
    return result;
  }
  std::optional<bool> conjunction() {
    std::optional<bool> result = negation();
    while (accept("&&")) {
      const std::optional<bool> next = negation();
      result = (result == false || next == false) ? std::optional<bool>(false)
               : (result && next)                 ? std::optional<bool>(true)
                                                  : std::nullopt;
    }
    return result;
  }
  std::optional<bool> negation() {
    if (!accept("!")) return primary();
    const std::optional<bool> inner = negation();
    return inner ? std::optional<bool>(!*inner) : std::nullopt;
  }
  std::optional<bool> primary() {
    if (accept("(")) {
      const std::optional<bool> inner = disjunction();
      if (!accept(")")) malformed_ = true;
      return inner;
    }
    if (accept("defined")) {
      const bool parenthesised = accept("(");
      const std::string name = next();
      if (parenthesised && !accept(")")) malformed_ = true;
      return languageDefines(language_, name);
    }
    const std::string word = next();
    if (!word.empty() && std::isdigit(static_cast<unsigned char>(word[0]))) return word != "0";
    // A bare name: 0 where the language leaves it undefined, otherwise the host's value.
    const std::optional<bool> defined = languageDefines(language_, word);
    return defined == false ? std::optional<bool>(false) : std::nullopt;
  }
  bool accept(const char* expected) {
    if (position_ < tokens_.size() && tokens_[position_] == expected) return ++position_, true;
    return false;
  }
  std::string next() {
    if (position_ >= tokens_.size() || !(std::isalnum(static_cast<unsigned char>(tokens_[position_][0])) ||
                                         tokens_[position_][0] == '_')) {
      malformed_ = true;
      return "";
    }
    return tokens_[position_++];
  }

  std::string language_;
  std::vector<std::string> tokens_;
  std::size_t position_ = 0;
  bool malformed_ = false;
};

// The text without the branches that its language rules out (a GLSL ES bundle keeps neither the
// C++ nor the HLSL spellings of prelude.h): a group whose condition the language decides keeps only
// its chosen branch, without the directives; every other group is left to the compiler as written.
std::string withoutOtherLanguages(const std::string& text, const std::string& language) {
  static const std::regex directive(R"(^\s*#\s*(if|ifdef|ifndef|elif|else|endif)\b(.*)$)");
  enum class Group { Kept, Decided, Dropped };  // Kept: the directives stay; Dropped: inside a dead branch
  struct Frame {
    Group group;
    bool live;   // Decided: this branch is kept
    bool taken;  // Decided: a branch has been chosen
  };
  std::vector<Frame> frames;
  const auto emitting = [&] {
    return std::all_of(frames.begin(), frames.end(), [](const Frame& f) { return f.group != Group::Dropped && f.live; });
  };
  const auto condition = [&](const std::string& keyword, std::string rest) {
    rest = rest.substr(0, rest.find("//"));
    if (keyword == "ifdef") return languageDefines(language, std::regex_replace(rest, std::regex(R"(\s)"), ""));
    if (keyword == "ifndef") {
      const std::optional<bool> defined = languageDefines(language, std::regex_replace(rest, std::regex(R"(\s)"), ""));
      return defined ? std::optional<bool>(!*defined) : std::nullopt;
    }
    return LanguageCondition(rest, language).value();
  };
  std::istringstream lines(text);
  std::string out;
  for (std::string read; std::getline(lines, read);) {
    // A directive continued with '\' is read as one line (`joined`) and written as it stands (`line`).
    std::string line = read;
    std::string joined = read;
    while (!joined.empty() && joined.back() == '\\' && joined.find_first_not_of(" \t") != std::string::npos &&
           joined[joined.find_first_not_of(" \t")] == '#' && std::getline(lines, read)) {
      line += '\n' + read;
      joined = joined.substr(0, joined.size() - 1) + ' ' + read;
    }
    std::smatch match;
    if (!std::regex_match(joined, match, directive)) {
      if (emitting()) out += line + '\n';
      continue;
    }
    const std::string keyword = match[1];
    if (keyword == "if" || keyword == "ifdef" || keyword == "ifndef") {
      if (!emitting()) {
        frames.push_back({Group::Dropped, false, false});
        continue;
      }
      const std::optional<bool> value = condition(keyword, match[2]);
      frames.push_back(value ? Frame{Group::Decided, *value, *value} : Frame{Group::Kept, true, false});
      if (!value) out += line + '\n';
      continue;
    }
    if (frames.empty()) throw Error("shader bundle: #" + keyword + " without #if: " + line);
    Frame& frame = frames.back();
    const bool outerEmitting = std::all_of(frames.begin(), frames.end() - 1, [](const Frame& f) {
      return f.group != Group::Dropped && f.live;
    });
    if (keyword == "endif") {
      if (frame.group == Group::Kept) out += line + '\n';
      frames.pop_back();
    } else if (frame.group == Group::Kept) {
      out += line + '\n';
    } else if (frame.group == Group::Decided && keyword == "else") {
      frame.live = !frame.taken;
      frame.taken = true;
    } else if (frame.group == Group::Decided) {  // #elif
      if (frame.taken) {
        frame.live = false;
        continue;
      }
      const std::optional<bool> value = condition("elif", match[2]);
      if (value) {
        frame.live = frame.taken = *value;
      } else if (outerEmitting) {
        // The earlier branches are gone: the rest of the group is left to the compiler from here.
        out += std::regex_replace(line, std::regex(R"(#\s*elif)"), "#if") + '\n';
        frame = {Group::Kept, true, false};
      }
    }
  }
  if (!frames.empty()) throw Error("shader bundle: an #if without #endif");
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
                  withoutOtherLanguages(expandedWithoutLines("glint_extended_lights.h", "glint_kernel.h"), options.language)
            : bundleHeader("the whole kernel as " + options.language) + preamble +
                  withoutOtherLanguages(expandedWithoutLines("glint_kernel.h"), options.language);
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
