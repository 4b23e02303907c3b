// `glint`: one command, git-style subcommands (docs/cli.md).
#include <cstdio>
#include <exception>

#include "commands.h"
#include "error.h"

int main(int argc, char** argv) {
  CLI::App app{"glint: procedural physically based glints (Chermain et al. 2020)", "glint"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "glint 0.1.0");
  glint::app::registerDictCommand(app);
  glint::app::registerEvalCommand(app);
  glint::app::registerDiffCommand(app);
  glint::app::registerRenderCommand(app);
  glint::app::registerViewCommand(app);
  glint::app::registerTraceCommand(app);
  glint::app::registerBenchCommand(app);
  glint::app::registerExportCommand(app);
  glint::app::registerAaErrorCommand(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "glint: error: %s (see glint --help)\n", e.what());
    return 2;
  } catch (const glint::Error& e) {
    std::fprintf(stderr, "glint: error: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "glint: internal error: %s\n", e.what());
    return 3;
  }
  return 0;
}
