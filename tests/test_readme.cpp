// The README's examples as a user types them: every command of its ```sh blocks runs, from the
// root of a clone alone (no ../shared), with exit status 0. They run in a fresh folder whose
// build/glint is this build's program, so that the files they write land there.
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "test_support.h"

namespace glint::test {
namespace {

// The lines of the README's fenced blocks whose info string is "sh", blank lines and comments left out.
std::vector<std::string> readmeShellCommands(const std::string& readme) {
  std::vector<std::string> commands;
  std::istringstream lines(readme);
  std::string line;
  bool inShell = false;
  bool inOther = false;
  while (std::getline(lines, line)) {
    if (line.rfind("```", 0) == 0) {
      if (inShell || inOther) {
        inShell = inOther = false;
      } else {
        inShell = line == "```sh";
        inOther = !inShell;
      }
      continue;
    }
    if (inShell && !line.empty() && line[0] != '#') commands.push_back(line);
  }
  return commands;
}

TEST(ReadmeCli, FindsTheShellBlocksOnly) {
  const std::string text = "intro\n```sh\nbuild/glint render sphere\n\n# a comment\nbuild/glint dict\n```\n"
                           "```\nscripts/test\n```\n```json\n{}\n```\n```sh\necho\n```\n";
  EXPECT_EQ(readmeShellCommands(text), (std::vector<std::string>{"build/glint render sphere", "build/glint dict", "echo"}));
}

TEST(ReadmeCli, EveryExampleRuns) {
  const std::vector<std::string> commands = readmeShellCommands(slurp(std::filesystem::path(GLINT_SOURCE_DIR) / "README.md"));
  ASSERT_GE(commands.size(), 5u) << "the README's examples block is missing";
  const auto folder = temporaryFolder("readme");
  std::filesystem::create_directory(folder / "build");
  std::filesystem::create_symlink(GLINT_EXECUTABLE, folder / "build" / "glint");
  for (const std::string& command : commands) {
    SCOPED_TRACE(command);
    const std::string shell = "cd '" + folder.string() + "' && (" + command + ") > out.txt 2> err.txt";
    const int status = std::system(shell.c_str());
    EXPECT_EQ(status, 0) << slurp(folder / "err.txt");
  }
  for (const char* written : {"sphere.png", "showroom.glb", "showroom.png", "glitter.png", "difference.png", "traced.exr"}) {
    EXPECT_TRUE(std::filesystem::exists(folder / written)) << written;
  }
}

}  // namespace
}  // namespace glint::test
