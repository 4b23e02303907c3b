// `glint eval`: the BRDF for JSON lines on stdin, one JSON line out per line in (docs/cli.md).
#include <iostream>
#include <memory>
#include <string>

#include "commands.h"
#include "glint/dictionary.h"
#include "glint/dictionary_exr.h"
#include "glint/error.h"
#include "eval_line.h"

namespace glint::app {

namespace {

void runEval(const std::string& dictionaryPath) {
  const Dictionary dictionary =
      dictionaryPath.empty() ? generateDictionary(DictionaryParameters{}) : loadAnyDictionary(dictionaryPath);
  std::string line;
  for (long number = 1; std::getline(std::cin, line); ++number) {
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    try {
      std::cout << evaluateLine(line, dictionary) << '\n';
    } catch (const Error& e) {
      throw Error("stdin line " + std::to_string(number) + ": " + e.what());
    }
  }
  std::cout.flush();
}

}  // namespace

void registerEvalCommand(CLI::App& app) {
  auto dictionaryPath = std::make_shared<std::string>();
  CLI::App* command = app.add_subcommand("eval", "Evaluate the BRDF for JSON lines on stdin (docs/cli.md)");
  command->add_option("--dict", *dictionaryPath,
                      "Dictionary file or the authors' EXR folder (default: generate the default dictionary)");
  command->callback([dictionaryPath] { runEval(*dictionaryPath); });
}

}  // namespace glint::app
