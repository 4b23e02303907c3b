// The `glint` program as a user meets it: determinism of `glint dict` across runs and thread
// counts, `glint eval` output, and one-line errors with a non-zero exit for every bad input.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "glint/version.h"
#include "test_support.h"

namespace glint {
namespace {

using namespace glint::test;

TEST(GlintCli, MistypedCommandsAndSizesSayWhatIsWrong) {
  const auto folder = temporaryFolder("cli_messages");
  RunResult result = runGlint(folder, "rendr sphere -o x.png");
  expectOneLineError(result, "unknown command 'rendr' (commands: dict, eval, diff, render, view, trace, bench");
  expectOneLineError(result, "did you mean 'render'?");
  expectOneLineError(runGlint(folder, "zzzzzz"), "unknown command 'zzzzzz'");
  // Command-line syntax errors exit with 2 (docs/conventions.md), an unknown command too; an
  // option before any command is named.
  EXPECT_EQ(result.exitCode, 2);
  const RunResult option = runGlint(folder, "--bogus");
  expectOneLineError(option, "unknown option '--bogus': give a command first (commands: dict, eval,");
  EXPECT_EQ(option.exitCode, 2);
  EXPECT_EQ(runGlint(folder, "--help").exitCode, 0);
  const RunResult empty = runGlint(folder, "''");
  expectOneLineError(empty, "unknown command '' (commands: dict,");
  EXPECT_EQ(empty.exitCode, 2);
  // A size that looks right but is out of range says the range, not the form.
  expectOneLineError(runGlint(folder, "render sphere --size 100000x100000 -o x.png"),
                     "--size must be between 1x1 and 8192x8192, got 100000x100000");
  expectOneLineError(runGlint(folder, "render sphere --size 99999999999x2 -o x.png"), "between 1x1 and 8192x8192");
  expectOneLineError(runGlint(folder, "render sphere --size 12 -o x.png"), "--size must look like 512x512");
  EXPECT_FALSE(std::filesystem::exists(folder / "x.png"));
}

// What CLI11 refuses in a command's arguments points at that command's help, not the top level's.
TEST(GlintCli, ArgumentErrorsPointAtTheirCommandsHelp) {
  const auto folder = temporaryFolder("cli_help_pointer");
  expectOneLineError(runGlint(folder, "render --bogus"), "--bogus (see glint render --help)");
  expectOneLineError(runGlint(folder, "trace sphere --spp many"), "(see glint trace --help)");
  expectOneLineError(runGlint(folder, "dict --levels"), "(see glint dict --help)");
  expectOneLineError(runGlint(folder, "--bogus"), "(see glint --help)");
}

// What a command prints on standard output must reach it: with the descriptor closed, the command
// fails in one line (exit status 1) where it used to exit 0 having written nothing. (The trailing
// '#' leaves runGlint's own redirections of stdout out of the shell command.)
TEST(GlintCli, AStandardOutputThatCannotBeWrittenIsAnError) {
  const auto folder = temporaryFolder("cli_closed_stdout");
  const RunResult result = runGlint(folder, "shader-bundle --language glsl 2> stderr.txt 1>&- #");
  expectOneLineError(result, "standard output: cannot write (Bad file descriptor)");
  EXPECT_EQ(result.exitCode, 1);
  const RunResult help = runGlint(folder, "render --help 2> stderr.txt 1>&- #");
  expectOneLineError(help, "standard output: cannot write (Bad file descriptor)");
  EXPECT_EQ(help.exitCode, 1);
}

// A whole number means what it says: CLI11 would read "010" as 8 and "0x10" as 16; every
// whole-number option of every command refuses both, and 0 itself is a number.
TEST(GlintCli, WholeNumbersAreDecimal) {
  const auto folder = temporaryFolder("cli_decimal");
  for (const auto& [arguments, option] : {std::pair<std::string, std::string>{"render sphere --size 8x8 --spp 010 -o x.png", "--spp"},
                                          {"trace sphere --size 8x8 --pattern-seed 0x10 -o x.exr", "--pattern-seed"},
                                          {"dict --seed 010 -o x.gdict", "--seed"},
                                          {"dict --levels 4 --plot x.png --plot-levels 0,03", "--plot-levels"},
                                          {"dict --threads 010 -o x.gdict", "--threads"}}) {  // an option with a check of its own
    const RunResult result = runGlint(folder, arguments);
    expectOneLineError(result, option + ": must be a decimal whole number (no leading 0, no 0x)");
    EXPECT_EQ(result.exitCode, 2) << arguments;
  }
  EXPECT_EQ(runGlint(folder, "dict --levels 2 --distributions 2 --texels 8 --seed 0 -o zero.gdict").exitCode, 0);
  for (const char* file : {"x.png", "x.exr", "x.gdict"}) EXPECT_FALSE(std::filesystem::exists(folder / file)) << file;
}

// An option given an empty value (an unset shell variable in `-o "$OUT"`) is refused, not taken as
// absent: `glint trace -o ''` would otherwise overwrite SCENE.exr and SCENE.png.
TEST(GlintCli, EmptyOptionValuesAreRefused) {
  const auto folder = temporaryFolder("cli_empty_values");
  for (const auto& [arguments, option] : {std::pair<std::string, std::string>{"trace sphere --size 8x8 --spp 1 -o ''", "-o"},
                                          {"shader-bundle --language glsl --output=", "--output"},
                                          {"render sphere --size 8x8 --dict ''", "--dict"}}) {
    const RunResult result = runGlint(folder, arguments);
    expectOneLineError(result, option + " was given an empty value (see glint " + arguments.substr(0, arguments.find(' ')) + " --help)");
    EXPECT_EQ(result.exitCode, 2) << arguments;
  }
  // Not an option given an empty value: an empty argument after a flag, after an option's value
  // that starts with '-', or after `--` is CLI11's to judge (here an unexpected argument).
  for (const char* arguments : {"trace sphere --size 8x8 --direct-only ''", "render sphere --size 8x8 --orbit 2 --orbit-degrees -90 ''",
                                "render sphere --size 8x8 -- ''"}) {
    const RunResult result = runGlint(folder, arguments);
    EXPECT_NE(result.exitCode, 0) << arguments;
    EXPECT_EQ(result.err.find("was given an empty value"), std::string::npos) << arguments << ": " << result.err;
  }
  for (const char* file : {"sphere.exr", "sphere.png"}) EXPECT_FALSE(std::filesystem::exists(folder / file)) << file;
}

// `glint --version` prints the version that project() declares in CMakeLists.txt (given to the
// tests as GLINT_PROJECT_VERSION by tests/CMakeLists.txt), as do the macros of glint/version.h.
TEST(GlintCli, VersionIsTheProjectVersion) {
  const RunResult result = runGlint(temporaryFolder("cli_version"), "--version");
  EXPECT_EQ(result.exitCode, 0) << result.err;
  EXPECT_EQ(result.out, std::string("glint ") + GLINT_PROJECT_VERSION + "\n");
  EXPECT_EQ(std::to_string(GLINT_VERSION_MAJOR) + "." + std::to_string(GLINT_VERSION_MINOR) + "." +
                std::to_string(GLINT_VERSION_PATCH),
            GLINT_PROJECT_VERSION);
}

// Standard output sent to a file, named through a link into /proc (as /dev/stdout is): the bytes
// go to that file and the link stays a link, not replaced by a renamed temporary.
TEST(DictCli, AnOutputLinkedIntoProcIsWrittenInPlace) {
  const auto folder = temporaryFolder("dict_proc_link");
  std::filesystem::create_symlink("/proc/self/fd/1", folder / "out.gdict");
  const RunResult result = runGlint(folder, "dict --levels 2 --distributions 2 --texels 8 -o out.gdict");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_EQ(result.out.size(), 64u + 2u * 2u * 2u * 8u);  // header + 2 levels x 2 distributions x 8 binary16 texels
  EXPECT_EQ(result.out.substr(0, 8), "GLINTDIC");
  EXPECT_TRUE(std::filesystem::is_symlink(folder / "out.gdict"));
}

TEST(DictCli, SameSeedGivesIdenticalBytesOnOneAndTwoThreads) {
  const auto folder = temporaryFolder("dict_determinism");
  ASSERT_EQ(runGlint(folder, "dict --seed 7 --threads 1 -o one.gdict").exitCode, 0);
  ASSERT_EQ(runGlint(folder, "dict --seed 7 --threads 2 -o two.gdict").exitCode, 0);
  ASSERT_EQ(runGlint(folder, "dict --seed 7 -o again.gdict").exitCode, 0);
  ASSERT_EQ(runGlint(folder, "dict --seed 8 -o other.gdict").exitCode, 0);
  const std::string one = slurp(folder / "one.gdict");
  EXPECT_EQ(one.size(), 64u + 393216u);
  EXPECT_TRUE(one == slurp(folder / "two.gdict"));
  EXPECT_TRUE(one == slurp(folder / "again.gdict"));
  EXPECT_FALSE(one == slurp(folder / "other.gdict"));
}

TEST(DictCli, TreeLevelsAreWrittenOnlyWhenAskedAndReadBack) {
  const auto folder = temporaryFolder("dict_tree_levels");
  const RunResult written = runGlint(folder, "dict --tree-levels -o tree.gdict");
  ASSERT_EQ(written.exitCode, 0) << written.err;
  EXPECT_NE(written.err.find("744 KiB: the levels and the tree levels, format version 2"), std::string::npos) << written.err;
  ASSERT_EQ(runGlint(folder, "dict -o plain.gdict").exitCode, 0);
  const std::string tree = slurp(folder / "tree.gdict");
  const std::string plain = slurp(folder / "plain.gdict");
  EXPECT_EQ(tree.size(), 64u + 2u * 31u * 192u * 64u);  // 16 levels, 15 tree levels
  EXPECT_EQ(tree.substr(64, plain.size() - 64), plain.substr(64));  // the levels as version 1 stores them
  // A stored tree level that is not the one level 0 makes (the first tree texel's lowest bit
  // flipped, the checksums remade) is refused in one line naming the file.
  std::string tampered = tree;
  const std::size_t firstTreeTexel = 64 + 2u * 16u * 192u * 64u;
  tampered[firstTreeTexel] = static_cast<char>(tampered[firstTreeTexel] ^ 1);
  auto putU32 = [&](std::size_t at, std::uint32_t value) {
    for (int b = 0; b < 4; ++b) tampered[at + b] = static_cast<char>(value >> (8 * b));
  };
  putU32(56, crc32Ieee(std::string_view(tampered).substr(64)));
  putU32(60, crc32Ieee(std::string_view(tampered).substr(0, 60)));
  std::ofstream(folder / "tampered.gdict", std::ios::binary) << tampered;
  expectOneLineError(runGlint(folder, "dict --from tampered.gdict --stats"),
                     "tampered.gdict: tree level 1, distribution 0 is not the mean its level 0 makes");
  const RunResult converted = runGlint(folder, "dict --from tree.gdict -o again.gdict");
  ASSERT_EQ(converted.exitCode, 0) << converted.err;
  EXPECT_TRUE(slurp(folder / "again.gdict") == plain);
  expectOneLineError(runGlint(folder, "dict --tree-levels --stats"), "--tree-levels needs -o FILE");
}

TEST(DictCli, WritesAPlotAndStatistics) {
  const auto folder = temporaryFolder("dict_plot");
  const RunResult result = runGlint(folder, "dict --levels 8 --plot plot.png --plot-levels 0,3,7 --stats");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  const std::string png = slurp(folder / "plot.png");
  ASSERT_GT(png.size(), 1000u);
  EXPECT_EQ(png.substr(1, 3), "PNG");
  EXPECT_NE(result.out.find("mean-marginal L1"), std::string::npos);
  EXPECT_EQ(std::count(result.out.begin(), result.out.end(), '\n'), 1 + 8);  // header + one line a level
}

TEST(DictCli, BadArgumentsGiveOneLineErrors) {
  const auto folder = temporaryFolder("dict_errors");
  expectOneLineError(runGlint(folder, "dict --levels 30 -o x.gdict"), "levels must be in [1, 16]");
  expectOneLineError(runGlint(folder, "dict --alpha nan -o x.gdict"), "alpha");
  expectOneLineError(runGlint(folder, "dict --placement clumped -o x.gdict"), "lobe placement");
  expectOneLineError(runGlint(folder, "dict"), "nothing to do");
  expectOneLineError(runGlint(folder, "dict --from missing.gdict --stats"), "missing.gdict: cannot open");
  expectOneLineError(runGlint(folder, "dict --from x.gdict --seed 3 --stats"), "cannot be combined with --from");
  expectOneLineError(runGlint(folder, "dict --plot plot.png --plot-levels 16"), "plot level 16 does not exist");
  expectOneLineError(runGlint(folder, "dict -o no/such/folder/x.gdict"), "no/such/folder/x.gdict: cannot create");
  expectOneLineError(runGlint(folder, "dict --no-such-flag"), "no-such-flag");
  expectOneLineError(runGlint(folder, "dict -o x.gdict --plot-levels 0,3"), "glint dict: --plot-levels needs --plot PNG");
  // The dictionary and its plot are one output: a plot that cannot be written leaves no dictionary.
  std::ofstream(folder / "afile") << "a file, not a folder";
  expectOneLineError(runGlint(folder, "dict --levels 4 -o x.gdict --plot afile/plot.png --plot-levels 0,3"), "afile/plot.png: cannot create");
  EXPECT_FALSE(std::filesystem::exists(folder / "x.gdict"));
  EXPECT_FALSE(std::filesystem::exists(folder / "plot.png"));
}

TEST(DictCli, NegativeSeedsAndThreadCountsAndHugeFolderNumbersAreRefused) {
  const auto folder = temporaryFolder("dict_numbers");
  expectOneLineError(runGlint(folder, "dict --seed -1 -o d.gdict"), "must be a non-negative integer");
  // One past the largest seed, and far past it: refused, not saturated to 2^64 - 1; nor is a sign
  // or a space taken (CLI11 would read "+18446744073709551616" as 2^64 - 1 and " -1" as -1).
  for (const char* seed : {"18446744073709551616", "99999999999999999999999"}) {
    const RunResult result = runGlint(folder, std::string("dict --seed ") + seed + " -o d.gdict");
    expectOneLineError(result, "must be an integer in [0, 2^64)");
    EXPECT_EQ(result.exitCode, 2) << seed;
  }
  for (const char* seed : {"+18446744073709551616", "' -1'", "+5"}) {
    const RunResult result = runGlint(folder, std::string("dict --seed ") + seed + " -o d.gdict");
    expectOneLineError(result, "must be a non-negative integer (digits only)");
    EXPECT_EQ(result.exitCode, 2) << seed;
  }
  ASSERT_EQ(runGlint(folder, "dict --levels 2 --distributions 2 --texels 8 --seed 18446744073709551615 -o largest.gdict").exitCode, 0);
  std::filesystem::remove(folder / "largest.gdict");
  expectOneLineError(runGlint(folder, "dict --threads -3 -o d.gdict"), "--threads");
  std::filesystem::create_directories(folder / "dict_99999999999_192_64_0p5_0p02");
  expectOneLineError(runGlint(folder, "dict --from dict_99999999999_192_64_0p5_0p02 -o d.gdict"),
                     "dict_99999999999_192_64_0p5_0p02: dictionary parameter levels must be in");
  std::filesystem::create_directories(folder / "dict_16_192_64_0p5_99999999999p0");
  expectOneLineError(runGlint(folder, "dict --from dict_16_192_64_0p5_99999999999p0 -o d.gdict"),
                     "not an EXR dictionary folder");
  EXPECT_FALSE(std::filesystem::exists(folder / "d.gdict"));
}

TEST(DictCli, DamagedDictionaryFilesGiveOneLineErrors) {
  const auto folder = temporaryFolder("dict_damaged");
  ASSERT_EQ(runGlint(folder, "dict -o good.gdict").exitCode, 0);
  const std::string good = slurp(folder / "good.gdict");
  auto write = [&](const std::string& name, const std::string& bytes) { std::ofstream(folder / name, std::ios::binary) << bytes; };
  write("truncated.gdict", good.substr(0, good.size() / 2));
  std::string corrupt = good;
  corrupt[5000] = static_cast<char>(corrupt[5000] ^ 0x40);
  write("corrupt.gdict", corrupt);
  std::string magic = good;
  magic[0] = 'X';
  write("magic.gdict", magic);
  std::string version = good;
  version[8] = 9;
  write("version.gdict", version);
  write("text.gdict", "hello\n");
  expectOneLineError(runGlint(folder, "eval --dict truncated.gdict", "{}\n"), "truncated.gdict: truncated");
  expectOneLineError(runGlint(folder, "eval --dict corrupt.gdict", "{}\n"), "corrupt.gdict: corrupt payload");
  expectOneLineError(runGlint(folder, "eval --dict magic.gdict", "{}\n"), "magic.gdict: not a glint dictionary");
  expectOneLineError(runGlint(folder, "eval --dict version.gdict", "{}\n"), "unsupported dictionary format version 9");
  expectOneLineError(runGlint(folder, "dict --from text.gdict --stats"), "text.gdict: truncated");
  expectOneLineError(runGlint(folder, "eval --dict .", "{}\n"), "not an EXR dictionary folder");
}

TEST(EvalCli, AnswersOneJsonLinePerInputLine) {
  const auto folder = temporaryFolder("eval");
  ASSERT_EQ(runGlint(folder, "dict -o d.gdict").exitCode, 0);
  const std::string input =
      R"({"uv":[0.3,0.7],"duvdx":[0.001,0],"duvdy":[0,0.001],"wo":[0.2,0.1,1],"wi":[-0.1,0,1],"alpha":[0.4,0.3],"log_density":22,"relative_area":1})"
      "\n\n"
      R"({"wo":[0.2,0.1,1],"wi":[-0.1,0,1],"alpha":[0.4,0.3],"brdf":"cook-torrance"})"
      "\n"
      R"({"wo":[0.2,0.1,1],"wi":[-0.1,0,1],"alpha":[0.4,0.3],"log_density":80})"
      "\n"
      R"({"wo":[0,0,1],"wi":[0,0,-1]})"
      "\n";
  const RunResult result = runGlint(folder, "eval --dict d.gdict", input);
  ASSERT_EQ(result.exitCode, 0) << result.err;
  std::istringstream lines(result.out);
  std::vector<std::string> outputs;
  for (std::string line; std::getline(lines, line);) outputs.push_back(line);
  ASSERT_EQ(outputs.size(), 4u) << result.out;  // the blank line is skipped
  for (const std::string& line : outputs) {
    EXPECT_NE(line.find("\"f\":"), std::string::npos);
    EXPECT_NE(line.find("\"D\":"), std::string::npos);
    EXPECT_NE(line.find("\"P22\":"), std::string::npos);
  }
  // Cook-Torrance and the glint BRDF at very high density print the same numbers.
  EXPECT_EQ(outputs[1], outputs[2]);
  EXPECT_NE(outputs[0], outputs[1]);
  EXPECT_EQ(outputs[3].find("\"f\":0.0"), outputs[3].find("\"f\":")) << outputs[3];  // wi below the surface
}

TEST(EvalCli, PatternSeedsAreExactToThirtyTwoBits) {
  // Seeds above 2^24 went through a float: 4294967295 became 0 (2^32 wrapped), 16777217 became
  // 16777216. Each must give the pattern of its own seed, which differs from its neighbours'.
  const auto folder = temporaryFolder("eval_seeds");
  auto p22 = [&](const std::string& seed) {
    const RunResult result = runGlint(folder, "eval", "{\"uv\":[0.3,0.7],\"wo\":[0.1,0.2,1],\"wi\":[-0.1,0,1],"
                                                      "\"log_density\":14,\"pattern_seed\":" + seed + "}\n");
    EXPECT_EQ(result.exitCode, 0) << result.err;
    return result.out;
  };
  EXPECT_NE(p22("4294967295"), p22("0"));
  EXPECT_NE(p22("16777217"), p22("16777216"));
  expectOneLineError(runGlint(folder, "eval", "{\"pattern_seed\":4294967296}\n"), "pattern_seed");
}

TEST(EvalCli, DirectionsAtAnyScaleAreTheirDirection) {
  // A direction is normalised on input: [1e30, 0, 1e30] squared overflowed a float (a zero
  // direction), [1e-30, 0, 1e-30] underflowed (refused as zero). Each must answer as the same
  // direction at unit scale does, exactly.
  const auto folder = temporaryFolder("eval_scales");
  auto answer = [&](const std::string& scale) {
    const std::string line = "{\"uv\":[0.3,0.7],\"log_density\":14,\"wo\":[" + scale + ",0," + scale + "],\"wi\":[0,0," +
                             scale + "]}\n";
    const RunResult result = runGlint(folder, "eval", line);
    EXPECT_EQ(result.exitCode, 0) << scale << ": " << result.err;
    return result.out;
  };
  const std::string unit = answer("1");
  EXPECT_NE(unit.find("\"f\":"), std::string::npos) << unit;
  for (const char* scale : {"1e30", "1e-30", "1e-7", "1e300", "1e-300"}) EXPECT_EQ(answer(scale), unit) << scale;
}

// A white furnace through `glint eval` alone, as a user outside the project would check it: the
// albedo of f (F = 1) for wo at 60 degrees, by a 64 x 64 midpoint rule in (cos theta, phi), for
// GGX with Smith masking at alpha 1, where single scattering loses about half of the light.
// With "multiple_scattering": true the compensation lobe brings it back to 1 within 1.5% (the
// albedo tables' interpolation and this quadrature); without it the albedo stays below 0.9. The
// glint BRDF at log density 80 is its smooth limit, and must answer alike.
TEST(EvalCli, MultipleScatteringFieldMakesTheWhiteFurnaceOne) {
  const auto folder = temporaryFolder("eval_furnace");
  constexpr int kSteps = 64;
  std::string input;
  for (int i = 0; i < kSteps; ++i) {
    const double mu = (i + 0.5) / kSteps;
    const double sine = std::sqrt(1.0 - mu * mu);
    for (int j = 0; j < kSteps; ++j) {
      const double phi = 2.0 * 3.14159265358979 * (j + 0.5) / kSteps;
      char line[160];
      std::snprintf(line, sizeof line, "\"wi\":[%.9f,%.9f,%.9f]", sine * std::cos(phi), sine * std::sin(phi), mu);
      input += std::string("{") + line + "}\n";
    }
  }
  for (const char* brdf : {"cook-torrance", "glint"}) {
    double albedo[2] = {};  // [with the compensation]
    for (const bool compensated : {false, true}) {
      std::string lines;
      const std::string common = std::string("{\"brdf\":\"") + brdf +
                                 "\",\"ndf\":\"ggx\",\"masking\":\"smith\",\"alpha\":[1,1],\"log_density\":80,"
                                 "\"wo\":[0.8660254,0,0.5],\"multiple_scattering\":" + (compensated ? "true," : "false,");
      std::istringstream each(input);
      for (std::string line; std::getline(each, line);) lines += common + line.substr(1) + "\n";
      const RunResult result = runGlint(folder, "eval", lines);
      ASSERT_EQ(result.exitCode, 0) << result.err;
      std::istringstream outputs(result.out);
      int count = 0;
      int i = 0;
      for (std::string line; std::getline(outputs, line); ++count, ++i) {
        const double f = nlohmann::json::parse(line).at("f").get<double>();
        const double mu = ((i / kSteps) + 0.5) / kSteps;
        albedo[compensated] += f * mu * (1.0 / kSteps) * (2.0 * 3.14159265358979 / kSteps);
      }
      ASSERT_EQ(count, kSteps * kSteps);
    }
    std::printf("%s, GGX and Smith at alpha 1, wo at 60 degrees: albedo %.4f without the compensation, %.4f with\n",
                brdf, albedo[0], albedo[1]);
    EXPECT_NEAR(albedo[1], 1.0, 0.015) << brdf;
    EXPECT_LT(albedo[0], 0.9) << brdf;
  }
}

TEST(EvalCli, BadLinesGiveOneLineErrorsWithTheLineNumber) {
  const auto folder = temporaryFolder("eval_errors");
  ASSERT_EQ(runGlint(folder, "dict -o d.gdict").exitCode, 0);
  const std::string ok = "{}\n";
  auto eval = [&](const std::string& line) { return runGlint(folder, "eval --dict d.gdict", ok + line + "\n"); };
  expectOneLineError(eval(R"({"uv":[0.5,)"), "stdin line 2: malformed JSON");
  expectOneLineError(eval(R"({"alpha":[NaN,0.5]})"), "stdin line 2: malformed JSON");
  expectOneLineError(eval(R"({"alpha":[1e999,0.5]})"), "stdin line 2:");
  expectOneLineError(eval(R"({"alpha":[0.5,3]})"), "alpha_y must be in [0.005, 2], got 3");
  expectOneLineError(eval(R"({"relative_area":0})"), "relative_area must be in (0, 1]");
  expectOneLineError(eval(R"({"log_density":-5})"), "log_density must be in [0, 100]");
  expectOneLineError(eval(R"({"wo":[0,0,0]})"), "'wo' must be a non-zero direction");
  expectOneLineError(eval(R"({"uv":[0.5]})"), "'uv' must be an array of 2 numbers");
  expectOneLineError(eval(R"({"uv":"middle"})"), "'uv' must be an array of 2 numbers");
  expectOneLineError(eval(R"({"brdf":"phong"})"), "'brdf' must be");
  expectOneLineError(eval(R"({"alpah":[0.5,0.5]})"), "unknown field 'alpah'");
  expectOneLineError(eval(R"([1,2,3])"), "expected a JSON object");
  expectOneLineError(eval(R"({"pattern_seed":-1})"), "pattern_seed");
  expectOneLineError(eval(R"({"multiple_scattering":1})"), "field 'multiple_scattering' must be true or false");
  expectOneLineError(runGlint(folder, "eval --dict missing.gdict", ok), "missing.gdict: cannot open");
}

}  // namespace
}  // namespace glint
