// `glint dict`: generate a dictionary, or load one, then write it, plot it, print its statistics.
#include <charconv>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include <tbb/global_control.h>

#include "commands.h"
#include "glint/dictionary.h"
#include "glint/dictionary_exr.h"
#include "glint/dictionary_plot.h"
#include "glint/error.h"
#include "glint/file_io.h"
#include "glint/image.h"

namespace glint::app {

namespace {

struct DictOptions {
  std::string output;
  std::string from;
  DictionaryParameters parameters;
  std::string placement = "stratified";
  int threads = 0;
  std::string plot;
  std::vector<int> plotDistributions = DictionaryPlotOptions{}.distributions;
  std::vector<int> plotLevels = DictionaryPlotOptions{}.levels;
  bool stats = false;
  bool treeLevels = false;
};

void printStatistics(const Dictionary& dictionary) {
  const DictionaryParameters& p = dictionary.parameters();
  std::printf("level  lobes  integral(min..max)   std(min..mean..max) / target %.5f   mean-marginal L1\n",
              targetStd(p));
  const auto levels = computeStatistics(dictionary);
  for (std::size_t l = 0; l < levels.size(); ++l) {
    const LevelStatistics& s = levels[l];
    std::printf("%5zu  %5u  %.5f..%.5f   %.5f..%.5f..%.5f                  %.4f\n", l, 1u << l, s.minIntegral,
                s.maxIntegral, s.minStd, s.meanStd, s.maxStd, s.meanMarginalL1);
  }
}

void runDict(const DictOptions& options, const CLI::App& command) {
  // The plot's own options without a plot would do nothing: said, not ignored.
  for (const char* name : {"--plot-distributions", "--plot-levels"}) {
    if (options.plot.empty() && command.count(name) > 0) throw Error(std::string("glint dict: ") + name + " needs --plot PNG");
  }
  if (options.output.empty() && options.plot.empty() && !options.stats) {
    throw Error("glint dict: nothing to do; give -o FILE, --plot PNG or --stats");
  }
  if (options.treeLevels && options.output.empty()) {
    throw Error("glint dict: --tree-levels needs -o FILE (it says what the file holds)");
  }
  std::optional<tbb::global_control> threadLimit;
  if (options.threads > 0) {
    threadLimit.emplace(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(options.threads));
  }
  const auto start = std::chrono::steady_clock::now();
  std::unique_ptr<Dictionary> dictionary;
  if (!options.from.empty()) {
    for (const char* name : {"--levels", "--distributions", "--texels", "--alpha", "--lobe-std", "--seed", "--placement"}) {
      if (command.count(name) > 0) {
        throw Error(std::string("glint dict: ") + name + " cannot be combined with --from (the parameters come from the file)");
      }
    }
    dictionary = std::make_unique<Dictionary>(loadAnyDictionary(options.from));
  } else {
    DictionaryParameters parameters = options.parameters;
    parameters.placement = lobePlacementFromString(options.placement);
    dictionary = std::make_unique<Dictionary>(generateDictionary(parameters));
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  // Outputs first, the report after: a failure prints its one error line and nothing else.
  std::optional<ImageRgb8> plot;  // drawn before anything is written: it validates its options
  if (!options.plot.empty()) plot = plotDictionary(*dictionary, {options.plotDistributions, options.plotLevels});
  const DictionaryFileTables tables =
      options.treeLevels ? DictionaryFileTables::LevelsAndTreeLevels : DictionaryFileTables::Levels;
  // The dictionary and its plot are one output: both are written, or neither (a plot that cannot
  // be written leaves no dictionary file behind).
  std::vector<FileContents> outputs;
  if (!options.output.empty()) outputs.push_back({options.output, dictionary->serialise(tables)});
  if (plot) outputs.push_back({options.plot, encodePng(*plot)});
  writeFilesAtomically(outputs);
  const std::size_t fileBytes = options.output.empty() ? 0 : outputs.front().bytes.size();
  const DictionaryParameters& p = dictionary->parameters();
  std::fprintf(stderr, "glint: %s dictionary: %d levels x %d distributions x %d texels, alpha %g, lobe std %g, %s",
               options.from.empty() ? "generated" : "loaded", p.numLevels, p.numDistributions,
               p.texelsPerDistribution, p.alpha, p.lobeStd, toString(p.placement));
  if (p.placement != LobePlacement::Imported) std::fprintf(stderr, ", seed %llu", static_cast<unsigned long long>(p.seed));
  std::fprintf(stderr, " (%.2f s)\n", seconds);
  if (!options.output.empty()) {
    std::fprintf(stderr, "glint: wrote %s (%zu KiB: %s)\n", options.output.c_str(), fileBytes / 1024,
                 tables == DictionaryFileTables::LevelsAndTreeLevels ? "the levels and the tree levels, format version 2"
                                                                     : "the levels, format version 1");
  }
  if (!options.plot.empty()) std::fprintf(stderr, "glint: wrote %s\n", options.plot.c_str());
  if (options.stats) printStatistics(*dictionary);
}

}  // namespace

void registerDictCommand(CLI::App& app) {
  auto options = std::make_shared<DictOptions>();
  CLI::App* command = app.add_subcommand(
      "dict", "Generate a dictionary of multi-level slope distributions (or load one), write, plot, measure it");
  command->add_option("-o,--output", options->output, "Write the dictionary to this file (binary, docs/dictionary.md)");
  command->add_flag("--tree-levels", options->treeLevels,
                    "Write the tree levels too (format version 2), for hosts that upload the file as it is and "
                    "draw the tree LOD construction (web/three); glint builds them itself when it loads a file");
  command->add_option("--from", options->from,
                      "Load instead of generating: a dictionary file, or the authors' EXR folder dict_L_N_R_alpha_s");
  DictionaryParameters& p = options->parameters;
  command->add_option("--levels", p.numLevels, "L: levels; level l has 2^l lobes per distribution")->capture_default_str();
  command->add_option("--distributions", p.numDistributions, "N: distributions per level")->capture_default_str();
  command->add_option("--texels", p.texelsPerDistribution, "R: texels per distribution")->capture_default_str();
  command->add_option("--alpha", p.alpha, "alpha_d: the dictionary's Beckmann roughness")->capture_default_str();
  command->add_option("--lobe-std", p.lobeStd, "s: standard deviation of each lobe")->capture_default_str();
  // CLI11 would wrap a negative seed around to a large unsigned one, saturate one past 2^64 - 1 and
  // take a sign or spaces: the text must be digits, and within range.
  command->add_option("--seed", p.seed, "Seed of the PCG32 streams, an integer in [0, 2^64); same seed, same bytes")
      ->check([](const std::string& text) {
        if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos) {
          return std::string("must be a non-negative integer (digits only)");
        }
        std::uint64_t value = 0;
        const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
        return error == std::errc::result_out_of_range ? std::string("must be an integer in [0, 2^64)") : std::string();
      })
      ->capture_default_str();
  command->add_option("--placement", options->placement,
                      "Lobe means: 'stratified' (unbiased mean at every level) or 'independent' (the paper's)")
      ->capture_default_str();
  command->add_option("--threads", options->threads, "Worker threads (0: all cores); the output does not depend on it")
      ->check(CLI::Range(0, 4096))
      ->capture_default_str();
  command->add_option("--plot", options->plot, "Draw chosen distributions at several levels to this PNG");
  command->add_option("--plot-distributions", options->plotDistributions, "Distributions to draw")
      ->delimiter(',')
      ->capture_default_str();
  command->add_option("--plot-levels", options->plotLevels, "Levels to draw, one panel each")
      ->delimiter(',')
      ->capture_default_str();
  command->add_flag("--stats", options->stats,
                    "Print per level: integrals, standard deviations, L1 distance of the mean marginal to the limit");
  command->callback([options, command] { runDict(*options, *command); });
}

}  // namespace glint::app
