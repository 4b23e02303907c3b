// `glint`: one command, git-style subcommands (docs/cli.md).
#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <exception>
#include <iostream>
#include <string>
#include <vector>

#include <fcntl.h>
#include <unistd.h>

#include "commands.h"
#include "glint/error.h"
#include "glint/version.h"

namespace {

// Levenshtein distance, for the nearest command name to a mistyped one.
std::size_t editDistance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

// The command called `name`, or null.
const CLI::App* commandNamed(const CLI::App& app, const std::string& name) {
  for (const CLI::App* command : app.get_subcommands({})) {
    if (command->get_name() == name) return command;
  }
  return nullptr;
}

// A first argument that is not a command, nor glint's own --help or --version: the one line that
// names it, the commands and the nearest one (CLI11 would say only that a subcommand is required),
// or empty when it is one. It is a command-line syntax error (exit status 2).
std::string unknownCommand(const CLI::App& app, int argc, char** argv) {
  if (argc < 2) return {};
  const std::string given = argv[1];
  std::string names;
  for (const CLI::App* command : app.get_subcommands({})) names += (names.empty() ? "" : ", ") + command->get_name();
  if (!given.empty() && given[0] == '-') {
    if (given == "-h" || given == "--help" || given == "--version") return {};
    return "unknown option '" + given + "': give a command first (commands: " + names + ")";
  }
  if (commandNamed(app, given) != nullptr) return {};
  std::string nearest;
  std::size_t nearestDistance = 3;  // suggest only names at most two edits away
  for (const CLI::App* command : app.get_subcommands({})) {
    const std::size_t distance = editDistance(given, command->get_name());
    if (distance < nearestDistance) {
      nearestDistance = distance;
      nearest = command->get_name();
    }
  }
  return "unknown command '" + given + "' (commands: " + names + ")" +
         (nearest.empty() ? "" : "; did you mean '" + nearest + "'?");
}

// An option of the command given an empty value (`-o ''`, `--dict=`, an unset shell variable in
// `-o "$OUT"`), which the commands would take as not given and fall back to their default (`glint
// trace -o ''` would overwrite SCENE.exr): the one line that names it, or empty when there is none.
// Only the command's own options that take a value count (not flags, negative numbers or values);
// `--` ends the options. A command-line syntax error (exit status 2).
std::string emptyOptionValue(const CLI::App& app, int argc, char** argv) {
  if (argc < 2) return {};
  const CLI::App* command = commandNamed(app, argv[1]);
  if (command == nullptr) return {};
  for (int i = 2; i < argc; ++i) {
    const std::string argument = argv[i];
    if (argument == "--") break;
    if (argument.size() < 2 || argument[0] != '-') continue;
    const std::size_t equals = argument.find('=');
    const std::string name = argument.substr(0, equals);
    const CLI::Option* option = command->get_option_no_throw(name);
    if (option == nullptr || option->get_items_expected_min() == 0) continue;  // not an option, or a flag
    if (equals != std::string::npos) {
      if (equals + 1 == argument.size()) return name + " was given an empty value";
      continue;
    }
    if (i + 1 < argc && argv[i + 1][0] == '\0') return name + " was given an empty value";
    ++i;  // its value, which may start with '-' (--look-at -1,0,0)
  }
  return {};
}

// What the command printed on standard output reached it (a full disk, a closed descriptor): a
// failed write is an error, not a cut-short file and exit status 0. Empty when it did.
std::string standardOutputProblem() {
  std::cout.flush();
  errno = 0;
  const bool failed = std::fflush(stdout) != 0 || std::ferror(stdout) != 0 || std::cout.fail();
  if (!failed) return {};
  // A write that failed while the command ran left no errno to read here; a closed descriptor
  // still says so (fcntl sets EBADF).
  if (errno == 0) ::fcntl(STDOUT_FILENO, F_GETFD);
  return std::string("standard output: cannot write (") + (errno != 0 ? std::strerror(errno) : "a write failed") + ")";
}

// CLI11 reads whole numbers with strtol's base 0, "010" as 8 and "0x10" as 16: every whole-number
// option of every command refuses a leading 0 and a base prefix, so that a number means what it
// says.
void requireDecimalWholeNumbers(CLI::App& app) {
  const CLI::Validator decimal(
      [](std::string& text) {
        const std::size_t sign = !text.empty() && (text[0] == '-' || text[0] == '+') ? 1 : 0;
        if (text.size() > sign + 1 && text[sign] == '0') {
          return "must be a decimal whole number (no leading 0, no 0x), got '" + text + "'";
        }
        return std::string();
      },
      "");
  for (CLI::App* command : app.get_subcommands({})) {
    for (CLI::Option* option : command->get_options({})) {
      // CLI11 appends an option's checks to its type name ("INT:INT in [0 - 4096]").
      const std::string type = option->get_type_name();
      const auto is = [&](const std::string& name) { return type == name || type.rfind(name + ":", 0) == 0; };
      if (is("INT") || is("UINT")) option->check(decimal);
    }
  }
}

// The command whose arguments CLI11 refused, "glint" or "glint render", so that its error points at
// that command's own --help (CLI11's message points at the top-level one).
std::string refusingCommand(const CLI::App& app) {
  std::string command = app.get_name();
  for (const CLI::App* parsed = &app; !parsed->get_subcommands().empty();) {
    parsed = parsed->get_subcommands().front();
    command += " " + parsed->get_name();
  }
  return command;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"glint: procedural physically based glints (Chermain et al. 2020)", "glint"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "glint " GLINT_VERSION_STRING);
  glint::app::registerDictCommand(app);
  glint::app::registerEvalCommand(app);
  glint::app::registerDiffCommand(app);
  glint::app::registerRenderCommand(app);
  glint::app::registerViewCommand(app);
  glint::app::registerTraceCommand(app);
  glint::app::registerBenchCommand(app);
  glint::app::registerExportCommand(app);
  glint::app::registerHdriCommand(app);
  glint::app::registerEnvRegionsCommand(app);
  glint::app::registerAaErrorCommand(app);
  glint::app::registerLodConsistencyCommand(app);
  glint::app::registerAlbedoTablesCommand(app);
  glint::app::registerShaderBundleCommand(app);
  glint::app::registerExtensionSchemaCommand(app);
  requireDecimalWholeNumbers(app);
  if (const std::string problem = unknownCommand(app, argc, argv); !problem.empty()) {
    std::fprintf(stderr, "glint: error: %s (see glint --help)\n", problem.c_str());
    return 2;
  }
  if (const std::string problem = emptyOptionValue(app, argc, argv); !problem.empty()) {
    std::fprintf(stderr, "glint: error: %s (see glint %s --help)\n", problem.c_str(), argv[1]);
    return 2;
  }
  // What was printed reached standard output, or the run fails whatever it did (--help too).
  const auto finished = [](int status) {
    if (const std::string problem = standardOutputProblem(); !problem.empty()) {
      std::fprintf(stderr, "glint: error: %s\n", problem.c_str());
      return status == 0 ? 1 : status;
    }
    return status;
  };
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return finished(app.exit(e));
  } catch (const CLI::CallForAllHelp& e) {
    return finished(app.exit(e));
  } catch (const CLI::CallForVersion& e) {
    return finished(app.exit(e));
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "glint: error: %s (see %s --help)\n", e.what(), refusingCommand(app).c_str());
    return 2;
  } catch (const glint::Error& e) {
    std::fprintf(stderr, "glint: error: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "glint: internal error: %s\n", e.what());
    return 3;
  }
  return finished(0);
}
