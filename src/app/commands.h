// The subcommands of `glint`. Each registers its options and a callback; callbacks report user
// errors by throwing glint::Error, which main prints as one line.
#pragma once

#include <CLI/CLI.hpp>

namespace glint::app {

void registerDictCommand(CLI::App& app);
void registerEvalCommand(CLI::App& app);
void registerDiffCommand(CLI::App& app);
void registerRenderCommand(CLI::App& app);
void registerViewCommand(CLI::App& app);
void registerTraceCommand(CLI::App& app);
void registerBenchCommand(CLI::App& app);
void registerExportCommand(CLI::App& app);
void registerAaErrorCommand(CLI::App& app);
void registerLodConsistencyCommand(CLI::App& app);
void registerAlbedoTablesCommand(CLI::App& app);
void registerHdriCommand(CLI::App& app);
void registerEnvRegionsCommand(CLI::App& app);
void registerShaderBundleCommand(CLI::App& app);
void registerExtensionSchemaCommand(CLI::App& app);

}  // namespace glint::app
