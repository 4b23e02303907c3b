// The user documentation checked against the program. docs/cli.md in step with it: every option that `glint COMMAND --help` lists is in that
// command's section of docs/cli.md, every option the section's tables name exists, and where an
// option takes one of the renderer's names (the BRDF models, the anti-aliasing modes) the section's
// row for it lists all of them.
#include <filesystem>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "gl/renderer.h"
#include "test_support.h"

namespace glint::test {
namespace {

const std::vector<std::string> kCommands = {"dict", "eval", "diff", "render", "export", "view", "trace", "bench", "aa-error", "lod-consistency", "hdri", "env-regions", "shader-bundle", "albedo-tables", "extension-schema"};

// The long options of a CLI11 help text: the first column of its option lines, --help left out.
std::set<std::string> helpOptions(const std::string& help) {
  std::set<std::string> options;
  const std::regex option(R"(^\s+(?:-\w,)?(--[a-z][a-z0-9-]*))");
  std::istringstream lines(help);
  std::string line;
  while (std::getline(lines, line)) {
    std::smatch match;
    if (std::regex_search(line, match, option) && match[1] != "--help") options.insert(match[1]);
  }
  return options;
}

// The section "## glint COMMAND" of docs/cli.md, up to the next section.
std::string cliSection(const std::string& document, const std::string& command) {
  const std::string heading = "## glint " + command + "\n";
  const std::size_t start = document.find(heading);
  if (start == std::string::npos) return "";
  const std::size_t end = document.find("\n## ", start + heading.size());
  return document.substr(start, end == std::string::npos ? std::string::npos : end - start);
}

// The rows of the section's tables (lines starting with '|').
std::vector<std::string> tableRows(const std::string& section) {
  std::vector<std::string> rows;
  std::istringstream lines(section);
  std::string line;
  while (std::getline(lines, line)) {
    if (line.rfind('|', 0) == 0) rows.push_back(line);
  }
  return rows;
}

std::set<std::string> documentedOptions(const std::string& section) {
  std::set<std::string> options;
  const std::regex option(R"((--[a-z][a-z0-9-]*))");
  for (const std::string& row : tableRows(section)) {
    const std::string firstCell = row.substr(0, row.find('|', 1));
    for (std::sregex_iterator it(firstCell.begin(), firstCell.end(), option), end; it != end; ++it) {
      options.insert((*it)[1]);
    }
  }
  return options;
}

// The table row that documents `option` (its first cell names it).
std::string rowOf(const std::string& section, const std::string& option) {
  for (const std::string& row : tableRows(section)) {
    const std::string firstCell = row.substr(0, row.find('|', 1));
    if (std::regex_search(firstCell, std::regex("`" + option + "[` ]|, " + option + "[` ]"))) return row;
  }
  return "";
}

std::string document(const std::string& name) { return slurp(std::filesystem::path(GLINT_SOURCE_DIR) / "docs" / name); }

std::string cliDocument() { return document("cli.md"); }

// Where a command's options are documented: its section of docs/cli.md, and for the two commands
// whose section sends the reader on, the page it names.
std::string optionDocumentation(const std::string& cliMd, const std::string& command) {
  std::string text = cliSection(cliMd, command);
  if (command == "dict") text += document("dictionary.md");
  if (command == "trace") text += document("trace.md");
  return text;
}

TEST(DocsCli, FindsTheOptionsOfAHelpTextAndASection) {
  const std::string help = "Usage: glint x\n\nOptions:\n  -h,--help   Print\n  -o,--output TEXT   Output\n"
                           "  --size TEXT=512x512   Size, as --size 1x1\n";
  EXPECT_EQ(helpOptions(help), (std::set<std::string>{"--output", "--size"}));
  const std::string document = "# t\n## glint x\n| option | meaning |\n|---|---|\n| `-o, --output` | the file, "
                               "see `--spp` |\n| `--alpha A[,B]`, `--rho R` | |\n## glint y\n| `--other` | |\n";
  EXPECT_EQ(documentedOptions(cliSection(document, "x")), (std::set<std::string>{"--output", "--alpha", "--rho"}));
  EXPECT_NE(rowOf(cliSection(document, "x"), "--rho"), "");
  EXPECT_EQ(rowOf(cliSection(document, "x"), "--other"), "");
}

TEST(DocsCli, EveryCommandsOptionsAreDocumentedAndNoOthers) {
  const std::string cliMd = cliDocument();
  const auto folder = temporaryFolder("cli-docs");
  for (const std::string& command : kCommands) {
    SCOPED_TRACE(command);
    const RunResult result = runGlint(folder, command + " --help");
    ASSERT_EQ(result.exitCode, 0) << result.err;
    ASSERT_NE(cliSection(cliMd, command), "") << "docs/cli.md has no section '## glint " << command << "'";
    const std::string section = optionDocumentation(cliMd, command);
    const std::set<std::string> inHelp = helpOptions(result.out);
    const std::set<std::string> inDocs = documentedOptions(section);
    for (const std::string& option : inHelp) {
      EXPECT_TRUE(inDocs.count(option)) << "glint " << command << " " << option << " is not in docs/cli.md's table";
    }
    for (const std::string& option : inDocs) {
      EXPECT_TRUE(inHelp.count(option)) << "docs/cli.md documents glint " << command << " " << option
                                        << ", which the program does not have";
    }
  }
}

TEST(DocsCli, NamedValuesAreListedInFull) {
  const std::string cliMd = cliDocument();
  const auto expectRowLists = [&](const std::string& command, const std::string& option,
                                  const std::vector<std::string>& names) {
    const std::string row = rowOf(cliSection(cliMd, command), option);
    ASSERT_NE(row, "") << "glint " << command << " " << option;
    for (const std::string& name : names) {
      EXPECT_NE(row.find("`" + name + "`"), std::string::npos)
          << "docs/cli.md: glint " << command << " " << option << " does not list `" << name << "`";
    }
  };
  std::vector<std::string> brdfs;
  for (const SpecularModel model : allSpecularModels()) brdfs.push_back(toString(model));
  std::vector<std::string> modes;
  for (const gl::AntiAliasing mode : gl::allAntiAliasingModes()) modes.push_back(gl::toString(mode));
  expectRowLists("render", "--brdf", brdfs);
  for (const std::string command : {"render", "view", "bench"}) expectRowLists(command, "--aa", modes);
}

// The README and docs/ speak to users about the program: not of how its work was organised
// (issues, sessions, machines lent) nor of files that are not in the repository.
TEST(DocsCli, SpeakOfTheProgramOnly) {
  const std::regex forbidden(R"(\b(issues?|sessions?|lent|model\.md)\b)", std::regex::icase);
  std::vector<std::filesystem::path> pages = {std::filesystem::path(GLINT_SOURCE_DIR) / "README.md"};
  for (const auto& entry : std::filesystem::directory_iterator(std::filesystem::path(GLINT_SOURCE_DIR) / "docs")) {
    if (entry.path().extension() == ".md") pages.push_back(entry.path());
  }
  for (const auto& page : pages) {
    std::istringstream lines(slurp(page));
    std::string line;
    for (int number = 1; std::getline(lines, line); ++number) {
      std::smatch match;
      EXPECT_FALSE(std::regex_search(line, match, forbidden))
          << page.filename().string() << ":" << number << ": '" << match.str() << "' in: " << line;
    }
  }
}

}  // namespace
}  // namespace glint::test
